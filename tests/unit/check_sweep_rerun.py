#!/usr/bin/env python3
"""Issue 22 item 1: a `rodnet sweep` rerun into the same folder after a change of a
parameter that is not one of the lists (E, nu, cells, edges_per_rod, perturb)
recomputes the points, and only an unchanged sweep file skips them ("done
before").  Every point file records every key of the sweep file (with its value
at that point), the rodnet version and the cell scene's hash.

Usage: check_sweep_rerun.py RODNET DIR"""
import csv
import json
import os
import subprocess
import sys

KEYS = ["lattice", "joint_model", "relative_density", "seed", "perturb",
        "edges_per_rod", "cells", "E", "nu"]


def run(rodnet, spec, out, name):
    path = os.path.join(out, name + ".json")
    with open(path, "w") as f:
        json.dump(spec, f)
    r = subprocess.run([rodnet, "sweep", path, "-o", os.path.join(out, "sweep")],
                       capture_output=True, text=True)
    text = r.stdout + r.stderr
    print(f"--- {name}: exit {r.returncode}\n{text.strip()}")
    if r.returncode != 0:
        sys.exit(f"FAILED: {name} exited {r.returncode}")
    with open(os.path.join(out, "sweep", "sweep.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    return "(done before)" in text, rows


def main():
    rodnet, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    for name in os.listdir(os.path.join(out, "sweep")) if os.path.isdir(
            os.path.join(out, "sweep")) else []:
        os.remove(os.path.join(out, "sweep", name))
    ok = True
    base = {"lattice": "honeycomb", "relative_density": [0.05, 0.1], "edges_per_rod": 4}
    skipped, rows0 = run(rodnet, base, out, "base")
    ok &= not skipped and len(rows0) == 2
    skipped, rows = run(rodnet, base, out, "same")
    ok &= skipped and [r["E1"] for r in rows] == [r["E1"] for r in rows0]
    # E 1000 times larger: E1 1000 times larger (not the old CSV again)
    skipped, rows = run(rodnet, dict(base, E=1000), out, "E")
    ratio = [float(a["E1"]) / float(b["E1"]) for a, b in zip(rows, rows0)]
    print("E1 ratios after E = 1000:", ratio)
    ok &= not skipped and all(abs(q / 1000 - 1) < 1e-6 for q in ratio)
    for key, value in (("nu", 0.25), ("cells", [2, 1]), ("edges_per_rod", 5),
                       ("perturb", 0.05)):
        skipped, rows = run(rodnet, dict(base, **{key: value}), out, key)
        print(f"{key} = {value}: {'skipped (WRONG)' if skipped else 'recomputed'}")
        ok &= not skipped
    # a path (issue 24 section 4): in the record; another number of steps, or
    # another end, recomputes
    path = {"strain": [-0.002, -0.002, 0], "steps": 2, "modes": "in-plane"}
    skipped, rows = run(rodnet, dict(base, path=path), out, "path")
    ok &= not skipped and rows[0].get("instability") in ("none", "local", "macroscopic")
    skipped, rows = run(rodnet, dict(base, path=path), out, "path_same")
    ok &= skipped
    for key, value in (("steps", 3), ("strain", [-0.003, -0.002, 0]),
                       ("bloch_method", "dense")):
        skipped, rows = run(rodnet, dict(base, path=dict(path, **{key: value})), out,
                            "path_" + key)
        print(f"path {key} = {value}: {'skipped (WRONG)' if skipped else 'recomputed'}")
        ok &= not skipped
    with open(os.path.join(out, "sweep", "point_0000.json")) as f:
        rec = json.load(f).get("parameters", {}).get("path")
    print("path record:", rec)
    ok &= rec == {"strain": [-0.002, -0.002, 0], "steps": 2, "modes": "in-plane",
                  "bloch_method": "dense"}
    skipped, rows = run(rodnet, dict(base, perturb=0.05), out, "no_path")
    # the record of a point
    with open(os.path.join(out, "sweep", "point_0000.json")) as f:
        p = json.load(f)
    rec = p.get("parameters", {})
    missing = [k for k in KEYS if k not in rec]
    print("record:", json.dumps(rec), p.get("rodnet_version"), p.get("scene_hash"))
    ok &= not missing and rec.get("perturb") == 0.05 and rec.get("relative_density") == 0.05
    ok &= isinstance(p.get("rodnet_version"), str) and \
        str(p.get("scene_hash", "")).startswith("fnv1a64:")
    if missing:
        print("missing from the record:", missing)
    print("OK" if ok else "FAILED")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
