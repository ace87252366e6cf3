#!/usr/bin/env python3
"""The planar model (docs/model.md) against the 3D model: the same in-plane answers
to 1e-10 (positions relative to the largest coordinate, energies, reactions relative
to the largest reaction component, the homogenised C relative to its largest entry,
the stress of a strain path), with fewer free DOFs; the scene checks of
"model": "planar" (a clear error naming what leaves the plane); the detection
report "model": {"used", "planar"} of RESULT.json.

    check_planar.py RODNET WORKDIR [MPIEXEC]
"""
import json
import os
import subprocess
import sys

TOL = 1e-10
FAILS = []


def run(args, expect=0):
    """expect: the exit code, or None for any failure (non-zero)."""
    p = subprocess.run(args, capture_output=True, text=True)
    if (p.returncode == 0) if expect is None else (p.returncode != expect):
        sys.exit("%s: exit %d (expected %s)\n%s%s" % (" ".join(args), p.returncode,
                                                      "non-zero" if expect is None else expect,
                                                      p.stdout, p.stderr))
    return p


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        FAILS.append(what)


def numbers(x):
    if isinstance(x, bool):
        return []
    if isinstance(x, (int, float)):
        return [float(x)]
    if isinstance(x, list):
        return [v for e in x for v in numbers(e)]
    if isinstance(x, dict):
        return [v for k in sorted(x) for v in numbers(x[k])]
    return []


def rel_diff(a, b):
    a, b = numbers(a), numbers(b)
    if len(a) != len(b):
        return float("inf")
    scale = max([abs(v) for v in a + b] + [1e-300])
    return max([abs(u - v) for u, v in zip(a, b)] + [0.0]) / scale


def with_model(src, dst, model, edit=None):
    with open(src) as f:
        s = json.load(f)
    if model:
        s["model"] = model
    if edit:
        edit(s)
    with open(dst, "w") as f:
        json.dump(s, f)
    return dst


def positions(res):
    return [[r["vertices"] for r in res["rods"]], [j["position"] for j in res["joints"]]]


def compare_solves(rodnet, wd, scene, label, solver_args=(), launcher=()):
    out = {}
    for m in ("planar", "3d"):
        sc = with_model(scene, os.path.join(wd, "%s_%s.json" % (label, m)), m)
        rj = os.path.join(wd, "%s_%s_result.json" % (label, m))
        run(list(launcher) + [rodnet, "solve", sc, "-o", rj] + list(solver_args))
        with open(rj) as f:
            out[m] = json.load(f)
    p, q = out["planar"], out["3d"]
    check(p["converged"] and q["converged"], "%s: both converge" % label)
    check(p["model"] == {"used": "planar", "planar": True}, "%s: planar reported" % label)
    check(q["model"] == {"used": "3d", "planar": True}, "%s: 3d, qualifies" % label)
    check(p["num_dofs"] < q["num_dofs"],
          "%s: %d < %d free DOFs" % (label, p["num_dofs"], q["num_dofs"]))
    d = rel_diff(positions(p), positions(q))
    check(d <= TOL, "%s: positions agree (%.2e)" % (label, d))
    d = abs(p["energy"] - q["energy"]) / max(abs(q["energy"]), 1e-300)
    check(d <= TOL, "%s: energies agree (%.2e)" % (label, d))
    d = rel_diff(p.get("reactions"), q.get("reactions"))
    check(d <= TOL, "%s: reactions agree (%.2e)" % (label, d))
    z0 = q["rods"][0]["vertices"][0][2]
    z = max([abs(v[2] - z0) for r in q["rods"] for v in r["vertices"]] + [0.0])
    check(z <= 1e-12, "%s: the 3D solve stays in the plane (max |z - z0| %.1e)" % (label, z))
    return p, q


def hom_g12(rodnet, wd):
    """C33 (G12) of the same honeycomb cell without the prescribed strain."""
    out = os.path.join(wd, "psh_free.json")
    with open(os.path.join(wd, "psh.json")) as f:
        s = json.load(f)
    del s["periodic"]["strain"]
    with open(out, "w") as f:
        json.dump(s, f)
    run([rodnet, "homogenize", out, "-o", out + ".result", "-q"])
    with open(out + ".result") as f:
        return json.load(f)["C"][2][2]


