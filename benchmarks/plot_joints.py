#!/usr/bin/env python3
"""plot_joints.py - bench_joints CSV to PNG: median nanoseconds per joint against
the valence, one panel per joint model (rigid, elastic), one colour per operation
(energy, energy + gradient, Hessian-vector product, Hessian block), solid lines for
the closed forms and dashed for the jets; log scale in time.  The title carries
the commit and compiler recorded in the CSV.

    plot_joints.py benchmarks/results/joints.csv -o benchmarks/results/joints.png
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OPS = [("energy", "energy"), ("grad", "energy + gradient"), ("hvp", "HVP"),
       ("hess", "Hessian block")]
COLOURS = {"energy": "tab:blue", "grad": "tab:orange", "hvp": "tab:green",
           "hess": "tab:red"}


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("csv")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()
    with open(a.csv, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r.get("bench") == "joints"]
    if not rows:
        sys.exit(f"plot_joints: {a.csv} has no bench_joints rows")
    models = [m for m in ("rigid", "elastic") if any(r["model"] == m for r in rows)]
    fig, axes = plt.subplots(1, len(models), figsize=(6.0 * len(models), 4.4),
                             squeeze=False)
    for ax, model in zip(axes[0], models):
        for op, label in OPS:
            for impl, style in (("closed", "-"), ("jets", "--")):
                pts = sorted((int(r["size"]), float(r["ns_median"])) for r in rows
                             if r["model"] == model and r["op"] == op and
                             r["impl"] == impl)
                if not pts:
                    continue
                ax.plot([p[0] for p in pts], [p[1] for p in pts], style, marker="o",
                        markersize=3, color=COLOURS[op],
                        label=f"{label}, {'closed form' if impl == 'closed' else 'jets'}")
        ax.set_yscale("log")
        ax.set_xlabel("valence (rod ends at the joint)")
        ax.set_ylabel("ns per joint (median)")
        ax.set_title(f"{model} joints")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    r0 = rows[0]
    fig.suptitle(f"joint kernels, closed forms vs jets ({r0['commit']}, "
                 f"{r0['compiler']})", fontsize=10)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)


if __name__ == "__main__":
    main()
