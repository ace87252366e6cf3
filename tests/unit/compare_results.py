#!/usr/bin/env python3
"""Two RESULT.json files of the same scene describe the same equilibrium: energies
within --energy-rtol (relative, or --energy-atol absolute: a stress-free state has
energy 0 up to round-off) and every vertex and joint position within --rtol of the
largest coordinate.  Used to check tr-krylov against tr-minres on every example
scene (issue 7).  Exit 0 if they agree, 1 (with the reason) if not.

Both solves stop when the force residual is below its tolerance (about 1e-9 of the
forces, or the round-off floor); two such states differ by up to that residual
times the largest compliance (1 / lowest Hessian eigenvalue): on the soft 215-degree
arch (lowest eigenvalue 0.02, force tolerance 1e-6) up to 5e-5.  Hence --rtol 1e-5
by default; the energies, stationary there, agree to 1e-8 and closer.

--twin: the scene is a single rod symmetric under the inversion through the midpoint
of its end vertices (the strip whose clamp is moved, strip_displaced.json: its two
S-shaped equilibria are such twins, with equal energies, and which one a solver finds
depends on its path); B's image under it (vertex order reversed, p -> p_0 + p_n - p)
is accepted as well.

    compare_results.py A.json B.json [--rtol 1e-5] [--energy-rtol 1e-8] [--twin]
"""
import argparse
import json
import sys


def flat(result):
    vals = []
    for rod in result["rods"]:
        for v in rod["vertices"]:
            vals.extend(v)
    for j in result.get("joints", []):
        vals.extend(j["position"])
    return vals


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--rtol", type=float, default=1e-5)
    ap.add_argument("--energy-rtol", type=float, default=1e-8)
    ap.add_argument("--energy-atol", type=float, default=1e-20)
    ap.add_argument("--twin", action="store_true")
    args = ap.parse_args()
    with open(args.a) as f:
        a = json.load(f)
    with open(args.b) as f:
        b = json.load(f)
    for r, name in ((a, args.a), (b, args.b)):
        if not r["converged"]:
            print("compare_results: %s did not converge (%s)" % (name, r["stop_reason"]))
            return 1
    xa, xb = flat(a), flat(b)
    if len(xa) != len(xb):
        print("compare_results: different numbers of points")
        return 1
    scale = max(max(abs(v) for v in xb), 1e-300)
    dx = max(abs(p - q) for p, q in zip(xa, xb))
    if args.twin:
        if len(b["rods"]) != 1 or b.get("joints"):
            print("compare_results: --twin needs a single rod")
            return 1
        v = b["rods"][0]["vertices"]
        image = [[v[0][k] + v[-1][k] - p[k] for k in range(3)] for p in reversed(v)]
        dt = max(abs(p - q) for p, q in zip(xa, [c for p in image for c in p]))
        if dt < dx:
            print("compare_results: B's twin (inversion through the chord midpoint)")
            dx = dt
    ea, eb = a["energy"], b["energy"]
    de = abs(ea - eb) / max(abs(eb), 1e-300)
    print("compare_results: %s vs %s: positions differ by %.3e of %.3e, energies %.17g and "
          "%.17g (relative %.3e); iterations %d and %d" %
          (a["solver"], b["solver"], dx, scale, ea, eb, de, a["iterations"], b["iterations"]))
    if dx > args.rtol * scale:
        print("compare_results: FAILED: positions differ by more than %g" % args.rtol)
        return 1
    if de > args.energy_rtol and abs(ea - eb) > args.energy_atol:
        print("compare_results: FAILED: energies differ by more than %g" % args.energy_rtol)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