def main():
    rodnet, wd = sys.argv[1], sys.argv[2]
    mpiexec = sys.argv[3] if len(sys.argv) > 3 else None
    os.makedirs(wd, exist_ok=True)
    j = lambda name: os.path.join(wd, name)

    # A finite honeycomb with rigid joints under uniaxial stretch, a square lattice
    # with elastic joints, tr-minres and tr-krylov (and 2 MPI ranks).
    run([rodnet, "generate", "honeycomb", "--cells", "3", "--joint-model", "rigid",
         "--edges-per-rod", "6", "--load", "stretch-x:0.05", "-o", j("hc.json")])
    compare_solves(rodnet, wd, j("hc.json"), "honeycomb")
    compare_solves(rodnet, wd, j("hc.json"), "honeycomb-krylov", ["--solver", "tr-krylov"])
    # the reduced derivatives of the planar model against central differences,
    # with the h-sweep of `rodnet check` (order 2)
    p = run([rodnet, "check", j("honeycomb_planar.json")])
    check("PASS" in p.stdout and "order  2.00" in p.stdout,
          "rodnet check on the planar honeycomb: " + p.stdout.strip().splitlines()[-1])
    if mpiexec:
        compare_solves(rodnet, wd, j("hc.json"), "honeycomb-krylov-2ranks",
                       ["--solver", "tr-krylov"], [mpiexec, "-n", "2"])
    # (under compression the 3D square lattice buckles out of plane: not a
    # planar equilibrium, docs/model.md)
    run([rodnet, "generate", "square", "--cells", "3", "--edges-per-rod", "6",
         "--load", "stretch-y:0.02", "-o", j("sq.json")])
    compare_solves(rodnet, wd, j("sq.json"), "square")

    # rodnet generate's biaxial and shear loads (docs/lattices.md), with --model.
    run([rodnet, "generate", "honeycomb", "--cells", "3", "--joint-model", "rigid",
         "--edges-per-rod", "6", "--load", "biaxial:0.01,-0.005", "--model", "planar",
         "-o", j("bx.json")])
    with open(j("bx.json")) as f:
        bx = json.load(f)
    check(bx.get("model") == "planar", "generate --model planar writes \"model\"")
    p, _ = compare_solves(rodnet, wd, j("bx.json"), "honeycomb biaxial")
    check(p["reactions"] is not None, "honeycomb biaxial: reactions written")
    run([rodnet, "generate", "square", "--cells", "3", "--edges-per-rod", "6",
         "--load", "shear:0.02", "-o", j("sh.json")])
    p, _ = compare_solves(rodnet, wd, j("sh.json"), "square shear")
    run([rodnet, "generate", "honeycomb", "--periodic", "--joint-model", "rigid",
         "--edges-per-rod", "8", "--load", "shear:0.001", "-o", j("psh.json")])
    with open(j("psh.json")) as f:
        per = json.load(f)["periodic"]
    check(per.get("strain") == [None, None, 0.001], "periodic shear: strain %s" %
          per.get("strain"))
    p, q = compare_solves(rodnet, wd, j("psh.json"), "periodic shear cell")
    d = rel_diff(p["cell"], q["cell"])
    check(d <= TOL, "periodic shear cell: strain and stress agree (%.2e)" % d)
    g12 = p["cell"]["stress"][2] / 0.001
    check(abs(g12 - hom_g12(rodnet, wd)) <= 1e-3 * g12,
          "periodic shear cell: stress / gamma = %.6e = C33 of homogenize (small strain)"
          % g12)
    for bad_args, what in ((["octet", "--load", "shear:0.1"], "need a planar lattice"),
                           (["square", "--load", "biaxial:0.1"], "biaxial:EX,EY"),
                           (["octet", "--model", "planar"], "not planar"),
                           (["square", "--model", "2d"], "planar or 3d")):
        pr = run([rodnet, "generate"] + bad_args + ["-o", j("x.json")], expect=2)
        check(what in pr.stderr, "generate %s: %s" % (" ".join(bad_args),
                                                       pr.stderr.strip().splitlines()[0]))

    # Single rods: a cantilever under an in-plane tip force, the end moment that
    # closes a rod into a circle (bending about z: I22 with d1 = e_z).
    rod = {"name": "beam", "material": "m", "section": "s",
           "line": {"from": [0, 0, 0.5], "to": [1, 0, 0.5], "vertices": 41},
           "d1": [0, 0, 1]}
    import math
    EI = 1.0e7 * 7.853981633974483e-09
    base = {"materials": {"m": {"E": 1.0e7, "nu": 0.5}},
            "sections": {"s": {"shape": "explicit", "A": 3.141592653589793e-4,
                               "I11": 7.853981633974483e-07,
                               "I22": 7.853981633974483e-09, "I12": 0,
                               "J": 1.5707963267948967e-06}},
            "rods": [rod],
            "constraints": [{"type": "clamp", "rod": "beam", "end": "start"}]}
    cant = dict(base, loads=[{"type": "force", "rod": "beam", "vertex": -1,
                              "value": [0, -3 * EI, 0]}])
    with open(j("cant.json"), "w") as f:
        json.dump(cant, f)
    compare_solves(rodnet, wd, j("cant.json"), "cantilever")
    circ = dict(base, loads=[{"type": "moment", "rod": "beam", "vertex": -1,
                              "value": [0, 0, 2 * math.pi * EI]}])
    with open(j("circle.json"), "w") as f:
        json.dump(circ, f)
    compare_solves(rodnet, wd, j("circle.json"), "end-moment circle")

    # The homogenised honeycomb cell: C and the constants; a strain path.
    run([rodnet, "generate", "honeycomb", "--periodic", "--joint-model", "rigid",
         "--edges-per-rod", "8", "-o", j("cell.json")])
    hom = {}
    for m in ("planar", "3d"):
        sc = with_model(j("cell.json"), j("cell_%s.json" % m), m)
        run([rodnet, "homogenize", sc, "-o", j("cell_%s_result.json" % m), "-q"])
        run([rodnet, "homogenize", sc, "--path", "0.02,-0.01,0.01", "--steps", "4",
             "-o", j("cell_%s_path.json" % m), "-q"])
        with open(j("cell_%s_result.json" % m)) as f:
            hom[m] = json.load(f)
        with open(j("cell_%s_path.json" % m)) as f:
            hom[m + "path"] = json.load(f)
    d = rel_diff(hom["planar"]["C"], hom["3d"]["C"])
    check(d <= TOL, "honeycomb cell: C agrees (%.2e)" % d)
    d = rel_diff(hom["planar"]["constants"], hom["3d"]["constants"])
    check(d <= TOL, "honeycomb cell: constants agree (%.2e)" % d)
    check(hom["planar"]["model"]["used"] == "planar", "honeycomb cell: planar reported")
    # bloch_min and acoustic_min differ: the 3D cell has out-of-plane modes too
    keep = lambda path: [[p["strain"], p["stress"], p["energy"]] for p in path]
    pp, qp = keep(hom["planarpath"]["path"]), keep(hom["3dpath"]["path"])
    d = rel_diff(pp, qp)
    check(d <= TOL, "honeycomb cell path: strain, stress, energy agree (%.2e)" % d)

    # Scene checks of "model": "planar": what leaves the plane is named.
    def bad(label, edit, expect):
        sc = with_model(j("cant.json"), j("bad.json"), "planar", edit)
        p = run([rodnet, "solve", sc, "-o", j("bad_result.json")], expect=None)
        check(expect in p.stderr and "planar" in p.stderr,
              "error: %s (%s)" % (label, p.stderr.strip()[:160]))
    bad("a force out of the plane",
        lambda s: s["loads"][0].__setitem__("value", [0, 0, -1]),
        "point force out of the plane")
    bad("a rod off the plane",
        lambda s: s["rods"].append({"name": "b", "material": "m", "section": "s",
                                    "line": {"from": [0, 1, 0], "to": [1, 1, 0],
                                             "vertices": 3}}),
        "off the plane")
    bad("a section without a principal axis along z",
        lambda s: s["rods"][0].__setitem__("d1", [0, 1, 1]),
        "principal axis")
    bad("an unknown model", lambda s: s.__setitem__("model", "2d"), "unknown model")
    check(not os.path.exists(j("bad_result.json")), "no result file after a scene error")
    # Detection: the same scene without "model" solves in 3D and says why it is
    # not planar.
    sc = with_model(j("cant.json"), j("tilted.json"), None,
                    lambda s: s["loads"][0].__setitem__("value", [0, -1e-3, -1e-3]))
    run([rodnet, "solve", sc, "-o", j("tilted_result.json")])
    with open(j("tilted_result.json")) as f:
        m = json.load(f)["model"]
    check(m["used"] == "3d" and m["planar"] is False and "out of the plane" in
          m.get("not_planar", ""), "detection: %s" % m)

    if FAILS:
        sys.exit("%d checks failed" % len(FAILS))


if __name__ == "__main__":
    main()
