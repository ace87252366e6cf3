#!/usr/bin/env python3
"""plot_bloch.py - bench_bloch CSV to PNG: the median time of the lowest Bloch
eigenvalue at one wave vector against the number of Bloch DOFs, dense (LAPACK
zheevr) and sparse (shift-invert Lanczos on the real form), log-log, with the
Lanczos steps of the sparse runs marked.  The title carries the commit and compiler.

    plot_bloch.py benchmarks/results/bloch.csv -o benchmarks/results/bloch.png
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_csv  # noqa: E402


def main():
    rows, output = bench_csv.plot_rows(__doc__, "bloch", "plot_bloch")
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for case, colour, label in (("dense", "tab:red", "dense (zheevr)"),
                                ("sparse", "tab:blue", "sparse (shift-invert Lanczos)")):
        pts = sorted((int(r["size"]), float(r["median"]), r["lanczos_steps"])
                     for r in rows if r["case"] == case)
        if not pts:
            continue
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "-o", color=colour,
                markersize=4, label=label)
        if case == "sparse":
            for n, t, steps in pts:
                ax.annotate(steps, (n, t), textcoords="offset points", xytext=(4, -10),
                            fontsize=7, color=colour)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("Bloch DOFs of the supercell")
    ax.set_ylabel("seconds per wave vector (median)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="upper left", fontsize=8)
    lat = rows[0].get("lattice", "")
    ax.set_title(f"lowest Bloch eigenvalue, {lat} supercells (numbers: Lanczos steps)\n"
                 + bench_csv.title(rows, "bench_bloch"), fontsize=8)
    fig.tight_layout()
    bench_csv.save(fig, output)


if __name__ == "__main__":
    main()
