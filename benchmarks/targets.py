#!/usr/bin/env python3
"""Issue 7's targets, as measured, from bench_lattice CSVs (benchmarks/targets.sh).

    python3 benchmarks/targets.py results/precond_solve.csv results/targets_solve.csv ...
        [--min-dofs 1e4] [-o summary.csv] [--plot targets.png]

Groups the rows into series (lattice, joint model, edges per rod, load, solver,
preconditioner, ranks) and reports per series, over the rows with at least
--min-dofs free DOFs:
  - MINRES iterations per Newton step: smallest, largest and their ratio
    (target: within 1.3x from 10^4 to 10^6 vertices);
  - the fitted exponent of rn_solve time against free DOFs (target: at most 1.1)
    and of the peak resident size (memory per vertex flat: exponent about 1, less
    while the ~80 MB of libraries dominate);
and per (lattice, cells, load) with both a tr-krylov and a tr-minres row, the
Newton iterations of tr-krylov over the exact trust region's (target: at most
+20 %).  --plot draws rn_solve time and peak memory per DOF against DOFs, one line
per series (matplotlib).  Nothing is asserted: these are measurements (a benchmark,
not a test).
"""
import argparse
import csv
import math
import sys
from collections import defaultdict


def slope(xs, ys):
    """Least-squares slope of log(y) against log(x); nan with fewer than 2 sizes."""
    if len(xs) < 2:
        return float("nan")
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    sxx = sum((a - mx) ** 2 for a in lx)
    if sxx <= 0:
        return float("nan")
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sxx


def vertices(r):
    """Vertices of a lattice row as docs/solvers.md counts them: every rod's vertices
    (a joint is counted once per rod end at it)."""
    return int(r["rods"]) * (int(r["edges_per_rod"]) + 1)


def read(paths):
    rows = []
    for p in paths:
        with open(p, newline="") as f:
            for r in csv.DictReader(f):
                if r.get("bench") != "lattice":
                    continue
                if r.get("stop") not in ("gradient", "step", "energy"):
                    print(f"targets.py: {p}: {r['case']} at {r['size']} DOFs did not "
                          f"converge (stop {r.get('stop')}): left out", file=sys.stderr)
                    continue
                rows.append(r)
    return rows


def fmt(x, spec=".2f"):
    return "n/a" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


def plot(curves, path):
    import os
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    for name, dofs, t, mem in curves:
        if len(dofs) < 2:
            continue
        ax[0].loglog(dofs, [a / b for a, b in zip(t, dofs)], "o-", label=name)
        if len(mem) == len(dofs):
            ax[1].loglog(dofs, [1e6 * a / b for a, b in zip(mem, dofs)], "o-", label=name)
    ax[0].set_ylabel("rn_solve time per free DOF [s]")
    ax[1].set_ylabel("peak resident size per free DOF [bytes]")
    for x in ax:
        x.set_xlabel("free DOFs")
        x.grid(True, which="both", alpha=0.3)
    ax[0].legend(fontsize=7)
    fig.suptitle("issue 7 targets: flat per-DOF cost means exponent 1 (benchmarks/targets.py)")
    fig.tight_layout()
    fig.savefig(path + ".tmp.png", dpi=110)
    os.replace(path + ".tmp.png", path)


