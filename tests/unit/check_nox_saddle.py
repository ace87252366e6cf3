#!/usr/bin/env python3
"""NOX solves grad E = 0, so from a straight column compressed past buckling it
converges to the straight (unstable) equilibrium, a saddle of the energy, where the
trust region finds the buckled minimum.  Checks both results of the pinned column:

    check_nox_saddle.py NOX.json EXACT.json

NOX: converged, "finds": "stationary point", lateral deflection below 1e-4 of the
length (straight up to the 1e-4 N probe force); the trust region: "local minimum",
buckled (deflection above 1e-2) with a lower energy.  Exits 1 on any failure."""
import json
import sys


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def deflection(result):
    return max(abs(v[0]) for rod in result["rods"] for v in rod["vertices"])


def main():
    nox, exact = load(sys.argv[1]), load(sys.argv[2])
    dn, de = deflection(nox), deflection(exact)
    print(f"check_nox_saddle: nox energy {nox['energy']:.6e} deflection {dn:.3e} "
          f"({nox.get('finds')}); tr-minres energy {exact['energy']:.6e} deflection "
          f"{de:.3e} ({exact.get('finds')})")
    ok = (nox["converged"] and nox.get("finds") == "stationary point" and dn < 1e-4
          and exact["converged"] and exact.get("finds") == "local minimum" and de > 1e-2
          and exact["energy"] < nox["energy"])
    if not ok:
        print("check_nox_saddle: FAILED")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
