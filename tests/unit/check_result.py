#!/usr/bin/env python3
"""Check a result JSON written by `rodnet solve`.

    check_result.py RESULT.json [--status converged] [--vertices N]
                    [--clamped-start X0 X1] [--edge-length L]
                    [--elastica P EI X0 XTIP]

Always: the required fields exist with the right types and finite values;
energy equals the sum of energy_terms; a converged result has a gradient
norm far below the initial one and load factor 1; every rod has
len(theta) == len(vertices) - 1; every joint has a name, a model, a finite
position and a rotation matrix that is orthonormal with determinant 1.  Options add: the status; the vertex count
of the first rod; a clamped start (first two vertices unmoved, given as
x of vertex 0 and 1 on the x axis); inextensibility (every edge within 1e-3
of L); the tip position of a cantilever elastica under a dead tip load P
(-z) along x, clamped at x = X0 (a DER clamp fixes the first edge: the
continuum clamp sits at its midpoint) with the tip at x = XTIP, computed here
by shooting; tolerance 5e-4 of the length (the O(h^2) discretisation and the
axial stretch give about 1e-4 at 100 edges).

    [--joints N] [--joint-at-rod-ends]
    [--stretch-energy NBARS E RADIUS STRAIN LENGTH]
    [--factorization NAME] [--min-factorizations N]

--joints: the number of joints; --joint-at-rod-ends: every joint's position
equals the end vertex of some rod exactly (rod ends alias the joint);
--stretch-energy: uniform axial strain of NBARS straight round bars (a
square lattice stretched along its bars): stretching energy
NBARS * E * pi RADIUS^2 * STRAIN^2 * LENGTH / 2 to 1e-8, bending and
twisting below 1e-12 of it.  Always: "factorizations" is an integer >= 0;
--factorization and --min-factorizations: the factorisation named and at
least N numeric factorisations."""
import argparse
import json
import math
import sys


def fail(msg):
    print("check_result: FAILED: " + msg)
    sys.exit(1)


def finite(x, what):
    if not isinstance(x, (int, float)) or isinstance(x, bool) or not math.isfinite(x):
        fail("%s is not a finite number: %r" % (what, x))
    return x


def elastica_tip(P, EI, L, n=4000):
    """Tip (x, z) of a clamped-free elastica, tip load P downwards:
    EI theta'' = -P cos(theta), theta(0) = 0, theta'(L) = 0."""
    def shoot(k0):
        h = L / n
        th, k, x, z = 0.0, k0, 0.0, 0.0
        def f(state):
            th_, k_, _, _ = state
            return (k_, -P / EI * math.cos(th_), math.cos(th_), -math.sin(th_))
        s = (th, k, x, z)
        for _ in range(n):
            a = f(s)
            b = f(tuple(si + 0.5 * h * ai for si, ai in zip(s, a)))
            c = f(tuple(si + 0.5 * h * bi for si, bi in zip(s, b)))
            d = f(tuple(si + h * ci for si, ci in zip(s, c)))
            s = tuple(si + h / 6 * (ai + 2 * bi + 2 * ci + di)
                      for si, ai, bi, ci, di in zip(s, a, b, c, d))
        return s
    lo, hi = 0.0, P * L / EI
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if shoot(mid)[1] > 0:
            hi = mid
        else:
            lo = mid
    s = shoot(0.5 * (lo + hi))
    return s[2], s[3]


def det3(m):
    return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))


def check_joints(r, a):
    if not isinstance(r.get("joints"), list):
        fail("missing field 'joints' (a list)")
    ends = set()
    for rod in r["rods"]:
        ends.add(tuple(rod["vertices"][0]))
        ends.add(tuple(rod["vertices"][-1]))
    for j in r["joints"]:
        if not isinstance(j.get("name"), str) or j.get("model") not in ("rigid", "elastic"):
            fail("joint %r: bad name or model" % j.get("name"))
        p, R = j.get("position"), j.get("rotation")
        if not isinstance(p, list) or len(p) != 3 or not isinstance(R, list) or len(R) != 3:
            fail("joint %r: position or rotation missing" % j["name"])
        for x in p:
            finite(x, "joint position")
        for row in R:
            if len(row) != 3:
                fail("joint %r: rotation rows must have 3 entries" % j["name"])
            for x in row:
                finite(x, "joint rotation")
        err = max(abs(sum(R[k][i] * R[k][m] for k in range(3)) - (i == m))
                  for i in range(3) for m in range(3))
        if err > 1e-9 or abs(det3(R) - 1) > 1e-9:
            fail("joint %r: rotation not orthonormal (err %g, det %r)" % (j["name"], err, det3(R)))
        if a.joint_at_rod_ends and tuple(p) not in ends:
            fail("joint %r at %r is not a rod end vertex" % (j["name"], p))
    if a.joints is not None and len(r["joints"]) != a.joints:
        fail("%d joints, expected %d" % (len(r["joints"]), a.joints))