def scaling_table(rows, min_dofs):
    """Per series (lattice, joints, edges per rod, load, solver, preconditioner, ranks):
    a Markdown row of the sizes, MINRES per Newton step and the time and memory
    exponents, printed; returns the summary rows and the curves to plot."""
    series = defaultdict(list)
    for r in rows:
        key = (r["lattice"], r["joint_model"], r["edges_per_rod"], r["load"], r["solver"],
               r.get("preconditioner", "") or "-", r["ranks"])
        series[key].append(r)

    out = []
    curves = []
    print("| lattice | joints | load | solver | precond | ranks | DOFs | vertices "
          "| MINRES/Newton min..max (ratio) | Newton | time exponent | memory exponent |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for key in sorted(series):
        rs = sorted((r for r in series[key] if float(r["size"]) >= min_dofs),
                    key=lambda r: int(r["size"]))
        # one row per size: the last measurement of a size wins
        by_size = {}
        for r in rs:
            by_size[int(r["size"])] = r
        rs = [by_size[s] for s in sorted(by_size)]
        if not rs:
            continue
        dofs = [int(r["size"]) for r in rs]
        t = [float(r["median"]) for r in rs]
        mem = [float(r["peak_rss_mb"]) for r in rs if r.get("peak_rss_mb")]
        mpn = [float(r["minres_per_newton"]) for r in rs]
        newton = [int(r["newton_iterations"]) for r in rs]
        ratio = max(mpn) / min(mpn) if min(mpn) > 0 else float("nan")
        te = slope(dofs, t) if len(rs) >= 3 else float("nan")
        me = slope(dofs, mem) if len(mem) == len(rs) and len(rs) >= 3 else float("nan")
        lattice, joints, epr, load, solver, prec, ranks = key
        print(f"| {lattice} | {joints} | {load} | {solver} | {prec} | {ranks} "
              f"| {dofs[0]:,}..{dofs[-1]:,} | {vertices(rs[0]):,}..{vertices(rs[-1]):,} "
              f"| {min(mpn):.2f}..{max(mpn):.2f} ({fmt(ratio)}) "
              f"| {'/'.join(map(str, newton))} | {fmt(te)} | {fmt(me)} |")
        curves.append((f"{lattice} {load} {solver}+{prec}", dofs, t, mem))
        out.append(dict(lattice=lattice, joint_model=joints, edges_per_rod=epr, load=load,
                        solver=solver, preconditioner=prec, ranks=ranks, sizes=len(rs),
                        dofs_min=dofs[0], dofs_max=dofs[-1], minres_per_newton_min=min(mpn),
                        minres_per_newton_max=max(mpn), minres_ratio=ratio,
                        time_exponent=te, memory_exponent=me))
    return out, curves


def newton_table(rows):
    """Newton steps of tr-krylov against the exact trust region on the same problem
    (a Markdown table, printed if any problem has both)."""
    exact = {}
    krylov = defaultdict(list)
    for r in rows:
        k = (r["lattice"], r["cells"], r["joint_model"], r["edges_per_rod"], r["load"],
             r["ranks"])
        if r["solver"] == "tr-minres":
            exact[k] = r
        elif r["solver"] == "tr-krylov":
            krylov[k].append(r)
    pairs = [(k, exact[k], kr) for k in sorted(exact) if k in krylov for kr in krylov[k]]
    if pairs:
        print()
        print("| lattice | cells | load | DOFs | tr-minres Newton | tr-krylov (precond) Newton "
              "| over the exact trust region |")
        print("|---|---|---|---|---|---|---|")
        for k, ex, kr in pairs:
            ne, nk = int(ex["newton_iterations"]), int(kr["newton_iterations"])
            print(f"| {k[0]} | {k[1]} | {k[4]} | {int(ex['size']):,} | {ne} "
                  f"| {nk} ({kr.get('preconditioner') or '-'}) | {100.0 * (nk - ne) / ne:+.0f} % |")


def write_summary(out, path):
    import os
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(out[0].keys()) if out else ["lattice"])
        w.writeheader()
        w.writerows(out)
    os.replace(path + ".tmp", path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("csv", nargs="+")
    ap.add_argument("--min-dofs", type=float, default=1e4)
    ap.add_argument("-o", "--out", help="write the per-series summary as CSV")
    ap.add_argument("--plot", help="write a PNG of time and memory per DOF")
    a = ap.parse_args()
    rows = read(a.csv)
    out, curves = scaling_table(rows, a.min_dofs)
    newton_table(rows)
    if a.plot:
        plot(curves, a.plot)
    if a.out:
        write_summary(out, a.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
