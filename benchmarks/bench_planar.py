#!/usr/bin/env python3
"""The planar/3D speed ratio (docs/model.md "The planar model", issue 9 section 5).

    bench_planar.py --rodnet build/rodnet [--repeats 5] [--sizes 10000,100000]
                    [--out planar.csv] [--work DIR] [--commit HASH]

For each size, a square lattice (rigid joints, 8 edges per rod) of about that many
3D DOFs under in-plane stretch (stretch-x 1 %, `rodnet generate square --load`) is
solved with "model": "planar" and "model": "3d" (tr-minres, the default); and a
honeycomb periodic cell (rigid joints, 16 edges per strut, a 4 x 4 supercell) is
homogenised with both.  The time is the solver's own (`time_s` of RESULT.json for
a solve; the seconds `rodnet homogenize` prints), so process start-up and file
I/O are left out; medians and minima over --repeats runs, the models alternating.
CSV columns: commit, compiler, flags, ranks, bench (planar), case, model, size
(3D DOFs), dofs (free DOFs of that model), repeats, median_s, min_s, ratio (3D
median / planar median, on the planar rows).  Nothing is asserted.
"""
import argparse
import csv
import json
import os
import re
import statistics
import subprocess
import sys


def provenance(rodnet, commit_override):
    """commit, compiler, flags from <build>/benchmarks/bench_config.h."""
    prov = {"commit": "unknown", "compiler": "unknown", "flags": ""}
    cfg = os.path.join(os.path.dirname(os.path.abspath(rodnet)), "benchmarks",
                       "bench_config.h")
    if os.path.exists(cfg):
        text = open(cfg).read()
        for key, name in (("commit", "RN_BENCH_COMMIT"), ("compiler", "RN_BENCH_COMPILER"),
                          ("flags", "RN_BENCH_FLAGS")):
            m = re.search(r'#define\s+%s\s+"([^"]*)"' % name, text)
            if m:
                prov[key] = m.group(1)
    if commit_override:
        prov["commit"] = commit_override
    return prov


def run(args):
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("bench_planar.py: %s: exit %d\n%s" % (" ".join(args), p.returncode,
                                                      p.stderr))
    return p


def with_model(src, dst, model):
    s = json.load(open(src))
    s["model"] = model
    json.dump(s, open(dst, "w"))
    return dst


def solve_time(rodnet, scene, out):
    run([rodnet, "solve", scene, "-o", out])
    r = json.load(open(out))
    if not r["converged"]:
        sys.exit("bench_planar.py: %s did not converge" % scene)
    return r["time_s"], r["num_dofs"]


def homogenize_time(rodnet, scene, out):
    p = run([rodnet, "homogenize", scene, "-o", out])
    m = re.search(r"([0-9]+) fluctuation DOFs, ([0-9.eE+-]+) s", p.stdout)
    return float(m.group(2)), int(m.group(1))


def measure(fn, scenes, repeats):
    times = {m: [] for m in scenes}
    dofs = {}
    for _ in range(repeats):
        for m, (scene, out) in scenes.items():
            t, n = fn(scene, out)
            times[m].append(t)
            dofs[m] = n
    return times, dofs


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rodnet", required=True)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--sizes", default="10000,100000")
    ap.add_argument("--out", default="planar.csv")
    ap.add_argument("--work", default="bench_planar_work")
    ap.add_argument("--commit")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    prov = provenance(a.rodnet, a.commit)
    w = lambda name: os.path.join(a.work, name)
    rows = []

    def add(case, size, times, dofs):
        med = {m: statistics.median(t) for m, t in times.items()}
        for m in ("planar", "3d"):
            ratio = med["3d"] / med["planar"] if m == "planar" else ""
            rows.append([prov["commit"], prov["compiler"], prov["flags"], 1, "planar", case,
                         m, size, dofs[m], a.repeats, med[m], min(times[m]), ratio])
            print("%-28s %-6s %8d DOFs  median %.4g s  min %.4g s%s" %
                  (case, m, dofs[m], med[m], min(times[m]),
                   "  3D/planar %.2f" % ratio if ratio else ""), flush=True)

    for size in [int(s) for s in a.sizes.split(",")]:
        # square lattice, rigid joints, 8 edges per rod: 2 n^2 rods of 4 * 8 - 1
        # DOFs (+ 6 per joint), about 70 n^2 3D DOFs
        n = max(2, round((size / 70.0) ** 0.5))
        base = w("square_%d.json" % size)
        run([a.rodnet, "generate", "square", "--cells", str(n), "--joint-model", "rigid",
             "--edges-per-rod", "8", "--load", "stretch-x:0.01", "-o", base])
        scenes = {m: (with_model(base, w("square_%d_%s.json" % (size, m)), m),
                      w("square_%d_%s_result.json" % (size, m))) for m in ("planar", "3d")}
        times, dofs = measure(lambda s, o: solve_time(a.rodnet, s, o), scenes, a.repeats)
        add("solve square %dx%d stretch" % (n, n), dofs["3d"], times, dofs)

    base = w("hc_cell.json")
    run([a.rodnet, "generate", "honeycomb", "--periodic", "--joint-model", "rigid",
         "--edges-per-rod", "16", "--cells", "4", "-o", base])
    scenes = {m: (with_model(base, w("hc_cell_%s.json" % m), m),
                  w("hc_cell_%s_result.json" % m)) for m in ("planar", "3d")}
    times, dofs = measure(lambda s, o: homogenize_time(a.rodnet, s, o), scenes, a.repeats)
    add("homogenize honeycomb 4x4 cell", dofs["3d"], times, dofs)

    with open(a.out, "w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(["commit", "compiler", "flags", "ranks", "bench", "case", "model",
                     "size", "dofs", "repeats", "median_s", "min_s", "ratio"])
        wr.writerows(rows)
    print("wrote", a.out)


if __name__ == "__main__":
    main()
