#!/usr/bin/env python3
"""Plot of a `rodnet sweep` CSV (docs/homogenization.md, "Sweeps"): E1 and nu12
against relative density, one series per lattice and joint model (mean over the
seeds), with the frame closed forms of the rigid-jointed regular honeycomb
(bending plus stretching; Gibson & Ashby's bending-only E) on the same axes.

Usage: plot_sweep.py SWEEP.csv OUT.png"""
import csv
import math
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def honeycomb_closed_form(rho, E_s=1.0):
    """E (force per length, cell size 1) and nu of the honeycomb with square
    t x t struts at relative density rho = 2 t / (sqrt(3) l) (VALIDATION.md 6.2)."""
    l = 1.0 / math.sqrt(3.0)
    t = math.sqrt(3.0) * rho * l / 2.0
    EA, EI = E_s * t * t, E_s * t ** 4 / 12.0
    s = EI / (EA * l * l)
    E = 16.0 * math.sqrt(3.0) * EI / l ** 3 / (1.0 + 36.0 * s)
    nu = (1.0 - 12.0 * s) / (1.0 + 36.0 * s)
    return E, nu, 16.0 * math.sqrt(3.0) * EI / l ** 3


def main():
    src, png = sys.argv[1:3]
    series = defaultdict(lambda: defaultdict(list))
    with open(src, newline="") as f:
        for row in csv.DictReader(f):
            key = (row["lattice"], row["joint_model"])
            rho = float(row["relative_density"])
            series[key][round(rho, 12)].append((float(row["E1"]), float(row["nu12"])))
    fig, (ax_e, ax_nu) = plt.subplots(1, 2, figsize=(11, 4.5))
    for (lat, jm), pts in sorted(series.items()):
        rhos = sorted(pts)
        E = [sum(p[0] for p in pts[r]) / len(pts[r]) for r in rhos]
        nu = [sum(p[1] for p in pts[r]) / len(pts[r]) for r in rhos]
        ax_e.loglog(rhos, E, "o", label=f"rodnet: {lat}, {jm} joints")
        ax_nu.semilogx(rhos, nu, "o", label=f"rodnet: {lat}, {jm} joints")
        if lat == "honeycomb" and jm == "rigid" and len(rhos) > 1:
            fine = [rhos[0] * (rhos[-1] / rhos[0]) ** (k / 200) for k in range(201)]
            cf = [honeycomb_closed_form(r) for r in fine]
            ax_e.loglog(fine, [c[0] for c in cf], "-", label="frame theory (bending + stretching)")
            ax_e.loglog(fine, [c[2] for c in cf], "--", label="Gibson & Ashby (bending only)")
            ax_nu.semilogx(fine, [c[1] for c in cf], "-", label="frame theory")
    ax_e.set_xlabel("relative density")
    ax_e.set_ylabel("E1 (force per length, E_s = 1, cell size 1)")
    ax_nu.set_xlabel("relative density")
    ax_nu.set_ylabel("nu12")
    for ax in (ax_e, ax_nu):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    main()
