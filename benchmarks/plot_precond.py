#!/usr/bin/env python3
"""Plot the preconditioner study (bench_precond CSV, benchmarks/precond.sh) into a PNG.

    python3 benchmarks/plot_precond.py results/precond.csv [--solve results/precond_solve.csv] \
        -o precond.png

Top row, bench_precond rows (bench = precond, one Newton system per preconditioner):
MINRES iterations, time per Newton system (numeric setup + MINRES) per vertex and the
preconditioner's memory per vertex against the number of vertices, one line per
(lattice, joints, preconditioner).  Bottom row, whole solves: bench_lattice rows of
--solve (rn_solve; solver and preconditioner), else bench_precond --newton rows
(bench = precond-newton): solve time, time per vertex and peak resident size per
vertex.  Prints the fitted exponent p of time ~ DOFs^p (least squares in log-log) of
every series with at least three sizes.
"""
import argparse
import csv
import math
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def slope(xs, ys):
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    n = len(lx)
    mx, my = sum(lx) / n, sum(ly) / n
    sxx = sum((a - mx) ** 2 for a in lx)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sxx if sxx > 0 else float("nan")


def read_series(path, solve):
    """The rows of the bench_precond CSV at path, and its series: (kind, model,
    precond) -> vertices -> row (the last row of a size wins), one for the Newton
    systems and one for the whole solves (with those of the bench_lattice CSV solve,
    per DOF)."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot_precond.py: {path} has no data rows")
    system = defaultdict(dict)  # (kind, model, precond) -> vertices -> row (last wins)
    newton = defaultdict(dict)
    for r in rows:
        key = (r["kind"], r["model"], r["precond"])
        target = system if r["bench"] == "precond" else newton
        target[key][int(r["vertices"])] = r
    if solve:
        with open(solve, newline="") as f:
            for r in csv.DictReader(f):
                key = (r["lattice"], r["joint_model"],
                       r["solver"] + ("+" + r["preconditioner"]
                                      if r["solver"] == "tr-krylov" else ""))
                # vertices are not in bench_lattice's CSV: DOFs / 3.7 (8 edges per rod)
                r["vertices"] = r["size"]
                r["bytes_per_vertex"] = str(float(r["peak_rss_mb"]) * 1048576.0
                                            / float(r["size"]))
                newton[key][int(r["size"])] = r
    return rows, system, newton


def print_exponent(what, label, pts, t):
    """The fitted exponent of time t against DOFs, for a series of 3 sizes or more."""
    if len(pts) >= 3:
        dofs = [float(r["size"]) for _, r in pts]
        print("  %-7s %-32s p = %.2f  (%d sizes, %d..%d vertices)"
              % (what, label, slope(dofs, t), len(pts), pts[0][0], pts[-1][0]))


def plot_systems(system, a_its, a_time, a_mem):
    """One Newton system per series: MINRES iterations, time and memory per vertex."""
    for key in sorted(system):
        pts = sorted(system[key].items())
        vx = [v for v, _ in pts]
        label = "%s %s %s" % key
        style = "-" if key[1] == "rigid" else "--"
        its = [float(r["minres_its"]) for _, r in pts]
        t = [float(r["setup2_s"]) + float(r["minres_s"]) for _, r in pts]
        mem = [float(r["bytes_per_vertex"]) for _, r in pts]
        a_its.plot(vx, its, style, marker="o", label=label)
        a_time.plot(vx, [1e6 * ti / v for ti, v in zip(t, vx)], style, marker="o", label=label)
        a_mem.plot(vx, mem, style, marker="o", label=label)
        print_exponent("system", label, pts, t)


def plot_solves(newton, a_ntime, a_nrate, a_rss):
    """Whole solves per series: time, time per vertex, peak resident size per vertex."""
    for key in sorted(newton):
        pts = sorted(newton[key].items())
        vx = [v for v, _ in pts]
        label = "%s %s %s" % key
        t = [float(r["median"]) for _, r in pts]
        rss = [float(r["bytes_per_vertex"]) for _, r in pts]
        a_ntime.loglog(vx, t, marker="o", label=label)
        a_nrate.plot(vx, [1e6 * ti / v for ti, v in zip(t, vx)], marker="o", label=label)
        a_rss.plot(vx, rss, marker="o", label=label)
        print_exponent("solve", label, pts, t)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("csv")
    ap.add_argument("--solve", help="bench_lattice CSV of whole solves")
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args()
    rows, system, newton = read_series(args.csv, args.solve)
    fig, axes = plt.subplots(2, 3, figsize=(17, 9.5))
    (a_its, a_time, a_mem), (a_ntime, a_nrate, a_rss) = axes
    print("fitted exponents of time against DOFs (>= 3 sizes):")
    plot_systems(system, a_its, a_time, a_mem)
    plot_solves(newton, a_ntime, a_nrate, a_rss)
    for ax, ttl, yl in (
            (a_its, "MINRES iterations, one Newton system", "iterations"),
            (a_time, "setup (numeric) + MINRES per vertex", "microseconds per vertex"),
            (a_mem, "preconditioner memory per vertex", "bytes per vertex"),
            (a_ntime, "whole solve", "seconds"),
            (a_nrate, "whole solve per vertex (per DOF with --solve)", "microseconds"),
            (a_rss, "peak resident size per vertex (per DOF with --solve)", "bytes")):
        ax.set_xscale("log")
        if ax in (a_its,):
            ax.set_yscale("log")
        ax.set_title(ttl, fontsize=10)
        ax.set_xlabel("vertices" if ax in (a_its, a_time, a_mem) or not args.solve
                      else "DOFs")
        ax.set_ylabel(yl)
        ax.grid(True, which="both", alpha=0.3)
    a_its.legend(fontsize=6, ncol=2)
    a_ntime.legend(fontsize=7)
    r0 = rows[0]
    fig.suptitle("rodnet preconditioners - commit %s, %s, %s rank(s)"
                 % (r0["commit"], r0["compiler"], r0["ranks"]))
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)

if __name__ == "__main__":
    main()
