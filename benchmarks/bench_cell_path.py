#!/usr/bin/env python3
"""bench_cell_path.py - issue 24's Bloch-Floquet path targets, measured as a user
waits for them: the whole `rodnet homogenize --path` process (generating the cell
is not timed), with the dense (LAPACK) and the sparse (shift-invert Lanczos) Bloch
method, median and minimum of --repeats runs, and the peak resident size.

Cases (rigid joints, square struts of slenderness 0.05, E = 1):
  honeycomb-32     the planar honeycomb cell, 32 edges per strut, equibiaxial
                   compression to about twice its critical strain, in-plane modes,
                   8 steps (target 1 s)
  octet-4          the octet cell, 4 edges per strut, hydrostatic compression to
                   -0.01, 4 steps, --bloch-grid 4 (target 3 s)
  octet-16         the same with 16 edges per strut (measured; no target)
  honeycomb-16x16  a 16 x 16 honeycomb supercell in the planar model, 8 edges per
                   strut (12,286 fluctuation DOFs, beyond dense reach: sparse only),
                   --bloch-grid 2, the cell's critical strain (target 2 minutes)

CSV columns: commit, compiler, flags, ranks, bench (cell_path), case, size (the
cell's fluctuation DOFs), repeats, median, min (seconds of the whole command), method, target_s, exit_status, critical_strain
(first component), kind, wave_vector, iterations (of the locate), peak_rss_mb.

    /usr/bin/python3 benchmarks/bench_cell_path.py --rodnet build/rodnet \\
        --out benchmarks/results/cell_path.csv [--repeats 3] [--cases a,b]
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_csv  # noqa: E402

CASES = {
    "honeycomb-32": {
        "generate": ["honeycomb", "--periodic", "--edges-per-rod", "32"],
        "path": ["--path", "-0.0015,-0.0015,0", "--steps", "8", "--modes", "in-plane"],
        "methods": ["dense", "sparse"], "target": 1.0},
    "octet-4": {
        "generate": ["octet", "--periodic", "--edges-per-rod", "4"],
        "path": ["--path", "-0.01,-0.01,-0.01,0,0,0", "--steps", "4", "--bloch-grid", "4"],
        "methods": ["dense", "sparse"], "target": 3.0},
    "octet-16": {
        "generate": ["octet", "--periodic", "--edges-per-rod", "16"],
        "path": ["--path", "-0.01,-0.01,-0.01,0,0,0", "--steps", "4", "--bloch-grid", "4"],
        "methods": ["sparse"], "target": None},
    "honeycomb-16x16": {
        "generate": ["honeycomb", "--periodic", "--cells", "16,16", "--edges-per-rod", "8",
                     "--model", "planar"],
        "path": ["--path", "-0.0015,-0.0015,0", "--steps", "8", "--bloch-grid", "2"],
        "methods": ["sparse"], "target": 120.0},
}


def result_of(out):
    """The instability and the fluctuation DOFs of RESULT.json (or its partial form)."""
    for path in (out, out.replace(".json", ".partial.json")):
        if os.path.exists(path):
            with open(path) as f:
                return json.load(f)
    return {}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rodnet", default="build/rodnet")
    ap.add_argument("--out", required=True)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cases", default=",".join(CASES))
    a = ap.parse_args()
    names = bench_csv.pick_cases(a.cases, CASES, "bench_cell_path")
    prov = bench_csv.provenance(a.rodnet)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            case = CASES[name]
            scene = os.path.join(tmp, name + ".json")
            subprocess.run([a.rodnet, "generate"] + case["generate"] +
                           ["--joint-model", "rigid", "--slenderness", "0.05", "-o", scene,
                            "-q"], check=True)
            for method in case["methods"]:
                out = os.path.join(tmp, "%s_%s.json" % (name, method))
                cmd = [a.rodnet, "homogenize", scene] + case["path"] + \
                    ["--bloch-method", method, "-o", out, "-q"]
                times, rss, status = [], 0.0, 0
                for _ in range(a.repeats):
                    wall, status, mb = bench_csv.run_once(cmd)
                    times.append(wall)
                    rss = max(rss, mb)
                res = result_of(out)
                inst = res.get("instability") or {}
                row = [prov["commit"], prov["compiler"], prov["flags"], 1, "cell_path", name,
                       res.get("fluctuation_dofs", ""), a.repeats,
                       "%.4f" % statistics.median(times), "%.4f" % min(times), method,
                       case["target"] if case["target"] is not None else "", status,
                       repr(inst["strain"][0]) if inst else "", inst.get("kind", ""),
                       " ".join(str(v) for v in inst.get("wave_vector", [])),
                       inst.get("bisections", ""), "%.1f" % rss]
                rows.append(row)
                print("bench_cell_path: %s %s: median %.3f s (min %.3f, %d runs), exit %d, "
                      "critical strain %s" % (name, method, statistics.median(times),
                                              min(times), a.repeats, status,
                                              row[13] or "-"), file=sys.stderr)
    tmp_out = a.out + ".tmp"
    with open(tmp_out, "w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(["commit", "compiler", "flags", "ranks", "bench", "case", "size",
                     "repeats", "median", "min", "method", "target_s", "exit_status",
                     "critical_strain", "kind", "wave_vector", "iterations",
                     "peak_rss_mb"])
        wr.writerows(rows)
    os.replace(tmp_out, a.out)


if __name__ == "__main__":
    main()
