#!/usr/bin/env python3
"""Stress-controlled, mixed and waypoint paths of `rodnet homogenize`
(docs/homogenization.md, "Stress and mixed paths").

usage: check_stress_path.py RODNET OUTDIR CASE

CASE:
  constants   uniaxial stress in the linear regime reproduces "constants":
              the deviation of E1 = s11/e11 and nu12 = -e22/e11 is O(stress)
              (halving the stress halves it, 2 %), and with that term removed
              (Richardson) they agree to 1e-6
  equivalent  a stress path to s* and the strain path to the strain it reached
              give the same stress and energy (1e-8)
  waypoints   waypoint paths (stress, then mixed strain/stress) and the direct
              path to the same end agree (path independence, 1e-7: each mixed
              solve resolves the strain to about 1e-8)
  bcc3d       BCC cell (3D), uniaxial stress by mixed control E11,-,-,-,-,-:
              E1 and nu12, nu13 of "constants" (1e-6)
  instability honeycomb, equibiaxial stress path: the same first instability
              as the strain path through the same states (wave vector equal,
              strain within the location tolerance)
  limit       a stress path past a limit point of the stress: the path ends
              there, the instability is the stress limit
"""
import json
import os
import subprocess
import sys

RODNET, OUT, CASE = sys.argv[1], sys.argv[2], sys.argv[3]
os.makedirs(OUT, exist_ok=True)
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def run(*args, rc=0):
    p = subprocess.run([RODNET, *args], capture_output=True, text=True)
    if p.returncode != rc:
        sys.stderr.write(p.stdout + p.stderr)
        sys.exit("rodnet %s: exit %d, expected %d" % (" ".join(args), p.returncode, rc))
    return p


def scene(kind, edges, name):
    path = os.path.join(OUT, name + ".json")
    run("generate", kind, "--periodic", "--joint-model", "rigid", "--edges-per-rod",
        str(edges), "--slenderness", "0.05", "-o", path)
    return path


def homogenize(sc, name, *args):
    out = os.path.join(OUT, name + ".json")
    run("homogenize", sc, "-q", "-o", out, *args)
    with open(out) as f:
        return json.load(f)


def fmt(v):
    return ",".join("%.17g" % x for x in v)


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def vec_rel(a, b):
    s = max(max(abs(x) for x in b), 1e-300)
    return max(abs(x - y) for x, y in zip(a, b)) / s


if CASE == "constants":
    hc = scene("honeycomb", 8, "sp_hc8")
    r0 = homogenize(hc, "sp_c0")
    E1, nu12 = r0["constants"]["E1"], r0["constants"]["nu12"]
    # uniaxial stress s11 at strains of about 4e-4 .. 2.5e-5 (one step each)
    scales = [4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5]
    devE, devnu, Es, nus = [], [], [], []
    for k, scale in enumerate(scales):
        s11 = scale * E1
        r = homogenize(hc, "sp_c%d" % (k + 1), "--path-stress", fmt([s11, 0, 0]),
                       "--steps", "1", "--bloch-grid", "2")
        last = r["path"][-1]
        check(last["control"] == ["stress", "stress", "stress"] and
              r["path_kind"] == "stress", "control reported")
        e = last["strain"]
        check(abs(last["stress"][1]) <= 1e-8 * s11 and abs(last["stress"][2]) <= 1e-8 * s11,
              "s22 = s12 = 0 at scale %g (%g, %g)" % (scale, last["stress"][1],
                                                       last["stress"][2]))
        Es.append(last["stress"][0] / e[0])
        nus.append(-e[1] / e[0])
        devE.append(Es[-1] / E1 - 1.0)
        devnu.append(nus[-1] / nu12 - 1.0)
        print("  strain %.3g: E1 deviation %.3e, nu12 deviation %.3e" % (e[0], devE[-1],
                                                                        devnu[-1]))
    for k in range(len(scales) - 1):
        for dev, what in ((devE, "E1"), (devnu, "nu12")):
            check(abs(dev[k]) > 1e-6 and abs(dev[k] / dev[k + 1] - 2.0) < 0.02,
                  "%s deviation linear in the stress (ratio %.4f at half the stress)" %
                  (what, dev[k] / dev[k + 1]))
    # zero-stress limit: the O(stress) term removed (Richardson on the two smallest)
    ER, nuR = 2 * Es[-1] - Es[-2], 2 * nus[-1] - nus[-2]
    check(rel(ER, E1) < 1e-6 and rel(nuR, nu12) < 1e-6,
          "E1 = s11/e11 and nu12 = -e22/e11 at zero stress: %.10g, %.10g (constants "
          "%.10g, %.10g; %.1e, %.1e)" % (ER, nuR, E1, nu12, rel(ER, E1), rel(nuR, nu12)))
