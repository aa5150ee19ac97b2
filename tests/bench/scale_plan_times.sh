#!/bin/sh
# Times loom-plan end to end (load, plan, print) on the scale_graph.py shapes at 1k, 10k and
# 100k and prints one Markdown row per run: shape, N, wall seconds, peak RSS (/usr/bin/time -v).
# docs/BENCHMARKS.md, "Frame graph at scale".
#
#   scale_plan_times.sh LOOM_PLAN [SIZES] [TIMEOUT_SECONDS]
#
# A run that takes longer than TIMEOUT_SECONDS (default 120) is stopped and shown as "> T s".
set -eu
plan=$1
sizes=${2:-"1000 10000 100000"}
limit=${3:-120}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run() {  # shape n args...
    shape=$1 n=$2
    shift 2
    python3 "$here/scale_graph.py" "$shape" "$n" "$work/graph.json"
    if timeout "$limit" /usr/bin/time -v "$plan" "$work/graph.json" "$@" >/dev/null 2>"$work/time"; then
        wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$work/time")
        rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$work/time")
        echo "| $shape $* | $n | $wall | $((rss / 1024)) MiB |"
    else
        echo "| $shape $* | $n | > $limit s (stopped) | - |"
    fi
}

echo "| shape, options | N | wall (m:ss) | peak RSS |"
echo "|---|---|---|---|"
for n in $sizes; do run ports "$n"; done
for n in $sizes; do run connect "$n"; done
for n in $sizes; do run live "$n" --allocator heap --max-heap 1; done
for n in $sizes; do run chain "$n" --json; done
