#!/usr/bin/env python3
"""Plot a rodnet benchmark CSV (from bench_kernels, bench_solve or bench_lattice) into a PNG.

    python3 benchmarks/plot.py results/kernels.csv -o results/kernels.png

kernels: median time per vertex against the number of vertices, one line per
(shape, operation), log-log (with --before CSV, an earlier run in grey), and the
achieved fraction of one core's peak flop rate with the counted work per vertex.  solve: median solve time (left) and Newton and
Krylov iterations (right) against the number of vertices.  lattice: median rn_solve time
(left) and Newton iterations and factorisations (right) against the free DOFs, one line per
(lattice, joint model).  The title carries the commit and compiler recorded in the CSV.
"""
import argparse
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import bench_csv  # noqa: E402


def read_rows(path):
    return bench_csv.read_rows(path, "plot.py")


def plot_kernels(rows, axes, before=None):
    """Left: median time per vertex (ns) against vertices, one line per (shape,
    operation), and those of an earlier run (--before) thin and grey.  Right (if
    the CSV has the counted work): achieved fraction of one core's peak flop
    rate, with the counted flops and modelled bytes per vertex in the legend."""
    ax_t, ax_p = axes
    ops = sorted({r["op"] for r in rows})
    colors = {op: f"C{i}" for i, op in enumerate(ops)}

    def series(rs, key):
        out = defaultdict(list)
        for r in rs:
            if key in r and r[key] not in ("", None):
                out[(r["case"], r["op"])].append((int(r["size"]), float(r[key])))
        return out

    if before:
        for i, ((shape, op), pts) in enumerate(sorted(series(before, "median_per_vertex").items())):
            pts.sort()
            ax_t.plot([p[0] for p in pts], [1e9 * p[1] for p in pts], ":", color="grey",
                      lw=1, label=f"all, commit {before[0]['commit']}" if i == 0 else None)
    for (shape, op), pts in sorted(series(rows, "median_per_vertex").items(),
                                   key=lambda kv: (kv[0][1], kv[0][0])):
        pts.sort()
        style = "-" if shape == "straight" else "--"
        ax_t.plot([p[0] for p in pts], [1e9 * p[1] for p in pts], style, marker="o",
                  color=colors[op], label=f"{op} ({shape})")
    ax_t.set_ylabel("median time per vertex [ns]")
    frac = series(rows, "peak_fraction")
    if frac:
        work = {(r["op"]): (float(r["flops_per_vertex"]), float(r["bytes_per_vertex"]))
                for r in rows if "flops_per_vertex" in r}
        for (shape, op), pts in sorted(frac.items(), key=lambda kv: (kv[0][1], kv[0][0])):
            pts.sort()
            style = "-" if shape == "straight" else "--"
            fl, by = work[op]
            ax_p.plot([p[0] for p in pts], [100.0 * p[1] for p in pts], style, marker="o",
                      color=colors[op], label=f"{op} ({shape}): {fl:.0f} flops, {by:.0f} B")
        ax_p.set_ylabel("fraction of one core's peak flop rate [%]")
    else:
        ax_p.set_visible(False)
    for ax in axes:
        ax.set_xscale("log")
        ax.set_xlabel("vertices")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize="x-small")
    ax_t.set_yscale("log")


def style_axes(axes, xlabel, ylog):
    for ax in axes:
        ax.set_xscale("log")
        if ylog:
            ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize="small")


def plot_solve(rows, axes):
    by_solver = defaultdict(list)
    for r in rows:
        by_solver[r["case"]].append((int(r["size"]), float(r["median"]),
                                     int(r["newton_iterations"]),
                                     int(r["krylov_iterations"])))
    ax_t, ax_i = axes
    for i, (solver, pts) in enumerate(sorted(by_solver.items())):
        pts.sort()
        n = [p[0] for p in pts]
        color = f"C{i}"
        ax_t.plot(n, [p[1] for p in pts], "-o", color=color, label=solver)
        ax_i.plot(n, [p[2] for p in pts], "-s", color=color, label=f"Newton ({solver})")
        ax_i.plot(n, [p[3] for p in pts], ":^", color=color, label=f"Krylov ({solver})")
    style_axes(axes, "vertices", ylog=True)
    ax_t.set_ylabel("median solve time [s]")
    ax_i.set_ylabel("iterations (all load steps)")


def plot_lattice(rows, axes):
    series = defaultdict(list)
    for r in rows:
        series[(r["lattice"], r["joint_model"])].append(
            (int(r["size"]), float(r["median"]), int(r["newton_iterations"]),
             int(r["factorizations"]), int(r["cells"])))
    ax_t, ax_i = axes
    for i, ((lattice, model), pts) in enumerate(sorted(series.items())):
        pts.sort()
        n = [p[0] for p in pts]
        color = f"C{i}"
        label = f"{lattice}, {model} joints"
        ax_t.plot(n, [p[1] for p in pts], "-o", color=color, label=label)
        for p in pts:
            ax_t.annotate(f"{p[4]}", (p[0], p[1]), textcoords="offset points",
                          xytext=(4, -10), fontsize="x-small", color=color)
        ax_i.plot(n, [p[2] for p in pts], "-s", color=color, label=f"Newton ({label})")
        ax_i.plot(n, [p[3] for p in pts], ":^", color=color,
                  label=f"factorisations ({label})")
    style_axes(axes, "free DOFs", ylog=False)
    ax_t.set_yscale("log")
    ax_t.set_ylabel("median rn_solve time [s] (labels: cells per side)")
    ax_i.set_ylabel("count per solve")


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("csv", help="CSV written by bench_kernels, bench_solve or bench_lattice")
    p.add_argument("-o", "--output", help="PNG to write (default: CSV name with .png)")
    p.add_argument("--before", help="kernels: CSV of an earlier run, drawn in grey")
    args = p.parse_args()
    rows = read_rows(args.csv)
    kinds = {r["bench"] for r in rows}
    if len(kinds) != 1:
        sys.exit(f"plot.py: one benchmark per CSV, found {sorted(kinds)}")
    kind = kinds.pop()
    if kind == "kernels":
        fig, axes = plt.subplots(1, 2, figsize=(13, 5.5))
        plot_kernels(rows, axes, read_rows(args.before) if args.before else None)
    elif kind == "solve":
        fig, axes = plt.subplots(1, 2, figsize=(11, 5))
        plot_solve(rows, axes)
    elif kind == "lattice":
        fig, axes = plt.subplots(1, 2, figsize=(12, 5))
        plot_lattice(rows, axes)
    else:
        sys.exit(f"plot.py: unknown benchmark '{kind}'")
    fig.suptitle(bench_csv.title(rows, kind), fontsize="medium")
    fig.tight_layout()
    out = args.output or (args.csv.rsplit(".", 1)[0] + ".png")
    fig.savefig(out, dpi=120)
    print(f"plot.py: wrote {out}")


if __name__ == "__main__":
    main()