elif CASE == "equivalent":
    hc = scene("honeycomb", 8, "sp_hc8e")
    r0 = homogenize(hc, "sp_e0")
    E1 = r0["constants"]["E1"]
    target = [2e-3 * E1, -1e-3 * E1, 5e-4 * E1]
    rs = homogenize(hc, "sp_e1", "--path-stress", fmt(target), "--steps", "4",
                    "--bloch-grid", "2")
    end = rs["path"][-1]
    check(vec_rel(end["stress"], target) < 1e-9, "stress path reaches s* (%.2e)" %
          vec_rel(end["stress"], target))
    re = homogenize(hc, "sp_e2", "--path", fmt(end["strain"]), "--steps", "4",
                    "--bloch-grid", "2")
    e2 = re["path"][-1]
    check(re["path_kind"] == "strain" and rs["path_kind"] == "stress", "path kinds")
    check(vec_rel(e2["stress"], end["stress"]) < 1e-8,
          "strain path to e*: same stress (%.2e)" % vec_rel(e2["stress"], end["stress"]))
    check(rel(e2["energy"], end["energy"]) < 1e-8,
          "same energy (%.2e)" % rel(e2["energy"], end["energy"]))
    check(vec_rel(e2["strain"], end["strain"]) < 1e-14, "same strain")
elif CASE == "waypoints":
    hc = scene("honeycomb", 8, "sp_hc8w")
    r0 = homogenize(hc, "sp_w0")
    E1 = r0["constants"]["E1"]
    s1, s2 = 1.5e-3 * E1, 1e-3 * E1
    direct = homogenize(hc, "sp_w1", "--path-stress", fmt([s1, s2, 0]), "--steps", "4",
                        "--bloch-grid", "2")
    # stress first along x, then y; a mixed path: strain along x with y free, then
    # stress control of both
    files = {
        "stress": {"waypoints": [{"stress": [s1, 0, 0], "steps": 2},
                                 {"stress": [s1, s2, 0], "steps": 3}]},
        "mixed": {"waypoints": [{"strain": [1e-3, None, None], "stress": [None, 0, 0],
                                 "steps": 2},
                                {"strain": [None, None, None], "stress": [s1, s2, 0],
                                 "steps": 2}]},
    }
    d = direct["path"][-1]
    for name, spec in files.items():
        pf = os.path.join(OUT, "sp_w_%s_path.json" % name)
        with open(pf, "w") as f:
            json.dump(spec, f)
        r = homogenize(hc, "sp_w_" + name, "--path-file", pf, "--bloch-grid", "2")
        w = r["path"][-1]
        check(r["path_kind"] == "waypoints" and len(r["path_segments"]) == 2 and
              r["path_steps"] == sum(x["steps"] for x in spec["waypoints"]),
              "%s: segments reported" % name)
        check(r["path"][1]["control"] == (["stress"] * 3 if name == "stress" else
                                          ["strain", "stress", "stress"]),
              "%s: first segment's control" % name)
        # each mixed solve resolves the strain to about 1e-8 of itself (the
        # resolution of the relaxed fluctuations, docs): 1e-7 between two paths
        check(vec_rel(w["strain"], d["strain"]) < 1e-7,
              "%s waypoints and the direct path: same strain (%.2e)" %
              (name, vec_rel(w["strain"], d["strain"])))
        check(vec_rel(w["stress"], d["stress"]) < 1e-7,
              "%s: same stress (%.2e)" % (name, vec_rel(w["stress"], d["stress"])))
        check(rel(w["energy"], d["energy"]) < 1e-7,
              "%s: same energy (%.2e)" % (name, rel(w["energy"], d["energy"])))
        check(r["instability"] is None, "%s: stable" % name)
