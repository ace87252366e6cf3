#!/usr/bin/env python3
"""Check the reactions block of a result JSON and the internal forces of the .vtu.

    check_reactions.py RESULT.json [--vtu RESULT.vtu] [--balance-tol T]
                       [--cantilever P L0] [--portal H HEIGHT SPAN EDGES TOL]

Always: every support has a kind, a point, a force and a moment (finite), the
resultant is the sum of the supports' forces and of their moments about the
origin (moment + point x force), and the reactions balance the applied loads:
|resultant + applied| <= max(T (default 1e-9) times the largest force, the
equilibrium's force_tolerance) (for moments: the largest moment or force times
the structure's size, and force_tolerance times the size plus the
moment_tolerance).  The imbalance is exactly minus the sum of the residual
forces at the free DOFs, so it is as small as the equilibrium the solver
certified (at least 10 x the round-off floor of the stencil forces).

--cantilever P L0: one clamp carrying a tip load P (-z) of a rod along x, L0
the undeformed distance from the clamp point (the midpoint of the clamped
edge, where a DER clamp sits) to the tip.  The root moment is P L, L = x_tip -
x_clamp point of the deformed rod, to 1e-9 (statics), and the linear closed
form P L0 to 1e-6 (P L^2 / E I = 5e-4 changes the lever arm by O(1e-8)); the
reaction force (0, 0, P) to the equilibrium's force tolerance.
With --vtu: every edge after the clamped one carries the internal force P
(0, 0, -P) and the internal moment (x_tip - c) x P about its midpoint c (the
statics of the part after the cut), relative to P (P L) to the residual the
solver left: (vertices) x force_residual / P (at least 1e-10).

--portal H HEIGHT SPAN EDGES TOL: a fixed-base portal frame (two clamps, equal
sections, rigid corners) with a lateral force H at the top of the first
column.  The closed form (slope-deflection method; e.g. Kleinlogel's frame
formulas, or Hibbeler, Structural Analysis, ch. 11): with h the column height
from the clamp point (HEIGHT - half an edge of HEIGHT / EDGES) and
k = (I_b / SPAN) / (I_c / h) = h / SPAN,
  base moments  M = H h (1 + 3k) / (2 (1 + 6k))  (both, the same sense),
  horizontal reactions  -H / 2 each,
  vertical reactions  -/+ V, V = 3 k H h / ((1 + 6k) SPAN)
relative tolerance TOL (the discretisation is O(h^2): 2.5e-3 at 16 edges per
rod, 6e-4 at 32).
"""
import argparse
import json
import math
import sys


def fail(msg):
    print("check_reactions: FAILED: " + msg)
    sys.exit(1)


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(v):
    return math.sqrt(sum(x * x for x in v))


def vec(x, what):
    if not isinstance(x, list) or len(x) != 3:
        fail("%s is not a 3-vector: %r" % (what, x))
    for c in x:
        if not isinstance(c, (int, float)) or not math.isfinite(c):
            fail("%s has a non-finite entry: %r" % (what, x))
    return x


def check_balance(r, rx, tol):
    sup = rx["supports"]
    F, M = [0.0] * 3, [0.0] * 3
    fbig, mbig = 0.0, 0.0
    for i, s in enumerate(sup):
        if s.get("kind") not in ("clamp", "vertex", "angle", "joint"):
            fail("support %d: bad kind %r" % (i, s.get("kind")))
        p, f, m = vec(s["point"], "point"), vec(s["force"], "force"), vec(s["moment"], "moment")
        pm = cross(p, f)
        for k in range(3):
            F[k] += f[k]
            M[k] += m[k] + pm[k]
        fbig, mbig = max(fbig, norm(f)), max(mbig, norm(m))
    res, app = rx["resultant"], rx["applied"]
    size = max(norm(v) for rod in r["rods"] for v in rod["vertices"])
    fbig = max(fbig, norm(vec(app["force"], "applied force")))
    mbig = max(mbig, norm(vec(app["moment"], "applied moment")), fbig * size)
    if norm([F[k] - res["force"][k] for k in range(3)]) > 1e-12 * fbig or \
       norm([M[k] - res["moment"][k] for k in range(3)]) > 1e-12 * mbig:
        fail("the resultant %r is not the sum of the supports %r" % (res, (F, M)))
    df = norm([res["force"][k] + app["force"][k] for k in range(3)])
    dm = norm([res["moment"][k] + app["moment"][k] for k in range(3)])
    # The reactions plus the applied loads equal minus the sum of the residual
    # forces at the free DOFs (translation and rotation invariance of the
    # elastic energy): zero up to the equilibrium the solver certified, whose
    # tolerance is at least 10 x the round-off floor of the stencil forces.
    eq = r["equilibrium"]
    ftol = max(tol * fbig, eq["force_tolerance"])
    mtol = max(tol * mbig, eq["force_tolerance"] * size + eq["moment_tolerance"])
    print("check_reactions: %d supports, |reactions + applied| = %.3e (force scale %.3e, "
          "tolerance %.3e), %.3e (moment scale %.3e, tolerance %.3e)"
          % (len(sup), df, fbig, ftol, dm, mbig, mtol))
    if df > ftol or dm > mtol:
        fail("the reactions do not balance the applied loads")


