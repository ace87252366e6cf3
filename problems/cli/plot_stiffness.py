#!/usr/bin/env python3
"""Polar plot of the directional Young's modulus from a `rodnet homogenize` RESULT.json.

Usage: plot_stiffness.py RESULT.json OUT.png   (docs/homogenization.md)
rodnet runs it on a temporary name and renames the PNG when it is complete
(rn_cli_run_script_to), and removes it on a signal; run by hand it writes OUT.png.
The radial axis runs from 0 to 15 % above the largest modulus, so that a curve
of constant radius (an isotropic cell) lies inside the frame, not on it."""
import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

RADIAL_MARGIN = 1.15  # the frame circle at this times the largest modulus


def figure(r):
    """The figure and its polar axes for the RESULT.json dictionary r."""
    lo, hi, step = r["directional_modulus_angles_deg"]
    th = [math.radians(a) for a in range(lo, hi + 1, step)]
    fig = plt.figure(figsize=(5.5, 5.5))
    ax = fig.add_subplot(111, projection="polar")
    planes = [("xy", "in the xy plane", "-")]
    if "directional_modulus_xz" in r:
        planes.append(("xz", "in the xz plane", "--"))
    top = 0.0
    for key, label, style in planes:
        E = r["directional_modulus_" + key]
        top = max(top, max(E))
        ax.plot(th, E, style, lw=2, label="E(θ) " + label)
    ax.set_ylim(0.0, RADIAL_MARGIN * top if top > 0 else 1.0)
    ax.set_rlabel_position(100)  # radial labels off the 0 and 90 degree axes
    ax.tick_params(axis="y", labelsize=7)
    c = r["constants"]
    ax.set_title("directional Young's modulus (%s)\nE1 = %.4g, E2 = %.4g, nu12 = %.4f, "
                 "rel. density %.4g" % (r["units"].split(" (")[0], c["E1"], c["E2"],
                                        c["nu12"], r["relative_density"]), fontsize=9)
    ax.legend(loc="upper right", bbox_to_anchor=(1.1, 1.08), fontsize=8)
    fig.tight_layout()
    return fig, ax


def main():
    if len(sys.argv) != 3:
        sys.stderr.write("usage: plot_stiffness.py RESULT.json OUT.png\n")
        return 2
    with open(sys.argv[1]) as f:
        r = json.load(f)
    fig, _ = figure(r)
    fig.savefig(sys.argv[2], dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
