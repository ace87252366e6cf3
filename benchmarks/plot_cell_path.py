#!/usr/bin/env python3
"""plot_cell_path.py - bench_cell_path CSV to PNG: the median wall time of the whole
`rodnet homogenize --path` per case, dense and sparse Bloch method side by side (log
scale), each case's target as a horizontal mark.  The title carries the commit and
compiler.

    plot_cell_path.py benchmarks/results/cell_path.csv -o benchmarks/results/cell_path.png
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_csv  # noqa: E402


def main():
    rows, output = bench_csv.plot_rows(__doc__, "cell_path", "plot_cell_path")
    cases = []
    for r in rows:
        if r["case"] not in cases:
            cases.append(r["case"])
    colours = {"dense": "tab:red", "sparse": "tab:blue"}
    fig, ax = plt.subplots(figsize=(7.0, 4.4))
    width = 0.38
    for i, c in enumerate(cases):
        for j, m in enumerate(("dense", "sparse")):
            sel = [r for r in rows if r["case"] == c and r["method"] == m]
            if not sel:
                continue
            t = float(sel[0]["median"])
            x = i + (j - 0.5) * width
            ax.bar(x, t, width, color=colours[m], label=m if i == 0 or m not in
                   [h.get_label() for h in ax.patches] else None)
            ax.annotate("%.2g s" % t, (x, t), ha="center", va="bottom", fontsize=8)
        tgt = [r["target_s"] for r in rows if r["case"] == c and r["target_s"]]
        if tgt:
            ax.hlines(float(tgt[0]), i - 0.45, i + 0.45, colors="k", linestyles="--",
                      label="target" if i == 0 else None)
    handles, labels = ax.get_legend_handles_labels()
    seen = {}
    for h, l in zip(handles, labels):
        if l and l not in seen:
            seen[l] = h
    ax.legend(seen.values(), seen.keys(), loc="upper left")
    ax.set_xticks(range(len(cases)))
    ax.set_xticklabels(["%s\n%s DOFs" % (c, [r["size"] for r in rows if r["case"] == c][0])
                        for c in cases], fontsize=8)
    ax.set_yscale("log")
    ax.set_ylabel("whole command, median (s)")
    ax.set_title(bench_csv.title(rows, "homogenize --path (Bloch method)"), fontsize=9)
    ax.grid(True, axis="y", which="both", alpha=0.3)
    fig.tight_layout()
    bench_csv.save(fig, output)


if __name__ == "__main__":
    main()
