#!/usr/bin/env python3
"""plot_dist.py - work per rank of a distributed Newton step (bench_dist.sh):
owned DOFs, owned stencils, instructions (callgrind) and bytes sent per step, per
rank, at each rank count, one group of bars per case.

    plot_dist.py dist.csv dist_instructions.csv -o dist.png
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("csv")
    ap.add_argument("instructions")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()
    rows = list(csv.DictReader(open(a.csv)))
    ins = {}
    for r in csv.DictReader(open(a.instructions)):
        if r["instructions"]:
            ins[(r["case"], int(r["ranks"]), int(r["rank"]))] = (
                float(r["instructions"]) - float(r.get("mpi_instructions") or 0))
    if not rows:
        sys.exit("plot_dist: no rows")
    cases = sorted({r["case"] for r in rows}, key=lambda c: int(c.rsplit("-", 1)[-1])
                   if c.rsplit("-", 1)[-1].isdigit() else 0)
    metrics = [("owned_dofs", "owned DOFs"), ("owned_stencils", "owned stencils"),
               ("instructions", "instructions per step outside MPI"),
               ("bytes_per_step", "bytes sent per step")]
    fig, axes = plt.subplots(1, len(metrics), figsize=(4.2 * len(metrics), 3.8))
    for ax, (key, title) in zip(axes, metrics):
        labels, values = [], []
        for c in cases:
            for r in rows:
                if r["case"] != c:
                    continue
                np_, rk = int(r["ranks"]), int(r["rank"])
                v = ins.get((c, np_, rk)) if key == "instructions" else float(r[key])
                labels.append(f"{c.rsplit('-', 1)[-1]}: {np_}r/#{rk}")
                values.append(v if v is not None else 0.0)
        ax.bar(range(len(values)), values, color=["C0" if "1r" in l else "C1" for l in labels])
        ax.set_xticks(range(len(values)))
        ax.set_xticklabels(labels, rotation=60, fontsize=7)
        ax.set_title(title, fontsize=9)
        ax.set_yscale("log")
    fig.suptitle("distributed Newton step, work per rank (cells: ranks/rank)", fontsize=10)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)


if __name__ == "__main__":
    main()