def read_vtu(path):
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    rd = vtkXMLUnstructuredGridReader()
    rd.SetFileName(path)
    rd.Update()
    g = rd.GetOutput()
    cd = g.GetCellData()
    arr = {}
    for name in ("internal_force", "internal_moment", "rod", "edge"):
        a = cd.GetArray(name)
        if a is None:
            fail("%s: no cell array %r" % (path, name))
        arr[name] = vtk_to_numpy(a)
    return arr


def check_cantilever(r, rx, P, L0, vtu):
    sup = rx["supports"]
    if len(sup) != 1 or sup[0]["kind"] != "clamp":
        fail("expected one clamp, got %r" % sup)
    s = sup[0]
    v = r["rods"][0]["vertices"]
    tip = v[-1]
    L = tip[0] - s["point"][0]
    M = -s["moment"][1]
    print("check_reactions: cantilever root moment %.12e, P L = %.12e (L = %.6f), rel %.2e"
          % (M, P * L, L, abs(M / (P * L) - 1)))
    if abs(M / (P * L) - 1) > 1e-9:
        fail("root moment %r, statics of the deformed rod P L = %r" % (M, P * L))
    print("check_reactions: cantilever root moment against the linear closed form P L0 = "
          "%.12e (L0 = %.6f): rel %.2e" % (P * L0, L0, abs(M / (P * L0) - 1)))
    if abs(M / (P * L0) - 1) > 1e-6:
        fail("root moment %r, closed form P L0 = %r" % (M, P * L0))
    ftol = max(1e-9 * P, r["equilibrium"]["force_tolerance"])
    if abs(s["force"][2] - P) > ftol or abs(s["force"][0]) > ftol:
        fail("clamp force %r, expected (0, 0, %r)" % (s["force"], P))
    if not vtu:
        return
    a = read_vtu(vtu)
    Pv = [0.0, 0.0, -P]
    worst = 0.0
    for c in range(len(v) - 1):
        if a["rod"][c] != 0 or a["edge"][c] != c:
            fail("cell %d is not edge %d of rod 0" % (c, c))
        if c == 0:
            continue  # the clamped edge
        mid = [0.5 * (v[c][k] + v[c + 1][k]) for k in range(3)]
        want_m = cross([tip[k] - mid[k] for k in range(3)], Pv)
        fm = list(a["internal_force"][c]) + list(a["internal_moment"][c])
        err = max(norm([fm[k] - Pv[k] for k in range(3)]) / P,
                  norm([fm[3 + k] - want_m[k] for k in range(3)]) / (P * L))
        worst = max(worst, err)
    # the part after the cut is in equilibrium up to the residual forces at its
    # free vertices: at most (vertices) x force_residual
    bound = max(1e-10, len(v) * r["equilibrium"]["force_residual"] / P)
    print("check_reactions: internal force and moment against the statics of the cut "
          "part: worst relative error %.3e (bound from the equilibrium residual %.3e)"
          % (worst, bound))
    if worst > bound:
        fail("internal forces or moments differ from the statics by %.3e" % worst)


def check_portal(rx, H, height, span, edges, tol):
    sup = rx["supports"]
    if len(sup) != 2 or any(s["kind"] != "clamp" for s in sup):
        fail("expected two clamps, got %r" % sup)
    h = height - 0.5 * height / edges
    k = h / span
    M = H * h * (1 + 3 * k) / (2 * (1 + 6 * k))
    V = 3 * k * H * h / ((1 + 6 * k) * span)
    a, b = sorted(sup, key=lambda s: s["point"][0])
    got = {"base moment A": (-a["moment"][1], M), "base moment D": (-b["moment"][1], M),
           "horizontal A": (a["force"][0], -H / 2), "horizontal D": (b["force"][0], -H / 2),
           "vertical A": (a["force"][2], -V), "vertical D": (b["force"][2], V)}
    for name, (x, want) in got.items():
        rel = abs(x / want - 1)
        print("check_reactions: portal %-14s %.9e, closed form %.9e, rel %.2e"
              % (name, x, want, rel))
        if rel > tol:
            fail("portal frame %s %r, closed form %r" % (name, x, want))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("result")
    ap.add_argument("--vtu")
    ap.add_argument("--balance-tol", type=float, default=1e-9)
    ap.add_argument("--cantilever", type=float, nargs=2)
    ap.add_argument("--portal", type=float, nargs=5)
    a = ap.parse_args()
    with open(a.result) as f:
        r = json.load(f)
    rx = r.get("reactions")
    if not isinstance(rx, dict) or not isinstance(rx.get("supports"), list):
        fail("missing the reactions block")
    check_balance(r, rx, a.balance_tol)
    if a.cantilever:
        check_cantilever(r, rx, a.cantilever[0], a.cantilever[1], a.vtu)
    if a.portal:
        check_portal(rx, *a.portal)
    print("check_reactions: ok")


if __name__ == "__main__":
    main()
