#!/usr/bin/env python3
"""Draws docs/images/pass-order.svg from the CSV files loom_pass_order_report writes (--csv DIR).

    loom_pass_order_report --csv build/pass-order
    tests/bench/plot_pass_order.py build/pass-order docs/images/pass-order.svg

Left: the sample graphs' peak of live bytes in declared order, in memory order and at the exact
optimum (lifetimes; for frames with async compute a lower bound). Right: the small random
corpus, each graph's peak in memory order and at the optimum relative to its declared order,
sorted. Plain SVG written by hand: no plotting library needed.
"""
import csv
import sys
from pathlib import Path

WIDTH, HEIGHT = 980, 440
COLOURS = {"declared": "#9e9e9e", "memory": "#1f77b4", "exact": "#2ca02c"}


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def text(x, y, s, size=12, anchor="start", weight="normal", colour="#222"):
    s = s.replace("&", "&amp;").replace("<", "&lt;")
    return (f'<text x="{x:.1f}" y="{y:.1f}" font-family="Helvetica, Arial, sans-serif" font-size="{size}" '
            f'text-anchor="{anchor}" font-weight="{weight}" fill="{colour}">{s}</text>')


def frames_panel(rows, x0, y0, w, h):
    out = [text(x0, y0 - 22, "Sample graphs: peak of live bytes (MiB)", 14, weight="bold")]
    rows = sorted(rows, key=lambda r: -int(r["declared_bytes"]))
    label_w = 150
    top = max(int(r["declared_bytes"]) for r in rows) / 2**20
    scale = (w - label_w - 60) / top
    band = h / len(rows)
    bar = band / 4.2
    for i, r in enumerate(rows):
        y = y0 + i * band
        out.append(text(x0 + label_w - 8, y + 2.2 * bar, r["graph"], 11, "end"))
        values = [("declared", r["declared_bytes"]), ("memory", r["memory_bytes"]), ("exact", r["exact_bytes"])]
        for j, (name, value) in enumerate(values):
            if not value:
                continue
            mib = int(value) / 2**20
            yy = y + j * bar + 0.3 * bar
            out.append(f'<rect x="{x0 + label_w}" y="{yy:.1f}" width="{mib * scale:.1f}" height="{bar * 0.9:.1f}" '
                       f'fill="{COLOURS[name]}"/>')
            if name != "exact":
                out.append(text(x0 + label_w + mib * scale + 4, yy + bar * 0.8, f"{mib:.1f}", 9))
    ly = y0 + h + 14
    out.append(text(x0, ly + 18, "exact: over lifetimes; with async compute (DOOM) a lower bound of what any order holds",
                    10, colour="#555"))
    for k, name in enumerate(["declared", "memory", "exact"]):
        lx = x0 + label_w + k * 110
        out.append(f'<rect x="{lx}" y="{ly - 9}" width="10" height="10" fill="{COLOURS[name]}"/>')
        label = {"declared": "declared order", "memory": "memory order", "exact": "exact optimum"}[name]
        out.append(text(lx + 14, ly, label, 11))
    return out


def corpus_panel(rows, x0, y0, w, h):
    solved = [r for r in rows if r["exact_bytes"]]
    memory = sorted(int(r["memory_bytes"]) / int(r["declared_bytes"]) for r in rows)
    exact = sorted(int(r["exact_bytes"]) / int(r["declared_bytes"]) for r in solved)
    optimal = sum(1 for r in solved if r["exact_bytes"] == r["memory_bytes"])
    out = [text(x0, y0 - 22, f"{len(rows)} small random graphs: peak / declared peak", 14, weight="bold")]
    lo = 0.3
    def px(i, n):
        return x0 + 40 + (w - 50) * i / max(1, n - 1)
    def py(v):
        return y0 + h - (v - lo) / (1.0 - lo) * h
    for v in (0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0):
        out.append(f'<line x1="{x0 + 40}" y1="{py(v):.1f}" x2="{x0 + w - 10}" y2="{py(v):.1f}" stroke="#e0e0e0"/>')
        out.append(text(x0 + 34, py(v) + 4, f"{v:.1f}", 10, "end"))
    for series, colour, dash in ((memory, COLOURS["memory"], ""), (exact, COLOURS["exact"], ' stroke-dasharray="5,4"')):
        points = " ".join(f"{px(i, len(series)):.1f},{py(max(lo, v)):.1f}" for i, v in enumerate(series))
        out.append(f'<polyline points="{points}" fill="none" stroke="{colour}" stroke-width="2"{dash}/>')
    out.append(text(x0 + 40 + (w - 50) / 2, y0 + h + 16, "graphs, sorted by ratio", 11, "middle"))
    out.append(text(x0 + 50, y0 + 16, f"memory order optimal on {optimal} of {len(solved)} solved exactly", 11,
                    colour=COLOURS["memory"]))
    out.append(text(x0 + 50, y0 + 32, "exact optimum (dashed) under it", 11, colour=COLOURS["exact"]))
    return out


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    data, target = Path(sys.argv[1]), Path(sys.argv[2])
    frames = read(data / "engine_frames.csv")
    corpus = read(data / "small_corpus.csv")
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" '
             f'viewBox="0 0 {WIDTH} {HEIGHT}">', f'<rect width="{WIDTH}" height="{HEIGHT}" fill="white"/>']
    parts += frames_panel(frames, 10, 50, 500, 320)
    parts += corpus_panel(corpus, 540, 50, 430, 320)
    parts.append("</svg>")
    target.write_text("\n".join(parts) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
