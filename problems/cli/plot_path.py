#!/usr/bin/env python3
"""plot_path.py PATH.csv PATH.png: the equilibrium path that `rodnet path` wrote.

Left: the conjugate force (displacement control) or the load factor (load control)
against the displacement of the controlled (monitored) coordinate, stable parts
solid, unstable parts dashed, limit points and bifurcations marked.  Right: the
lowest eigenvalue of the constrained Hessian along the arclength, on a symmetric
log scale with one labelled tick per few decades (at most 4 on a side, so that
the labels do not overlap).  The PNG is written to a temporary file and renamed
(completely or not at all).
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FixedLocator, NullLocator  # noqa: E402

MAX_DECADE_TICKS = 4  # labelled ticks on each side of zero at most


def symlog_ticks(values, linthresh):
    """Tick positions and labels for a symlog axis over values: 0 and powers of
    ten from linthresh to the largest magnitude, every k-th decade so that each
    side has at most MAX_DECADE_TICKS."""
    finite = [v for v in values if v == v and abs(v) != float("inf")]
    top = max([abs(v) for v in finite] + [linthresh])
    e0, e1 = math.ceil(math.log10(linthresh)), math.floor(math.log10(top))
    step = max(1, math.ceil((e1 - e0 + 1) / MAX_DECADE_TICKS))
    exps = list(range(e1, e0 - 1, -step))[::-1]
    ticks, labels = [0.0], ["0"]
    for sign, present in ((1, any(v > 0 for v in finite)), (-1, any(v < 0 for v in finite))):
        if not present:
            continue
        for e in exps:
            ticks.append(sign * 10.0 ** e)
            labels.append("$%s10^{%d}$" % ("-" if sign < 0 else "", e))
    order = sorted(range(len(ticks)), key=lambda i: ticks[i])
    return [ticks[i] for i in order], [labels[i] for i in order]


def figure(rows, title=""):
    """The figure and its two axes (path, eigenvalue) for the CSV rows."""
    pts = [r for r in rows if r["event"] in ("point", "branch-switch")]
    loads = [float(r["load_factor"]) for r in pts]
    # displacement control: the load factor is constant; plot the force instead
    force_plot = max(loads) - min(loads) < 1e-14 * max(1.0, abs(max(loads)))
    yname = "force" if force_plot else "load_factor"
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 5))
    for a, b in zip(pts[:-1], pts[1:]):
        unstable = a["stability"] == "unstable" or b["stability"] == "unstable"
        ax.plot([float(a["displacement"]), float(b["displacement"])],
                [float(a[yname]), float(b[yname])],
                "--" if unstable else "-", color="tab:red" if unstable else "tab:blue")
    marks = {"limit": ("o", "limit point"), "bifurcation": ("s", "bifurcation"),
             "branch-switch": ("^", "branch switch")}
    for ev, (m, label) in marks.items():
        sel = [r for r in rows if r["event"] == ev]
        if sel:
            ax.plot([float(r["displacement"]) for r in sel], [float(r[yname]) for r in sel],
                    m, color="k", mfc="none", label=label)
    ax.plot([], [], "-", color="tab:blue", label="stable")
    ax.plot([], [], "--", color="tab:red", label="unstable")
    ax.set_xlabel("displacement of the %s coordinate" %
                  ("controlled" if force_plot else "monitored"))
    ax.set_ylabel("conjugate force" if force_plot else "load factor")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    s = [float(r["arclength"]) for r in pts]
    lam = [float(r["lowest_eigenvalue"]) for r in pts]
    known = [v for v in lam if v == v]
    ax2.plot(s, lam, ".-", color="tab:green")
    ax2.axhline(0.0, color="k", lw=0.8)
    ax2.set_xlabel("arclength")
    ax2.set_ylabel("lowest eigenvalue of the constrained Hessian")
    if known:
        linthresh = max(1e-12, 1e-6 * max(abs(v) for v in known))
        ax2.set_yscale("symlog", linthresh=linthresh)
        ticks, labels = symlog_ticks(known, linthresh)
        ax2.yaxis.set_major_locator(FixedLocator(ticks))
        ax2.yaxis.set_minor_locator(NullLocator())
        ax2.set_yticklabels(labels)
    ax2.grid(True, alpha=0.3)
    if title:
        fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig, (ax, ax2)


def main(argv):
    if len(argv) != 3:
        sys.stderr.write("usage: plot_path.py PATH.csv PATH.png\n")
        return 2
    with open(argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.stderr.write("plot_path.py: %s has no points\n" % argv[1])
        return 1
    fig, _ = figure(rows, os.path.basename(argv[1]))
    tmp = argv[2] + ".tmp.png"
    fig.savefig(tmp, dpi=120)
    os.replace(tmp, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
