#!/usr/bin/env python3
"""check_stability.py - the "stability" block of a rodnet RESULT.json.

    check_stability.py RESULT.json [--verified true|false] [--zero-modes K]
                       [--symmetries S] [--soft-modes F] [--soft-positive P]
                       [--lowest-below R] [--min-abs-z Z]
                       [--method cholesky|lobpcg] [--same-as OTHER.json]

Fails (exit 1) unless the block has every contract key (checked, lowest_eigenvalue,
scale, verified_minimum, zero_modes) with finite numbers, the run converged when it
claims a verified minimum, verified_minimum is the one asked for, zero_modes equals K,
symmetries, soft_modes and soft_positive (when separated, not null) are consistent
(zero_modes = symmetries + soft_modes - soft_positive; a verified minimum has only
symmetries among its zero modes and a positive lowest eigenvalue) and equal S, F, P,
the lowest eigenvalue is below R scale (a soft mode reported as the lowest),
and (--min-abs-z) some rod vertex lies at |z| >= Z (a planar lattice buckled out of
its plane); --method: the check's method; --same-as: the lowest eigenvalue within
1e-6 relative (+ 1e-12 scale) of OTHER's, the same zero modes and verdict (the
same state checked by the other method)."""
import argparse
import json
import math
import sys


def fail(msg):
    print("check_stability: FAILED: " + msg)
    sys.exit(1)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("result")
    ap.add_argument("--verified", choices=("true", "false"))
    ap.add_argument("--zero-modes", type=int)
    ap.add_argument("--symmetries", type=int)
    ap.add_argument("--soft-modes", type=int)
    ap.add_argument("--soft-positive", type=int)
    ap.add_argument("--lowest-below", type=float)
    ap.add_argument("--min-abs-z", type=float)
    ap.add_argument("--method", choices=("cholesky", "lobpcg"))
    ap.add_argument("--same-as")
    a = ap.parse_args()
    with open(a.result) as f:
        r = json.load(f)
    st = r.get("stability")
    if not isinstance(st, dict):
        fail("no stability block")
    for key in ("checked", "lowest_eigenvalue", "scale", "verified_minimum", "zero_modes"):
        if key not in st:
            fail("stability lacks %r: %r" % (key, st))
    if st["checked"] is not True:
        fail("stability not checked: %r" % st)
    for key in ("lowest_eigenvalue", "scale"):
        if not isinstance(st[key], (int, float)) or not math.isfinite(st[key]):
            fail("stability.%s is not a finite number" % key)
    if st["verified_minimum"] and not r["converged"]:
        fail("a verified minimum of a run that did not converge")
    for key in ("symmetries", "soft_modes", "soft_positive"):
        if key not in st:
            fail("stability lacks %r: %r" % (key, st))
    separated = st["symmetries"] is not None
    if separated:
        if st["zero_modes"] != st["symmetries"] + st["soft_modes"] - st["soft_positive"]:
            fail("zero_modes %d != symmetries + soft_modes - soft_positive" %
                 st["zero_modes"])
        if not 0 <= st["soft_positive"] <= st["soft_modes"]:
            fail("soft_positive %d outside 0 .. soft_modes" % st["soft_positive"])
        if st["verified_minimum"] and st["zero_modes"] != st["symmetries"]:
            fail("verified, yet %d zero modes besides the %d symmetries" %
                 (st["zero_modes"] - st["symmetries"], st["symmetries"]))
        if st["verified_minimum"] and not st["lowest_eigenvalue"] > 0.0:
            fail("verified, yet lowest eigenvalue %g <= 0" % st["lowest_eigenvalue"])
    elif st["verified_minimum"] and not st["lowest_eigenvalue"] > 1e-12 * st["scale"]:
        fail("verified, yet lowest eigenvalue %g <= 1e-12 scale" % st["lowest_eigenvalue"])
    for key, want in (("symmetries", a.symmetries), ("soft_modes", a.soft_modes),
                      ("soft_positive", a.soft_positive)):
        if want is not None and st[key] != want:
            fail("%s %r, expected %d" % (key, st[key], want))
    if a.lowest_below is not None and not st["lowest_eigenvalue"] < a.lowest_below * st["scale"]:
        fail("lowest eigenvalue %g not below %g scale" % (st["lowest_eigenvalue"], a.lowest_below))
    if a.verified and st["verified_minimum"] != (a.verified == "true"):
        fail("verified_minimum %r, expected %s" % (st["verified_minimum"], a.verified))
    if a.zero_modes is not None and st["zero_modes"] != a.zero_modes:
        fail("zero_modes %d, expected %d" % (st["zero_modes"], a.zero_modes))
    if a.min_abs_z is not None:
        zmax = max(abs(v[2]) for rod in r["rods"] for v in rod["vertices"])
        if not zmax >= a.min_abs_z:
            fail("max |z| = %g < %g: not buckled out of plane" % (zmax, a.min_abs_z))
        print("check_stability: max |z| = %g" % zmax)
    if a.method and st.get("method") != a.method:
        fail("method %r, expected %s" % (st.get("method"), a.method))
    if a.same_as:
        with open(a.same_as) as f:
            o = json.load(f)["stability"]
        d = abs(st["lowest_eigenvalue"] - o["lowest_eigenvalue"])
        print("check_stability: lowest eigenvalue %.10g vs %.10g (%s)" %
              (st["lowest_eigenvalue"], o["lowest_eigenvalue"], a.same_as))
        if d > 1e-6 * abs(o["lowest_eigenvalue"]) + 1e-12 * o["scale"]:
            fail("lowest eigenvalues differ by %g" % d)
        for key in ("zero_modes", "verified_minimum"):
            if st[key] != o[key]:
                fail("%s %r vs %r" % (key, st[key], o[key]))
    print("check_stability: ok: %s %r" % (a.result, st))


if __name__ == "__main__":
    main()
