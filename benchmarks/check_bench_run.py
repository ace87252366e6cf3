#!/usr/bin/env python3
"""Check a `rodnet bench` output directory against the contract (docs/benchmarking.md).

    check_bench_run.py DIR --problems A,B --solvers X,Y [--reference-solver S]

Asserts: DIR/runs.csv has the contract's columns and exactly one row per problem and
solver; the machine columns are filled; counters are non-negative integers, times
positive; verified_minimum is 0 or 1 for converged runs; the reference solver
converged on every problem to a verified minimum within 1e-6 of the stored reference
answer; DIR/profile_time.png, profile_hvp.png and data_profile.png are PNG files and
profile_summary.csv lists every solver.  Exit 1 with the reasons otherwise.
"""
import argparse
import csv
import os
import sys

CONTRACT = ["problem", "solver", "converged", "verified_minimum", "iterations",
            "gradients", "hvps", "krylov_iterations", "gradient_norm", "error", "time_s"]
MACHINE = ["commit", "compiler", "flags", "cpu", "cores", "blas"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--problems", required=True)
    ap.add_argument("--solvers", required=True)
    ap.add_argument("--reference-solver", default="tr-minres")
    a = ap.parse_args()
    bad = []
    with open(os.path.join(a.dir, "runs.csv"), newline="") as f:
        rd = csv.DictReader(f)
        cols = rd.fieldnames or []
        rows = list(rd)
    bad += [f"runs.csv: no column '{c}'" for c in CONTRACT + MACHINE if c not in cols]
    if bad:
        sys.exit("\n".join(bad))
    problems, solvers = a.problems.split(","), a.solvers.split(",")
    pairs = [(r["problem"], r["solver"]) for r in rows]
    want = [(p, s) for p in problems for s in solvers]
    if sorted(pairs) != sorted(want):
        bad.append(f"runs.csv: rows {sorted(pairs)} != problems x solvers {sorted(want)}")
    for r in rows:
        tag = f"{r['problem']}/{r['solver']}"
        for c in ("iterations", "gradients", "hvps", "krylov_iterations"):
            if not r[c].isdigit():
                bad.append(f"{tag}: {c} = '{r[c]}' is not a count")
        if not float(r["time_s"]) > 0:
            bad.append(f"{tag}: time_s = {r['time_s']}")
        if r["converged"] not in ("0", "1"):
            bad.append(f"{tag}: converged = '{r['converged']}'")
        if r["converged"] == "1" and r["verified_minimum"] not in ("0", "1"):
            bad.append(f"{tag}: converged but verified_minimum = '{r['verified_minimum']}'")
        for c in MACHINE:
            if r[c] in ("", "unknown"):
                bad.append(f"{tag}: machine column {c} empty")
        if r["solver"] == a.reference_solver:
            if r["converged"] != "1" or r["verified_minimum"] != "1":
                bad.append(f"{tag}: the reference solver did not reach a verified minimum")
            if r["error"] == "" or float(r["error"]) > 1e-6:
                bad.append(f"{tag}: error against the reference answer '{r['error']}'")
    for png in ("profile_time.png", "profile_hvp.png", "data_profile.png"):
        path = os.path.join(a.dir, png)
        with open(path, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                bad.append(f"{png}: not a PNG file")
    with open(os.path.join(a.dir, "profile_summary.csv"), newline="") as f:
        listed = {r["solver"] for r in csv.DictReader(f) if r["scope"] == "all"}
    if listed != set(solvers):
        bad.append(f"profile_summary.csv: solvers {sorted(listed)} != {sorted(solvers)}")
    if bad:
        sys.exit("check_bench_run.py: " + "\n  ".join(bad))
    print(f"check_bench_run.py: {len(rows)} runs, profiles and summary as required")


if __name__ == "__main__":
    main()
