#!/usr/bin/env python3
"""plot_sweep_throughput.py - bench_sweep CSV to PNG: points per second of the whole `rodnet
sweep` against the ranks, one line per case, with the ideal (linear) speed-up from
the 1-rank point dashed (log scale: the cases differ by orders of magnitude).  The title carries the commit and compiler.

    plot_sweep_throughput.py benchmarks/results/sweep.csv -o benchmarks/results/sweep.png
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_csv  # noqa: E402


def main():
    rows, output = bench_csv.plot_rows(__doc__, "sweep", "plot_sweep_throughput")
    cases = []
    for r in rows:
        if r["case"] not in cases:
            cases.append(r["case"])
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    colours = ["tab:blue", "tab:orange", "tab:green", "tab:red"]
    for i, c in enumerate(cases):
        sel = sorted((int(r["ranks"]), float(r["points_per_s"]), r) for r in rows
                     if r["case"] == c)
        n = [s[0] for s in sel]
        pps = [s[1] for s in sel]
        col = colours[i % len(colours)]
        ax.plot(n, pps, "o-", color=col, label="%s (%s points)" % (c, sel[0][2]["size"]))
        if n[0] == 1:
            ax.plot(n, [pps[0] * k for k in n], "--", color=col, alpha=0.5,
                    label="%s, linear from 1 rank" % c)
        for k, p, r in sel:
            ax.annotate("%.2f/s\n%s s" % (p, r["median"]), (k, p),
                        textcoords="offset points", xytext=(6, -4), fontsize=8)
    ax.set_xlabel("MPI ranks")
    ax.set_ylabel("points per second (whole command, median)")
    ax.set_xticks(sorted({int(r["ranks"]) for r in rows}))
    ax.set_yscale("log")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="center left")
    ax.set_title("rodnet sweep throughput - commit %s, %s" % (rows[0]["commit"],
                                                              rows[0]["compiler"]),
                 fontsize=9)
    fig.tight_layout()
    bench_csv.save(fig, output)


if __name__ == "__main__":
    main()
