#!/usr/bin/env python3
"""plot_path.py PATH.csv PATH.png: the equilibrium path that `rodnet path` wrote.

Left: the conjugate force (displacement control) or the load factor (load control)
against the displacement of the controlled (monitored) coordinate, stable parts
solid, unstable parts dashed, limit points and bifurcations marked.  Right: the
lowest eigenvalue of the constrained Hessian along the arclength.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    if len(argv) != 3:
        sys.stderr.write("usage: plot_path.py PATH.csv PATH.png\n")
        return 2
    with open(argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.stderr.write("plot_path.py: %s has no points\n" % argv[1])
        return 1
    pts = [r for r in rows if r["event"] in ("point", "branch-switch")]
    loads = [float(r["load_factor"]) for r in pts]
    # displacement control: the load factor is constant; plot the force instead
    force_plot = max(loads) - min(loads) < 1e-14 * max(1.0, abs(max(loads)))
    yname = "force" if force_plot else "load_factor"
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
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
    ax2.plot(s, lam, ".-", color="tab:green")
    ax2.axhline(0.0, color="k", lw=0.8)
    ax2.set_xlabel("arclength")
    ax2.set_ylabel("lowest eigenvalue of the constrained Hessian")
    ax2.set_yscale("symlog", linthresh=max(1e-12, 1e-6 * max(abs(v) for v in lam if v == v)))
    ax2.grid(True, alpha=0.3)
    fig.suptitle(argv[1])
    fig.tight_layout()
    fig.savefig(argv[2], dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
