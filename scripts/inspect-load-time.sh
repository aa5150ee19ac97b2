#!/usr/bin/env bash
# Opens inspector pages (loom-inspect's output) in headless Chromium, each RUNS times with the
# pages taking turns, and prints per page its size and the load time the page measured itself
# (<body data-load-ms>: from navigation to the end of its script): median, fastest and slowest.
# Each run has a fresh profile and no network, as the page tests do (tests/inspect).
#
#   scripts/inspect-load-time.sh [--runs N] PAGE.html...      (N defaults to 10)
#
# $LOOM_CHROMIUM names the browser (default: chromium on the PATH).
set -euo pipefail

runs=10
pages=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --runs) runs=$2; shift 2 ;;
    -*) echo "inspect-load-time: unknown option '$1'" >&2; exit 2 ;;
    *) pages+=("$1"); shift ;;
  esac
done
if [[ ${#pages[@]} -eq 0 ]]; then
  echo "usage: scripts/inspect-load-time.sh [--runs N] PAGE.html..." >&2
  exit 2
fi
chromium=${LOOM_CHROMIUM:-chromium}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

declare -A times
for ((run = 0; run < runs; ++run)); do
  for page in "${pages[@]}"; do
    rm -rf "$work/profile"
    url="file://$(realpath "$page")"
    ms=$(timeout 120 "$chromium" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
           --disable-background-networking --disable-component-update --disable-sync \
           --user-data-dir="$work/profile" --window-size=1600,4000 --dump-dom "$url" 2>/dev/null |
         grep -o 'data-load-ms="[0-9.]*"' | head -1 | grep -o '[0-9.]*' || true)
    if [[ -z $ms ]]; then
      echo "inspect-load-time: $page did not report its load time" >&2
      exit 1
    fi
    times[$page]+="$ms "
  done
done

printf '%-40s %12s %10s %10s %10s\n' page bytes median fastest slowest
for page in "${pages[@]}"; do
  read -r median fastest slowest < <(tr ' ' '\n' <<<"${times[$page]}" | grep . | sort -n |
    awk '{ v[NR] = $1 } END { m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2; printf "%.0f %.0f %.0f\n", m, v[1], v[NR] }')
  printf '%-40s %12d %8s ms %7s ms %7s ms\n' "$page" "$(stat -c %s "$page")" "$median" "$fastest" "$slowest"
done