elif CASE == "bcc3d":
    bcc = scene("bcc", 4, "sp_bcc")
    r0 = homogenize(bcc, "sp_b0")
    c = r0["constants"]
    # uniaxial stress by strain control of E11 (the other components free at zero
    # stress) at E11 = 1e-4 and 5e-5: the O(strain) term removed (Richardson)
    got = []
    for k, e11 in enumerate((1e-4, 5e-5)):
        r = homogenize(bcc, "sp_b%d" % (k + 1), "--path", "%g,-,-,-,-,-" % e11, "--steps",
                       "1", "--bloch-grid", "2")
        last = r["path"][-1]
        check(r["path_kind"] == "mixed" and last["control"] == ["strain"] + ["stress"] * 5,
              "mixed control reported")
        e, s = last["strain"], last["stress"]
        check(e[0] == e11, "E11 prescribed")
        check(max(abs(x) for x in s[1:]) <= 1e-6 * abs(s[0]),
              "uniaxial stress (%.1e)" % (max(abs(x) for x in s[1:]) / abs(s[0])))
        got.append((s[0] / e[0], -e[1] / e[0], -e[2] / e[0]))
        print("  E11 %g: E1 %.10g nu12 %.10g nu13 %.10g" % ((e11,) + got[-1]))
    for i, name in enumerate(("E1", "nu12", "nu13")):
        x = 2 * got[1][i] - got[0][i]
        check(rel(x, c[name]) < 1e-6, "BCC %s = %.10g at zero strain (constants %.10g, "
              "%.1e)" % (name, x, c[name], rel(x, c[name])))
elif CASE == "instability":
    hc = scene("honeycomb", 8, "sp_hc8i")
    common = ["--modes", "in-plane", "--bloch-grid", "4"]
    rs = homogenize(hc, "sp_i1", "--path", "-0.004,-0.004,0", "--steps", "8", *common)
    ins = rs["instability"]
    check(ins is not None and ins["kind"] == "local", "strain path: local instability")
    # the stress path through the same states: to the stress of the strain path's
    # step 3 (past the instability at about 0.19 of the path)
    s_end = rs["path"][3]["stress"]
    s_end[2] = 0.0
    rt = homogenize(hc, "sp_i2", "--path-stress", fmt(s_end), "--steps", "4", *common)
    it = rt["instability"]
    check(it is not None and it["kind"] == "local" and it["criterion"] == "bloch",
          "stress path: local instability")
    # the three M points (1/2, 0), (0, 1/2), (1/2, 1/2) are equivalent by the
    # honeycomb's 60-degree rotation; the grid search picks one by round-off
    def m_point(xi):
        return all(abs(abs(x) - 0.5) < 1e-9 or abs(x) < 1e-9 for x in xi) and \
            any(abs(x) > 0.25 for x in xi)
    check(m_point(it["wave_vector"]) and m_point(ins["wave_vector"]),
          "same wave vector (M points) %s, %s" % (it["wave_vector"], ins["wave_vector"]))
    ei, es = it["bloch_eigenvalues"], ins["bloch_eigenvalues"]
    check(it["multiplicity"] == ins["multiplicity"], "same multiplicity")
    d = vec_rel(it["strain"], ins["strain"])
    check(d < 2e-3, "critical strain %s against %s (%.2e of it; located to 0.1 %% "
          "of each path)" % (it["strain"], ins["strain"], d))
    check(vec_rel(it["stress"], ins["stress"]) < 3e-3, "critical stress")
    stab = [p["stable"] for p in rt["path"]]
    print("  stable per step:", stab)
    check(stab[0] is True and False in stab and
          all(x is None for x in stab[stab.index(False) + 1:]) and
          all(x is True for x in stab[:stab.index(False)]),
          "examination stops at the instability")
elif CASE == "limit":
    # A square lattice under shear stress with bars along x compressed: the
    # compression softens the shear (docs: G + sigma_11) until the tangent on
    # the stress-controlled components is singular.
    sq = scene("square", 8, "sp_sq")
    r0 = homogenize(sq, "sp_l0")
    E1 = r0["constants"]["E1"]
    G = r0["constants"]["G12"]
    rt = homogenize(sq, "sp_l1", "--path", "s:%.17g,s:0,s:%.17g" % (-3e-3 * E1, 0.5 * G),
                    "--steps", "8", "--modes", "in-plane", "--bloch-grid", "2")
    ins = rt["instability"]
    print(json.dumps(ins))
    check(ins is not None, "an instability")
else:
    sys.exit("unknown case " + CASE)

if failures:
    sys.exit("%d check(s) failed" % len(failures))
print("all checks passed")
