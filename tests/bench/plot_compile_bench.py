#!/usr/bin/env python3
"""Draws docs/images/compile-vs-peers.svg: µs per pass against pass count, one line per library,
from the JSON that loom_framegraph_compile_bench writes (Google Benchmark's --benchmark_out).

    build/o3/tests/bench/loom_framegraph_compile_bench --benchmark_min_time=0.3 \\
        --benchmark_out=build/compile.json --benchmark_out_format=json
    tests/bench/plot_compile_bench.py build/compile.json docs/images/compile-vs-peers.svg

Both axes are logarithmic: a flat line costs the same per pass at every size, a rising one grows
with the graph. Plain SVG written by hand: no plotting library needed.
"""
import json
import math
import re
import sys

from plot_pass_order import text  # the same SVG text element (this folder is on sys.path)

WIDTH, HEIGHT = 760, 440
LEFT, RIGHT, TOP, BOTTOM = 70, 250, 40, 60
# Benchmark name (without the size) -> the label and colour of its line.
SERIES = {
    "BM_CompileLoomTyped/interval": ("loom, interval, typed", "#1f77b4"),
    "BM_CompileLoomByName/interval": ("loom, interval, by names", "#6baed6"),
    "BM_CompileLoomTyped/interval_reused": ("loom, interval, graph reused", "#08306b"),
    "BM_CompileLoomTyped/heap": ("loom, heap, typed", "#ff7f0e"),
    "BM_CompileSkaarj": ("skaarj1989/FrameGraph", "#2ca02c"),
    "BM_CompileAcdemiralp": ("acdemiralp/fg", "#d62728"),
}


def read_points(path):
    """{series name: [(passes, µs per pass)]} from the benchmark's JSON (medians when it ran
    repetitions, else the single run)."""
    with open(path) as f:
        runs = json.load(f)["benchmarks"]
    medians = {r["run_name"] for r in runs if r.get("aggregate_name") == "median"}
    points = {}
    for r in runs:
        if r.get("run_type") == "aggregate" and r.get("aggregate_name") != "median":
            continue
        if r.get("run_type") != "aggregate" and r["run_name"] in medians:
            continue
        m = re.match(r"(.*)/(\d+)$", r["run_name"])
        if not m or m.group(1) not in SERIES or "per_pass" not in r:
            continue
        # per_pass is an inverted rate: seconds per pass.
        points.setdefault(m.group(1), []).append((int(m.group(2)), r["per_pass"] * 1e6))
    return {k: sorted(v) for k, v in points.items()}


def plot(points):
    xs = [n for v in points.values() for n, _ in v]
    ys = [t for v in points.values() for _, t in v]
    x_lo, x_hi = math.log10(min(xs)), math.log10(max(xs))
    y_lo, y_hi = math.floor(math.log10(min(ys))), math.ceil(math.log10(max(ys)))
    w, h = WIDTH - LEFT - RIGHT, HEIGHT - TOP - BOTTOM

    def px(n):
        return LEFT + (math.log10(n) - x_lo) / max(x_hi - x_lo, 1e-9) * w

    def py(t):
        return TOP + h - (math.log10(t) - y_lo) / (y_hi - y_lo) * h

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" viewBox="0 0 {WIDTH} {HEIGHT}">',
           f'<rect width="{WIDTH}" height="{HEIGHT}" fill="white"/>',
           text(LEFT, 22, "Declare + compile, µs per pass (log) against passes (log)", 14, weight="bold")]
    for e in range(y_lo, y_hi + 1):
        y = py(10 ** e)
        out.append(f'<line x1="{LEFT}" y1="{y:.1f}" x2="{LEFT + w}" y2="{y:.1f}" stroke="#ddd"/>')
        out.append(text(LEFT - 8, y + 4, f"{10 ** e:g}", 11, "end"))
    for n in sorted(set(xs)):
        x = px(n)
        out.append(f'<line x1="{x:.1f}" y1="{TOP}" x2="{x:.1f}" y2="{TOP + h}" stroke="#eee"/>')
        out.append(text(x, TOP + h + 18, f"{n:,}", 11, "middle"))
    out.append(text(LEFT + w / 2, HEIGHT - 16, "passes in the graph", 12, "middle"))
    out.append(f'<rect x="{LEFT}" y="{TOP}" width="{w}" height="{h}" fill="none" stroke="#888"/>')
    legend_y = TOP + 10
    for name, (label, colour) in SERIES.items():
        if name not in points:
            continue
        line = " ".join(f"{px(n):.1f},{py(t):.1f}" for n, t in points[name])
        out.append(f'<polyline points="{line}" fill="none" stroke="{colour}" stroke-width="2"/>')
        for n, t in points[name]:
            out.append(f'<circle cx="{px(n):.1f}" cy="{py(t):.1f}" r="3.5" fill="{colour}"/>')
        out.append(f'<line x1="{LEFT + w + 16}" y1="{legend_y - 4}" x2="{LEFT + w + 40}" y2="{legend_y - 4}" '
                   f'stroke="{colour}" stroke-width="2"/>')
        out.append(text(LEFT + w + 46, legend_y, label, 12))
        legend_y += 22
    out.append("</svg>")
    return "\n".join(out) + "\n"


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_compile_bench.py BENCHMARK_JSON OUTPUT_SVG")
    points = read_points(sys.argv[1])
    if not points:
        sys.exit(f"plot_compile_bench: no compile benchmark with a per_pass counter in {sys.argv[1]}")
    with open(sys.argv[2], "w") as f:
        f.write(plot(points))
    for name, values in points.items():
        print(f"{SERIES[name][0]}: " + ", ".join(f"{n:,}: {t:.3g} µs/pass" for n, t in values))


if __name__ == "__main__":
    main()
