#!/usr/bin/env python3
"""Relative-density sweep of the periodic regular honeycomb (docs/homogenization.md):
rodnet generate honeycomb --periodic --relative-density RHO, rodnet homogenize, for
N densities; writes CSV (rho, E1, nu12, the closed forms) and a PNG of E and nu against
relative density with the frame closed forms (bending + stretching) and Gibson &
Ashby's bending-only limit on the same axes.

Usage: homog_sweep.py RODNET OUT.csv OUT.png [N] [EDGES]"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def closed_form(rho):
    """E (force per length, cell size 1, E_s = 1) and nu of the honeycomb with
    square t x t struts at relative density rho = 2 t / (sqrt(3) l)."""
    l = 1.0 / math.sqrt(3.0)
    t = math.sqrt(3.0) * rho * l / 2.0
    EA, EI = t * t, t ** 4 / 12.0
    s = EI / (EA * l * l)
    E = 16.0 * math.sqrt(3.0) * EI / l ** 3 / (1.0 + 36.0 * s)
    nu = (1.0 - 12.0 * s) / (1.0 + 36.0 * s)
    E_ga = 16.0 * math.sqrt(3.0) * EI / l ** 3  # bending only (Gibson & Ashby)
    return E, nu, E_ga


def main():
    rodnet, out_csv, out_png = sys.argv[1:4]
    n = int(sys.argv[4]) if len(sys.argv) > 4 else 20
    edges = sys.argv[5] if len(sys.argv) > 5 else "16"
    rhos = [0.01 * (30.0 ** (k / (n - 1))) for k in range(n)]  # 0.01 .. 0.3
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for k, rho in enumerate(rhos):
            scene, res = os.path.join(d, "hc.json"), os.path.join(d, "hc_result.json")
            subprocess.run([rodnet, "generate", "honeycomb", "--periodic", "--joint-model",
                            "rigid", "--edges-per-rod", edges, "--relative-density",
                            "%.17g" % rho, "-q", "-o", scene], check=True)
            subprocess.run([rodnet, "homogenize", scene, "-o", res, "-q"], check=True)
            r = json.load(open(res))
            E, nu, E_ga = closed_form(rho)
            c = r["constants"]
            rows.append([r["relative_density"], c["E1"], c["nu12"], E, nu, E_ga, r["time_s"]])
            sys.stderr.write("\r[%2d/%d] rho = %.4f" % (k + 1, n, rho))
    sys.stderr.write("\n")
    tmp = out_csv + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["relative_density", "E1", "nu12", "E_closed_form", "nu_closed_form",
                    "E_bending_only", "time_s"])
        w.writerows(rows)
    os.replace(tmp, out_csv)
    rho = [r[0] for r in rows]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    a1.loglog(rho, [r[1] for r in rows], "o", label="rodnet homogenize (%s edges/member)" % edges)
    a1.loglog(rho, [r[3] for r in rows], "-", label="frame closed form (bending + stretching)")
    a1.loglog(rho, [r[5] for r in rows], "--", label="bending only (Gibson & Ashby)")
    a1.set_xlabel("relative density")
    a1.set_ylabel("E (force per length, cell size 1, E_s = 1)")
    a1.legend(fontsize=8)
    a2.semilogx(rho, [r[2] for r in rows], "o", label="rodnet homogenize")
    a2.semilogx(rho, [r[4] for r in rows], "-", label="(1 - 12 s)/(1 + 36 s)")
    a2.axhline(1.0, ls="--", color="gray", label="bending only: 1")
    a2.set_xlabel("relative density")
    a2.set_ylabel("nu12")
    a2.legend(fontsize=8)
    fig.suptitle("regular honeycomb, rigid joints, square struts")
    fig.tight_layout()
    tmp = out_png + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, out_png)
    print("wrote %s and %s (%d points)" % (out_csv, out_png, len(rows)))


if __name__ == "__main__":
    main()
