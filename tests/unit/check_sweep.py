#!/usr/bin/env python3
"""Checks a `rodnet sweep` CSV of the rigid-jointed regular honeycomb against the
frame closed forms (VALIDATION.md 6.2; docs/homogenization.md "Sweeps"): every
point's E1 within 1 % (16 DER edges per member: the discretisation error is about
-0.8 %), nu12 within 2e-3, the expected number of points, and the PNG written.

Usage: check_sweep.py SWEEP.csv NPOINTS PNG"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "problems", "cli"))
from plot_sweep import honeycomb_closed_form  # noqa: E402


def main():
    src, npoints, png = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    rows = list(csv.DictReader(open(src, newline="")))
    ok = len(rows) == npoints
    print(f"{len(rows)} points (expected {npoints})")
    for r in rows:
        rho = float(r["relative_density"])
        E, nu, _ = honeycomb_closed_form(rho)
        dE = float(r["E1"]) / E - 1.0
        dnu = float(r["nu12"]) - nu
        good = abs(dE) < 1e-2 and abs(dnu) < 2e-3 and abs(rho / float(r["relative_density_target"]) - 1) < 1e-12
        print(f"rho {rho:.5f}: E1 {float(r['E1']):.6e} (closed form {E:.6e}, {dE:+.4%}), "
              f"nu12 {float(r['nu12']):.6f} ({nu:.6f}) {'ok' if good else 'FAILED'}")
        ok &= good
    ok &= os.path.getsize(png) > 10000
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
