#!/usr/bin/env python3
"""Writes the large graph files the frame-graph scaling measurements plan with loom-plan
(docs/BENCHMARKS.md, "Frame graph at scale"). Each shape stresses one part of planning:

  ports N    one pass with N outputs, every one a graph output (merging and looking up ports)
  connect N  N outputs of one pass feeding the N inputs of another (connect's port lookup)
  live N     N passes whose outputs one last pass reads: N resources alive at once
             (plan with --allocator heap --max-heap 1, every resource in a heap of its own)
  chain N    N passes in a chain, the last one's output a graph output (plan size; --json)

  scale_graph.py SHAPE N OUT.json
"""

import json
import sys

SIZE = [16, 16]  # small textures: the measurements are about counts, not bytes


def ports(n):
    outputs = [{"name": f"o{i}", "format": "RGBA8", "size": SIZE} for i in range(n)]
    return {"passes": [{"name": "wide", "outputs": outputs}],
            "connections": [],
            "outputs": [f"wide.o{i}" for i in range(n)]}


def connect(n):
    return {"passes": [{"name": "producer",
                        "outputs": [{"name": f"o{i}", "format": "RGBA8", "size": SIZE} for i in range(n)]},
                       {"name": "consumer",
                        "inputs": [{"name": f"i{i}"} for i in range(n)],
                        "outputs": [{"name": "final", "format": "RGBA8", "size": SIZE}]}],
            "connections": [[f"producer.o{i}", f"consumer.i{i}"] for i in range(n)],
            "outputs": ["consumer.final"]}


def live(n):
    passes = [{"name": f"p{i}", "outputs": [{"name": "out", "format": "RGBA8", "size": SIZE}]} for i in range(n)]
    passes.append({"name": "reader",
                   "inputs": [{"name": f"i{i}"} for i in range(n)],
                   "outputs": [{"name": "final", "format": "RGBA8", "size": SIZE}]})
    return {"passes": passes,
            "connections": [[f"p{i}.out", f"reader.i{i}"] for i in range(n)],
            "outputs": ["reader.final"]}


def chain(n):
    passes = [{"name": "p0", "outputs": [{"name": "out", "format": "RGBA8", "size": SIZE}]}]
    passes += [{"name": f"p{i}", "inputs": [{"name": "in"}], "outputs": [{"name": "out"}]} for i in range(1, n)]
    return {"passes": passes,
            "connections": [[f"p{i - 1}.out", f"p{i}.in"] for i in range(1, n)],
            "outputs": [f"p{n - 1}.out"]}


SHAPES = {"ports": ports, "connect": connect, "live": live, "chain": chain}


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in SHAPES:
        sys.exit(f"usage: scale_graph.py {{{','.join(SHAPES)}}} N OUT.json")
    graph = SHAPES[sys.argv[1]](int(sys.argv[2]))
    with open(sys.argv[3], "w", encoding="utf-8") as out:
        json.dump(graph, out, separators=(",", ":"))
        out.write("\n")


if __name__ == "__main__":
    main()
