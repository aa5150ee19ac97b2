#!/usr/bin/env bash
# The README's main job: renders the flagship sample headless on every compiled-in backend and
# writes its pictures under OUT. Usage: scripts/demo.sh BUILD_DIR OUT_DIR
set -euo pipefail
build=${1:?build directory}
out=${2:?output directory}
mkdir -p "$out"

backends=()
grep -q '^LOOM_WITH_GL:BOOL=ON' "$build/CMakeCache.txt" && backends+=(gl)
grep -q '^LOOM_WITH_VULKAN:BOOL=ON' "$build/CMakeCache.txt" && backends+=(vulkan)

if [[ -x "$build/samples/deferred/loom-deferred" ]]; then
  for b in "${backends[@]}"; do
    "$build/samples/deferred/loom-deferred" --backend "$b" --out "$out/deferred-$b"
  done
else
  # Until the deferred sample lands (issue 5), the triangle sample is the main job.
  for b in "${backends[@]}"; do
    "$build/samples/triangle/loom-triangle" --backend "$b" --out "$out/triangle-$b.png"
  done
fi
echo "demo: pictures written under $out/"
