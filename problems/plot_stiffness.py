#!/usr/bin/env python3
"""Polar plot of the directional Young's modulus from a `rodnet homogenize` RESULT.json.

Usage: plot_stiffness.py RESULT.json OUT.png   (docs/homogenization.md)
rodnet runs it on a temporary name and renames the PNG when it is complete
(rn_cli_run_script_to), and removes it on a signal; run by hand it writes OUT.png."""
import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.stderr.write("usage: plot_stiffness.py RESULT.json OUT.png\n")
        return 2
    with open(sys.argv[1]) as f:
        r = json.load(f)
    lo, hi, step = r["directional_modulus_angles_deg"]
    th = [math.radians(a) for a in range(lo, hi + 1, step)]
    fig = plt.figure(figsize=(5, 5))
    ax = fig.add_subplot(111, projection="polar")
    planes = [("xy", "in the xy plane")]
    if "directional_modulus_xz" in r:
        planes.append(("xz", "in the xz plane"))
    for key, label in planes:
        ax.plot(th, r["directional_modulus_" + key], label="E(θ) " + label)
    c = r["constants"]
    ax.set_title("directional Young's modulus (%s)\nE1 = %.4g, E2 = %.4g, nu12 = %.4f, "
                 "rel. density %.4g" % (r["units"].split(" (")[0], c["E1"], c["E2"],
                                        c["nu12"], r["relative_density"]), fontsize=9)
    ax.legend(loc="lower right", fontsize=8)
    fig.savefig(sys.argv[2], dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
