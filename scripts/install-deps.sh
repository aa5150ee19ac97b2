#!/usr/bin/env bash
# Installs the Debian 12 packages loom needs to build, test and run, and only those that
# are missing. Does nothing (and needs no root) when everything is present.
#
#   scripts/install-deps.sh           install what is missing
#   scripts/install-deps.sh --list    print every package with "installed" or "missing"; install nothing
#   scripts/install-deps.sh --fuzz    also the fuzzing toolchain (clang with libFuzzer; make fuzz)
#   scripts/install-deps.sh --bench   also valgrind and Python (make draw-cost)
#
# Packages are installed with --no-install-recommends, so every package whose files loom's
# build touches must be named here, even when another package's config file refers to it.
set -euo pipefail

mode=install
with_fuzz=0
with_bench=0
for arg in "$@"; do
  case $arg in
    --list) mode=list ;;
    --fuzz) with_fuzz=1 ;;
    --bench) with_bench=1 ;;
    *) echo "install-deps: unknown option '$arg' (expected --list, --fuzz or --bench)" >&2; exit 2 ;;
  esac
done

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config
  # shader toolchain: glslang (GLSL -> SPIR-V) and SPIRV-Cross (SPIR-V -> GL GLSL, reflection)
  glslang-dev spirv-tools libspirv-cross-c-shared-dev
  # glslang-dev's CMake package (glslang-targets-none.cmake) imports /usr/bin/glslangValidator
  # and find_package(glslang) fails when that file is missing; it ships in glslang-tools, which
  # glslang-dev does not depend on. Without it a fresh machine stops at CMake configure.
  glslang-tools
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
  # Dear ImGui: the frame overlay of the windowed samples (samples/overlay), drawn through loom's RHI
  libimgui-dev
  # zlib: loom-inspect embeds its input in the page compressed (samples/inspect)
  zlib1g-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # Graphviz renders the plan DOT pictures (make demo; the DOT export tests)
  graphviz
  # headless Chromium opens the inspector's pages in its tests (tests/inspect, docs/inspector.md)
  chromium
)

# make fuzz: libFuzzer and the sanitizer runtimes come with Debian 12's clang 14.
(( with_fuzz )) && packages+=(clang-14 libclang-rt-14-dev)
# make draw-cost: callgrind counts the instructions, a Python script splits them by object.
(( with_bench )) && packages+=(valgrind python3)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  if [[ "$status" == "install ok installed" ]]; then
    [[ $mode == list ]] && printf '  %-32s installed\n' "$p"
  else
    missing+=("$p")
    [[ $mode == list ]] && printf '  %-32s missing\n' "$p"
  fi
done

if [[ $mode == list ]]; then
  echo "install-deps: ${#packages[@]} packages, ${#missing[@]} missing${missing:+: ${missing[*]}}"
  exit 0
fi

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
