#!/usr/bin/env python3
"""Issue 24 section 4: `mpirun -np N rodnet sweep` spreads the points over the ranks.

- A sweep with a strain path (6 densities of the honeycomb, each to its first
  instability) on 1 rank and on NP ranks: the same CSV (every column but the
  times; C, the constants and the critical strain to 1e-12 relative), each point
  file written once, one progress bar (rank 0 only: every point once on stderr)
  and one summary line.
- A rerun on NP ranks skips every point ("done before", no point file rewritten);
  after two point files are removed it recomputes exactly those two.
- Failing points (the dense Bloch analysis asked for a cell beyond it) are each
  reported once, by rank 0, with the point and the reason; exit status 4 on every
  rank; the CSV is written without them.

Usage: check_sweep_mpi.py RODNET MPIEXEC NP DIR"""
import csv
import json
import os
import shutil
import subprocess
import sys

SPEC = {"lattice": "honeycomb", "joint_model": "rigid",
        "relative_density": {"from": 0.03, "to": 0.2, "count": 6},
        "edges_per_rod": 6,
        "path": {"strain": [-0.02, -0.02, 0], "steps": 10, "modes": "in-plane"}}
FAIL = {"lattice": "honeycomb", "relative_density": [0.05, 0.1, 0.2],
        "edges_per_rod": 4, "cells": [10, 10],
        "path": {"strain": [-0.01, -0.01, 0], "steps": 2, "modes": "in-plane",
                 "bloch_method": "dense"}}
NUMERIC = ["relative_density", "E1", "E2", "nu12", "G12", "critical_load_factor"]
VECTORS = ["critical_strain", "critical_stress", "wave_vector"]


def run(cmd, name):
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    err = r.stderr.replace("\r", "\n")
    print(f"--- {name}: exit {r.returncode}\n{r.stdout.strip()}")
    return r.returncode, r.stdout, err


def rows(folder):
    with open(os.path.join(folder, "sweep.csv"), newline="") as f:
        return list(csv.DictReader(f))


def close(a, b, tol=1e-12):
    return abs(a - b) <= tol * max(abs(a), abs(b), 1e-300)


def same_rows(r1, r2):
    if len(r1) != len(r2):
        print(f"{len(r1)} rows against {len(r2)}")
        return False
    ok = True
    for a, b in zip(r1, r2):
        for k in a:
            if k in ("time_s",):
                continue
            if k in NUMERIC:
                good = (a[k] == b[k]) or close(float(a[k]), float(b[k]))
            elif k in VECTORS:
                va, vb = a[k].split(), b[k].split()
                good = len(va) == len(vb) and all(
                    close(float(x), float(y)) or abs(float(x) - float(y)) < 1e-300
                    for x, y in zip(va, vb))
            else:
                good = a[k] == b[k]
            if not good:
                print(f"point {a['index']}: {k} {a[k]} against {b[k]}")
                ok = False
    return ok


def mtimes(folder):
    return {n: os.stat(os.path.join(folder, n)).st_mtime_ns
            for n in os.listdir(folder) if n.startswith("point_") and
            not n.endswith(".scene.json")}


def main():
    rodnet, mpiexec, np_, out = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    spec = os.path.join(out, "sweep.json")
    with open(spec, "w") as f:
        json.dump(SPEC, f)
    mpi = [mpiexec, "-q", "-n", np_, rodnet, "sweep", spec]
    one, many = os.path.join(out, "one"), os.path.join(out, "many")
    ok = True

    rc, so, err = run([rodnet, "sweep", spec, "-o", one], "1 rank")
    ok &= rc == 0
    rc, so, err = run(mpi + ["-o", many], f"{np_} ranks")
    ok &= rc == 0
    ok &= so.count("rodnet sweep: 6 points (0 failed)") == 1 and f"({np_} ranks)" in so
    bars = [ln for ln in err.split("\n") if ln.startswith("rodnet sweep: [")]
    shown = sorted(int(ln.split("] ")[1].split("/")[0]) for ln in bars)
    print(f"progress lines: {len(bars)}, counts {shown}")
    ok &= shown == list(range(1, 7))  # one bar: every point once
    r1, rn = rows(one), rows(many)
    ok &= len(r1) == 6 and all(r["instability"] == "local" for r in r1)
    ok &= same_rows(r1, rn)
    for r in rn:
        print(f"  rho {float(r['relative_density']):.4f}: {r['instability']} at "
              f"E11 {r['critical_strain'].split()[0]} xi {r['wave_vector']}")

    # rerun: nothing recomputed; two removed points recomputed, the others kept
    before = mtimes(many)
    rc, so, err = run(mpi + ["-o", many], f"{np_} ranks, rerun")
    ok &= rc == 0 and err.count("(done before)") >= 1 and mtimes(many) == before
    for n in ("point_0001.json", "point_0004.json"):
        os.remove(os.path.join(many, n))
    rc, so, err = run(mpi + ["-o", many], f"{np_} ranks, two points removed")
    after = mtimes(many)
    changed = sorted(n for n in after if after[n] != before.get(n))
    print("recomputed:", changed)
    ok &= rc == 0 and changed == ["point_0001.json", "point_0004.json"]
    ok &= same_rows(r1, rows(many))

    # failing points: one message each, by rank 0; exit 4; the CSV without them
    fail = os.path.join(out, "fail.json")
    with open(fail, "w") as f:
        json.dump(FAIL, f)
    rc, so, err = run([mpiexec, "-q", "-n", np_, rodnet, "sweep", fail, "-o",
                       os.path.join(out, "fail")], f"{np_} ranks, failing points")
    msgs = [ln for ln in err.split("\n") if "the dense Bloch analysis takes at most" in ln]
    print("\n".join(msgs))
    ok &= rc == 4 and len(msgs) == 3 and \
        sorted(ln.split("point ")[1].split(" ")[0] for ln in msgs) == ["0", "1", "2"]
    ok &= "3 points (3 failed)" in so and rows(os.path.join(out, "fail")) == []
    print("OK" if ok else "FAILED")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
