#!/usr/bin/env bash
# The README's main job: renders the flagship sample (samples/deferred, the paper's Figure 2
# pipeline) and the engine frame (samples/engine: prepass, hierarchical Z, light list, shadow
# cascades, async SSAO, bloom) headless on every compiled-in backend and writes their pictures
# under OUT: OUT/deferred-<backend>/ and OUT/engine-<backend>/ each hold final.png, every
# intermediate texture, plan.json, plan.dot, summary.txt, inspect.html (the frame inspector,
# docs/inspector.md: open it in a browser) with the inspect.json it was made from and, with
# Graphviz installed, plan.svg. Usage: scripts/demo.sh BUILD_DIR OUT_DIR
set -euo pipefail
build=${1:?build directory}
out=${2:?output directory}
mkdir -p "$out"

backends=()
grep -q '^LOOM_WITH_GL:BOOL=ON' "$build/CMakeCache.txt" && backends+=(gl)
grep -q '^LOOM_WITH_VULKAN:BOOL=ON' "$build/CMakeCache.txt" && backends+=(vulkan)
if [[ ${#backends[@]} -eq 0 ]]; then
  echo "demo: no backend compiled in (LOOM_WITH_GL and LOOM_WITH_VULKAN are both OFF)" >&2
  exit 1
fi

sample="$build/samples/deferred/loom-deferred"
engine="$build/samples/engine/loom-engine"
inspect="$build/samples/inspect/loom-inspect"
for program in "$sample" "$engine" "$inspect"; do
  if [[ ! -x "$program" ]]; then
    echo "demo: $program was not built (LOOM_BUILD_SAMPLES=OFF?)" >&2
    exit 1
  fi
done

for b in "${backends[@]}"; do
  "$sample" --backend "$b" --out "$out/deferred-$b" --inspect "$out/deferred-$b/inspect.json"
  "$engine" --backend "$b" --out "$out/engine-$b" --inspect "$out/engine-$b/inspect.json"
  "$inspect" "$out/deferred-$b/inspect.json" --title "loom-deferred ($b)" --out "$out/deferred-$b/inspect.html"
  "$inspect" "$out/engine-$b/inspect.json" --title "loom-engine ($b)" --out "$out/engine-$b/inspect.html"
  if command -v dot >/dev/null 2>&1; then
    dot -Tsvg "$out/deferred-$b/plan.dot" -o "$out/deferred-$b/plan.svg"
    dot -Tsvg "$out/engine-$b/plan.dot" -o "$out/engine-$b/plan.svg"
  fi
done
echo "demo: pictures written under $out/deferred-*/ and $out/engine-*/ (final.png, every intermediate, plan.json/.dot/.svg and inspect.html per backend)"