def check_stretch_energy(r, nbars, E, radius, strain, length):
    want = nbars * 0.5 * E * math.pi * radius ** 2 * strain ** 2 * length
    got = r["energy_terms"]
    print("check_result: stretching energy %.17g, uniform strain %.17g" % (got["stretch"], want))
    if abs(got["stretch"] / want - 1) > 1e-8:
        fail("stretching energy %r, expected %r" % (got["stretch"], want))
    if abs(got["bend"]) + abs(got["twist"]) > 1e-12 * want:
        fail("bending %r / twisting %r energy in a uniform stretch" % (got["bend"], got["twist"]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("result")
    ap.add_argument("--status")
    ap.add_argument("--vertices", type=int)
    ap.add_argument("--clamped-start", type=float, nargs=2)
    ap.add_argument("--edge-length", type=float)
    ap.add_argument("--elastica", type=float, nargs=4)
    ap.add_argument("--joints", type=int)
    ap.add_argument("--joint-at-rod-ends", action="store_true")
    ap.add_argument("--stretch-energy", type=float, nargs=5)
    ap.add_argument("--factorization")
    ap.add_argument("--min-factorizations", type=int)
    a = ap.parse_args()
    with open(a.result) as f:
        r = json.load(f)
    for key in ("status", "energy", "gradient_norm", "iterations", "time_s", "rods",
                "solver", "stop_reason", "converged", "energy_terms", "load_factor",
                "initial_gradient_norm", "evaluations", "num_dofs", "factorizations"):
        if key not in r:
            fail("missing field '%s'" % key)
    if not isinstance(r["status"], str) or not isinstance(r["iterations"], int):
        fail("status must be a string and iterations an integer")
    for key in ("energy", "gradient_norm", "time_s", "load_factor", "initial_gradient_norm"):
        finite(r[key], key)
    if r["time_s"] < 0 or r["gradient_norm"] < 0 or r["iterations"] < 0:
        fail("negative time, gradient norm or iteration count")
    nf = r["factorizations"]
    if not isinstance(nf, int) or isinstance(nf, bool) or nf < 0:
        fail("factorizations must be an integer >= 0, got %r" % (nf,))
    if a.min_factorizations is not None and nf < a.min_factorizations:
        fail("%d factorizations, expected at least %d" % (nf, a.min_factorizations))
    if a.factorization and r.get("factorization") != a.factorization:
        fail("factorization %r, expected %r" % (r.get("factorization"), a.factorization))
    if a.status and r["status"] != a.status:
        fail("status %r, expected %r" % (r["status"], a.status))
    if r["converged"] != (r["status"] == "converged"):
        fail("converged flag %r inconsistent with status %r" % (r["converged"], r["status"]))
    terms = sum(finite(v, "energy_terms." + k) for k, v in r["energy_terms"].items())
    if abs(terms - r["energy"]) > 1e-9 * max(1e-300, sum(abs(v) for v in r["energy_terms"].values())):
        fail("energy %r differs from the sum of its terms %r" % (r["energy"], terms))
    if r["converged"]:
        # 0 Newton iterations only when the load-step predictor solved it
        if r["iterations"] < 1 and r.get("predictor_steps", 0) < 1:
            fail("converged in %d iterations" % r["iterations"])
        if not r["gradient_norm"] <= 1e-6 * r["initial_gradient_norm"]:
            fail("gradient norm %g not below 1e-6 x initial %g" % (
                r["gradient_norm"], r["initial_gradient_norm"]))
        if r["load_factor"] != 1:
            fail("converged at load factor %r" % r["load_factor"])
    if not r["rods"]:
        fail("no rods")
    for rod in r["rods"]:
        v, th = rod["vertices"], rod["theta"]
        if not isinstance(rod.get("name"), str) or len(v) < 2 or len(th) != len(v) - 1:
            fail("rod %r: %d vertices, %d angles" % (rod.get("name"), len(v), len(th)))
        for p in v:
            if len(p) != 3:
                fail("vertex %r is not a point" % p)
            for x in p:
                finite(x, "vertex coordinate")
        for t in th:
            finite(t, "theta")
    check_joints(r, a)
    if a.stretch_energy:
        check_stretch_energy(r, *a.stretch_energy)
    v = r["rods"][0]["vertices"]
    if a.vertices is not None and len(v) != a.vertices:
        fail("%d vertices, expected %d" % (len(v), a.vertices))
    if a.clamped_start:
        for i, x0 in enumerate(a.clamped_start):
            if max(abs(v[i][0] - x0), abs(v[i][1]), abs(v[i][2])) > 1e-14:
                fail("clamped vertex %d moved to %r" % (i, v[i]))
    if a.edge_length:
        for i in range(len(v) - 1):
            l = math.dist(v[i], v[i + 1])
            if abs(l / a.edge_length - 1) > 1e-3:
                fail("edge %d has length %r, expected %r" % (i, l, a.edge_length))
    if a.elastica:
        P, EI, x0, xtip = a.elastica
        L = xtip - x0
        xt, zt = elastica_tip(P, EI, L)
        xt += x0
        tip = v[-1]
        err = math.hypot(tip[0] - xt, tip[2] - zt) / L
        print("check_result: tip (%.6f, %.6f), elastica (%.6f, %.6f), |diff| / L = %.2e" % (
            tip[0], tip[2], xt, zt, err))
        if err > 5e-4 or abs(tip[1]) > 1e-9:
            fail("tip off the elastica")
    print("check_result: ok: %s (status %s, %d iterations)" % (a.result, r["status"], r["iterations"]))


if __name__ == "__main__":
    main()
