#!/usr/bin/env python3
"""Checks a `rodnet homogenize` RESULT.json of the periodic regular honeycomb
(`rodnet generate honeycomb --periodic --joint-model rigid --edges-per-rod 16
--slenderness T`, square t x t struts, E_s = 1): the contract keys, a symmetric
tensor, and E, nu within 1 % of the frame closed forms
E = 16 sqrt(3) (EI/l^3)/(1+36 s), nu = (1-12 s)/(1+36 s), s = EI/(EA l^2)
(docs/homogenization.md); the PNG exists and is a PNG.

Usage: check_homogenize.py RESULT.json T [PNG]
       check_homogenize.py --cell SOLVE_RESULT.json STRESS11
         (rodnet solve of a stress-controlled cell: "cell" has the applied stress
         (s, 0, 0) to 1e-6 and a stretch along x)
       check_homogenize.py --same RESULT.json OTHER.json
         (a supercell gives the cell's tensor: C equal to 1e-9 of max |C|)"""
import json
import math
import sys


def same(a, b):
    ra, rb = json.load(open(a)), json.load(open(b))
    Ca, Cb = ra["C"], rb["C"]
    cmax = max(abs(v) for row in Ca for v in row)
    worst = max(abs(x - y) for ra_, rb_ in zip(Ca, Cb) for x, y in zip(ra_, rb_)) / cmax
    print("C of %s against %s: worst difference %.2e of max |C|" % (a, b, worst))
    assert worst < 1e-9, "the supercell's tensor differs from the cell's"
    assert abs(ra["relative_density"] / rb["relative_density"] - 1.0) < 1e-12
    print("ok")


def cell(path, s11):
    c = json.load(open(path))["cell"]
    print("cell:", c)
    assert c["dimension"] == 2 and len(c["strain"]) == 3 and len(c["stress"]) == 3
    assert abs(c["stress"][0] / s11 - 1.0) < 1e-6
    assert abs(c["stress"][1]) < 1e-6 * s11 and abs(c["stress"][2]) < 1e-6 * s11
    assert c["strain"][0] > 0 and c["strain"][1] < 0  # the honeycomb's nu ~ 1
    print("ok")


def main():
    if sys.argv[1] == "--cell":
        return cell(sys.argv[2], float(sys.argv[3]))
    if sys.argv[1] == "--same":
        return same(sys.argv[2], sys.argv[3])
    r = json.load(open(sys.argv[1]))
    T = float(sys.argv[2])
    for key in ("C", "constants", "area", "relative_density"):
        assert key in r, "missing key " + key
    for key in ("E1", "E2", "nu12", "G12"):
        assert key in r["constants"], "missing constant " + key
    C = r["C"]
    assert len(C) == 3 and all(len(row) == 3 for row in C)
    for i in range(3):
        for j in range(3):
            assert C[i][j] == C[j][i], "C is not symmetric"
    l = 1.0 / math.sqrt(3.0)  # cell size 1: bar length a / sqrt(3)
    t = T * l
    EA, EI = t * t, t * t ** 3 / 12.0
    s = EI / (EA * l * l)
    E = 16.0 * math.sqrt(3.0) * EI / l ** 3 / (1.0 + 36.0 * s)
    nu = (1.0 - 12.0 * s) / (1.0 + 36.0 * s)
    c = r["constants"]
    print("E1/E = %.6f E2/E = %.6f nu12 = %.6f (closed form %.6f) rho = %.6f (%.6f)"
          % (c["E1"] / E, c["E2"] / E, c["nu12"], nu, r["relative_density"],
             2.0 / math.sqrt(3.0) * T))
    assert abs(c["E1"] / E - 1.0) < 0.01 and abs(c["E2"] / E - 1.0) < 0.01
    assert abs(c["nu12"] / nu - 1.0) < 0.01
    assert abs(r["relative_density"] / (2.0 / math.sqrt(3.0) * T) - 1.0) < 1e-12
    assert abs(r["area"] - math.sqrt(3.0) / 2.0) < 1e-12
    if len(sys.argv) > 3:
        with open(sys.argv[3], "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n", "not a PNG"
    print("ok")


if __name__ == "__main__":
    main()
