#!/usr/bin/env python3
"""Instructions and heap allocations per draw, loom's RHI against the raw APIs (issue: the RHI
costs almost nothing per draw). Runs each program of tests/bench/draw_cost under
`valgrind --tool=callgrind` for N and 2N draws and divides the difference by N, so that the
fixed costs of a frame cancel; splits the instructions by the object that executed them:

  loom      loom's code (the RHI, what it inlines from loom's headers) in loom_draw_cost
  bench     the benchmark's own code (tests/bench/draw_cost/: the loop, the per-draw constants);
            all of a raw program's own code
  runtime   the C and C++ runtime it calls (libc, libstdc++, libm, libgcc)
  dispatch  the API's dispatch layer (libepoxy, libglvnd, the Vulkan loader)
  driver    Mesa (llvmpipe / lavapipe, their JIT code)

Usage: draw_cost.py BUILD_DIR [--draws N] [--paths a,b] [--backends gl,vulkan] [--validation on|off|both]
                   [--json FILE]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

PATHS = ["push_constants", "transient_uniforms", "bind_group", "vertex_buffers", "pipeline"]
RUNTIME = re.compile(r"/(libc|libstdc\+\+|libm|libgcc_s|ld-linux[^/]*|libpthread)[.-][^/]*$")
DISPATCH = re.compile(r"/(libepoxy|libGLdispatch|libEGL|libGLX|libOpenGL|libGL|libvulkan)\.so[^/]*$")


def categorise(obj, program, bench_source=False):
    if os.path.realpath(obj) == os.path.realpath(program):
        return "bench" if bench_source or os.path.basename(program).startswith("raw_") else "loom"
    if RUNTIME.search(obj):
        return "runtime"
    if DISPATCH.search(obj):
        return "dispatch"
    return "driver"


def costs_by_object(path):
    """Exclusive instruction counts per object of a callgrind output file ({(object, bench source):
    instructions}, bench source: the code is the benchmark's own, in tests/bench/, inlined or not),
    and the inclusive cost of every call between two objects ({(caller, callee): instructions})."""
    names = {}
    costs = {}
    calls = {}
    obj = "???"
    function_file = current_file = "???"
    callee = None
    in_call = False

    def name(value, kind):
        # Objects and files are numbered apart ("(3) /usr/lib/...", then "(3)" alone).
        m = re.match(r"\((\d+)\)(?: (.*))?$", value)
        if not m:
            return value
        if m.group(2) is not None:
            names[(kind, m.group(1))] = m.group(2)
        return names.get((kind, m.group(1)), "???")

    with open(path) as f:
        for line in f:
            line = line.rstrip("\n")
            if not line:
                continue
            c = line[0]
            if c.isdigit() or c in "+-*":
                parts = line.split()
                cost = int(parts[1]) if len(parts) >= 2 else 0
                if in_call:
                    key = (obj, callee or obj)
                    calls[key] = calls.get(key, 0) + cost
                    in_call = False
                    callee = None
                else:
                    key = (obj, "/tests/bench/" in current_file)
                    costs[key] = costs.get(key, 0) + cost
            elif line.startswith("ob="):
                obj = name(line[3:], "ob")
            elif line.startswith("fl="):
                function_file = current_file = name(line[3:], "fl")
            elif line.startswith(("fi=", "fe=")):
                current_file = name(line[3:], "fl")
            elif line.startswith("fn="):
                current_file = function_file
            elif line.startswith(("cfi=", "cfl=")):
                name(line[4:], "fl")  # a callee's file, maybe named here first
            elif line.startswith("cob="):
                callee = name(line[4:], "ob")
            elif line.startswith("calls="):
                in_call = True
    return costs, calls


def run(program, args, draws):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "callgrind.out")
        cmd = ["valgrind", "--tool=callgrind", "--instr-atstart=no", f"--callgrind-out-file={out}", program] + args + [
            "--draws", str(draws)]
        result = subprocess.run(cmd, capture_output=True, text=True)
        if result.returncode != 0:
            sys.exit(f"draw_cost: {' '.join(cmd)} failed:\n{result.stderr[-2000:]}")
        m = re.search(r"allocations=(\d+)", result.stdout)
        if not m:
            sys.exit(f"draw_cost: {' '.join(cmd)} printed no report:\n{result.stdout}")
        split = {"loom": 0, "bench": 0, "runtime": 0, "dispatch": 0, "driver": 0}
        costs, calls = costs_by_object(out)
        for (obj, bench_source), cost in costs.items():
            split[categorise(obj, program, bench_source)] += cost
        # The runtime the driver and the dispatch layer call (malloc, memcpy) is theirs, not the
        # program's: only what the program itself calls stays in the runtime column.
        for (caller, callee), cost in calls.items():
            by, to = categorise(caller, program), categorise(callee, program)
            if to == "runtime" and by in ("driver", "dispatch"):
                split["runtime"] -= cost
                split[by] += cost
        return split, int(m.group(1))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("build_dir")
    parser.add_argument("--draws", type=int, default=1000)
    parser.add_argument("--paths", default=",".join(PATHS))
    parser.add_argument("--backends", default="gl,vulkan")
    parser.add_argument("--validation", default="on", choices=["on", "off", "both"],
                        help="loom's DeviceDesc::validation: on (the default), off, or both side by side")
    parser.add_argument("--json")
    options = parser.parse_args()
    bench = os.path.join(options.build_dir, "tests", "bench")
    programs = []
    for backend in options.backends.split(","):
        raw = os.path.join(bench, f"raw_{backend}_draw_cost")
        if not os.path.exists(raw):
            print(f"draw_cost: {raw} is not built; {backend} skipped", file=sys.stderr)
            continue
        for validation in (["on", "off"] if options.validation == "both" else [options.validation]):
            label = f"loom {backend}" if validation == "on" else f"loom {backend} unvalidated"
            programs.append((label, os.path.join(bench, "loom_draw_cost"),
                             ["--backend", backend, "--validation", validation]))
        programs.append((f"raw {backend}", raw, []))
    rows = []
    n = options.draws
    for path in options.paths.split(","):
        for label, program, args in programs:
            small, allocations_small = run(program, args + ["--path", path], n)
            large, allocations_large = run(program, args + ["--path", path], 2 * n)
            per_draw = {k: (large[k] - small[k]) / n for k in small}
            per_draw["total"] = sum(per_draw.values())
            rows.append({"path": path, "program": label, **per_draw,
                         "allocations": (allocations_large - allocations_small) / n})
    print(f"Instructions per draw (callgrind, ({2 * n} draws - {n} draws) / {n}); allocations per draw (operator new)\n")
    print("| path | program | loom's code | runtime | loom + runtime | benchmark's code | dispatch | driver | total | vs raw | allocations/draw |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        backend = row["program"].split()[1]
        raw = next((r for r in rows if r["path"] == row["path"] and r["program"] == "raw " + backend), None)
        ratio = f"{row['total'] / raw['total']:.3f}" if raw and raw["total"] else "-"
        print(f"| {row['path']} | {row['program']} | {row['loom']:,.0f} | {row['runtime']:,.0f} | "
              f"{row['loom'] + row['runtime']:,.0f} | {row['bench']:,.0f} | {row['dispatch']:,.0f} | "
              f"{row['driver']:,.0f} | {row['total']:,.0f} | {ratio} | {row['allocations']:.2f} |")
    if options.json:
        with open(options.json, "w") as f:
            json.dump(rows, f, indent=2)


if __name__ == "__main__":
    main()
