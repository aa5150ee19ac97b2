#!/usr/bin/env bash
# Installs the Debian 12 packages loom needs to build, test and run, and only those that
# are missing. Does nothing (and needs no root) when everything is present.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config
  # shader toolchain: glslang (GLSL -> SPIR-V) and SPIRV-Cross (SPIR-V -> GL GLSL, reflection)
  glslang-dev spirv-tools libspirv-cross-c-shared-dev
  # OpenGL: EGL (headless), libepoxy (function loading), GLFW (windows)
  libegl-dev libgl-dev libepoxy-dev libglfw3-dev
  # Vulkan: loader, headers, validation layer
  libvulkan-dev vulkan-validationlayers
  # a virtual X server for the windowed (swapchain) tests
  xvfb xauth
  # Mesa software drivers: llvmpipe (GL) and lavapipe (Vulkan)
  libgl1-mesa-dri libegl-mesa0 mesa-vulkan-drivers
  # maths, scenes, images, JSON
  libglm-dev libtinygltf-dev libstb-dev nlohmann-json3-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # Graphviz renders the plan DOT pictures (make demo; the DOT export tests)
  graphviz
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
if [[ $(id -u) -eq 0 ]]; then
  sudo=()
elif command -v sudo >/dev/null 2>&1; then
  sudo=(sudo)
else
  echo "install-deps: missing packages (${missing[*]}) and neither root nor sudo is available" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -q
"${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
