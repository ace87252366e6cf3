#!/usr/bin/env python3
"""Plot of a `rodnet sweep` CSV (docs/homogenization.md, "Sweeps"): E1 and nu12
against relative density, one series per lattice and joint model, with the frame
closed forms of the rigid-jointed regular honeycomb (bending plus stretching;
Gibson & Ashby's bending-only E) on the same axes.  A series with several
imperfection seeds shows their mean, the bars their range, and says so in the
legend ("mean of N seeds").  A series has one colour in both panels.

Usage: plot_sweep.py SWEEP.csv OUT.png
The PNG is written to a temporary file and renamed (completely or not at all)."""
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

CLOSED_FORM_COLOUR = "0.2"


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


def read(src):
    """{(lattice, joint_model): {rho: [(E1, nu12, seed), ...]}} from the CSV."""
    series = defaultdict(lambda: defaultdict(list))
    with open(src, newline="") as f:
        for row in csv.DictReader(f):
            key = (row["lattice"], row["joint_model"])
            rho = float(row["relative_density"])
            series[key][round(rho, 12)].append(
                (float(row["E1"]), float(row["nu12"]), row["seed"]))
    return series


def series_label(lat, jm, pts):
    seeds = {p[2] for v in pts.values() for p in v}
    label = f"rodnet: {lat}, {jm} joints"
    if len(seeds) > 1:
        label += f" (mean of {len(seeds)} seeds, bars: range)"
    return label


def figure(series):
    """The figure and its two axes (E1, nu12) for the series of read()."""
    fig, (ax_e, ax_nu) = plt.subplots(1, 2, figsize=(12, 5))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for n, ((lat, jm), pts) in enumerate(sorted(series.items())):
        colour = colours[n % len(colours)]
        rhos = sorted(pts)
        label = series_label(lat, jm, pts)
        for ax, k in ((ax_e, 0), (ax_nu, 1)):
            mean = [sum(p[k] for p in pts[r]) / len(pts[r]) for r in rhos]
            lo = [max(0.0, m - min(p[k] for p in pts[r])) for m, r in zip(mean, rhos)]
            hi = [max(0.0, max(p[k] for p in pts[r]) - m) for m, r in zip(mean, rhos)]
            if any(lo) or any(hi):
                ax.errorbar(rhos, mean, yerr=[lo, hi], fmt="o", color=colour, ms=4,
                            capsize=2, label=label)
            else:
                ax.plot(rhos, mean, "o", color=colour, ms=4, label=label)
        if lat == "honeycomb" and jm == "rigid" and len(rhos) > 1:
            fine = [rhos[0] * (rhos[-1] / rhos[0]) ** (k / 200) for k in range(201)]
            cf = [honeycomb_closed_form(r) for r in fine]
            ax_e.plot(fine, [c[0] for c in cf], "-", color=CLOSED_FORM_COLOUR, lw=1,
                      label="frame theory, rigid honeycomb (bending + stretching)")
            ax_e.plot(fine, [c[2] for c in cf], ":", color=CLOSED_FORM_COLOUR, lw=1,
                      label="Gibson & Ashby (bending only)")
            ax_nu.plot(fine, [c[1] for c in cf], "-", color=CLOSED_FORM_COLOUR, lw=1,
                       label="frame theory, rigid honeycomb")
    ax_e.set_xscale("log")
    ax_e.set_yscale("log")
    ax_nu.set_xscale("log")
    ax_e.set_xlabel("relative density")
    ax_e.set_ylabel("E1 (force per length, E_s = 1, cell size 1)")
    ax_nu.set_xlabel("relative density")
    ax_nu.set_ylabel("nu12")
    ax_e.set_title("effective Young's modulus E1", fontsize=10)
    ax_nu.set_title("effective Poisson's ratio nu12", fontsize=10)
    for ax in (ax_e, ax_nu):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    return fig, (ax_e, ax_nu)


def main():
    if len(sys.argv) != 3:
        sys.stderr.write("usage: plot_sweep.py SWEEP.csv OUT.png\n")
        return 2
    src, png = sys.argv[1:3]
    fig, _ = figure(read(src))
    tmp = png + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
