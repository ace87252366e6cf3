#!/usr/bin/env python3
"""Plot the start-up and I/O benchmarks (bench_startup.py, bench_io) into a PNG.

    python3 benchmarks/plot_startup_io.py results/startup.csv -o results/startup.png
    python3 benchmarks/plot_startup_io.py results/io.csv -o results/io.png

startup: per case and size, the median whole-process time split into the solve
(time_s) and the rest (start-up, reading, writing), with the minimum of the rest
marked; several CSVs (e.g. before and after a change) are drawn side by side.
io: median time of each step (generate, read, solve, write_json, write_vtk)
against the number of vertices, log-log, with 1 us per vertex as a guide.
The title carries the commit and compiler recorded in the CSV.
"""
import argparse
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import bench_csv  # noqa: E402


def read_rows(path):
    return bench_csv.read_rows(path, "plot_startup_io.py")


def plot_startup(tables, ax):
    labels, rest, rest_min, solve = [], [], [], []
    for rows in tables:
        for r in rows:
            size = int(r["size"])
            what = r["case"] if size == 0 else f"{r['case']} {size}"
            labels.append(f"{what}\n{r['commit'][:12]}")
            rest.append(1e3 * float(r["median"]))
            rest_min.append(1e3 * float(r["min"]))
            solve.append(1e3 * float(r.get("solve_median") or 0.0))
    x = range(len(labels))
    ax.bar(x, rest, color="C0", label="start-up + read + write (median)")
    ax.bar(x, solve, bottom=rest, color="C1", alpha=0.6, label="solve: time_s (median)")
    ax.plot(list(x), rest_min, "k_", markersize=18, label="start-up + read + write (min)")
    for i, v in enumerate(rest):
        ax.annotate(f"{v:.0f} ms", (i, v), textcoords="offset points", xytext=(0, 3),
                    ha="center", fontsize="small")
    ax.set_xticks(list(x))
    ax.set_xticklabels(labels, fontsize="small")
    ax.set_ylabel("whole process, wall time [ms]")
    ax.grid(True, axis="y", alpha=0.3)
    ax.legend(fontsize="small")


def plot_io(rows, ax):
    series = defaultdict(list)
    for r in rows:
        series[r["case"]].append((int(r["size"]), float(r["median"]), float(r["min"])))
    order = ["generate", "read", "solve", "write_json", "write_vtk"]
    sizes = sorted({int(r["size"]) for r in rows})
    for i, step in enumerate(sorted(series, key=lambda s: order.index(s)
                                    if s in order else len(order))):
        pts = sorted(series[step])
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "-o", color=f"C{i}", label=step)
    ax.plot(sizes, [1e-6 * n for n in sizes], "k:", label="1 us per vertex")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("vertices")
    ax.set_ylabel("median time [s]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small")


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("csv", nargs="+", help="CSV of bench_startup.py or bench_io (one kind)")
    p.add_argument("-o", "--output", help="PNG to write (default: first CSV with .png)")
    args = p.parse_args()
    tables = [read_rows(path) for path in args.csv]
    kinds = {r["bench"] for rows in tables for r in rows}
    if len(kinds) != 1:
        sys.exit(f"plot_startup_io.py: one benchmark kind per plot, found {sorted(kinds)}")
    kind = kinds.pop()
    if kind == "startup":
        fig, ax = plt.subplots(figsize=(2.2 + 1.6 * sum(len(t) for t in tables), 5))
        plot_startup(tables, ax)
    elif kind == "io":
        if len(tables) != 1:
            sys.exit("plot_startup_io.py: one io CSV per plot")
        fig, ax = plt.subplots(figsize=(8, 5.5))
        plot_io(tables[0], ax)
    else:
        sys.exit(f"plot_startup_io.py: unknown benchmark '{kind}'")
    fig.suptitle(bench_csv.title(tables[-1], kind), fontsize="medium")
    fig.tight_layout()
    out = args.output or (args.csv[0].rsplit(".", 1)[0] + ".png")
    fig.savefig(out, dpi=120)
    print(f"plot_startup_io.py: wrote {out}")


if __name__ == "__main__":
    main()
