#!/usr/bin/env python3
"""plot_periodic_dist.py - bench_periodic_dist CSV to PNG: seconds of the whole command
against the supercell's DOFs, one panel per step in the CSV (homogenize, solve,
path), one line per lattice and rank count (log-log), and the generate time in the
first panel (dotted).  The
title carries the commit and compiler.

    plot_periodic_dist.py benchmarks/results/periodic_dist.csv \\
        -o benchmarks/results/periodic_dist.png
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_csv  # noqa: E402


def family(case):
    """The lattice of a case name (its letters: hc, octet)."""
    return case.rstrip("0123456789")


def main():
    rows, output = bench_csv.plot_rows(__doc__, "periodic", "plot_periodic_dist")
    steps = [s for s in ("homogenize", "solve", "path") if any(r["step"] == s for r in rows)]
    fig, axes = plt.subplots(1, len(steps), figsize=(5 * len(steps), 4.2), squeeze=False)
    axes = axes[0]
    colours = {1: "tab:blue", 2: "tab:orange", 3: "tab:green", 4: "tab:red"}
    markers = {"hc": "o", "octet": "^", "dhc": "D"}
    names = {"hc": "honeycomb", "octet": "octet", "dhc": "disordered honeycomb"}
    for ax, step in zip(axes, steps):
        ranks = sorted({int(r["ranks"]) for r in rows if r["step"] == step})
        for fam in sorted({family(r["case"]) for r in rows}):
            for n in ranks:
                sel = sorted((int(r["size"]), float(r["median"]), r["case"]) for r in rows
                             if r["step"] == step and int(r["ranks"]) == n
                             and family(r["case"]) == fam)
                if not sel:
                    continue
                ax.plot([q[0] for q in sel], [q[1] for q in sel],
                        "-" + markers.get(fam, "s"), color=colours.get(n, "k"),
                        label="%s, %d rank%s" % (names.get(fam, fam), n,
                                                 "s" if n > 1 else ""))
                for size, t, case in sel:
                    ax.annotate("%s %.2f s" % (case, t), (size, t),
                                textcoords="offset points",
                                xytext=(5, 4) if n == 1 else (-62, -3), fontsize=7)
        if step == steps[0]:
            sel = sorted((int(r["size"]), float(r["median"])) for r in rows
                         if r["step"] == "generate")
            ax.plot([s[0] for s in sel], [s[1] for s in sel], "s:", color="tab:gray",
                    label="generate (1 process)")
        sizes = [int(r["size"]) for r in rows]
        ax.set_xscale("log")
        ax.set_xlim(min(sizes) / 2.5, max(sizes) * 2.5)  # room for the labels
        ax.set_yscale("log")
        ax.set_xlabel("reduced DOFs of the supercell")
        ax.set_ylabel("seconds, whole command (median)")
        ax.set_title("rodnet %s" % ("homogenize --path" if step == "path" else step),
                     fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="lower right")
    fig.suptitle("periodic supercells on 1 and 2 ranks - commit %s, %s"
                 % (rows[0]["commit"], rows[0]["compiler"]), fontsize=9)
    fig.tight_layout()
    bench_csv.save(fig, output)


if __name__ == "__main__":
    main()
