#!/usr/bin/env python3
"""Whole-process cost of the `rodnet` command around the solver: start-up and output.

    python3 benchmarks/bench_startup.py [--rodnet build/rodnet] [--sizes 401]
                                        [--repeats 21] [--out startup.csv]

For each size N it writes the issue's cantilever (L = 1, circle r = 0.01, E = 1e7,
nu = 0.5, clamped first edge at x = 0, N vertices evenly on [0, L], tip load along
-z with P L^2 / (E I) = 5) into a temporary folder and times, as separate processes:

  version          `rodnet --version`: process start and dynamic loading only
  solve            `rodnet solve SCENE -o RESULT.json --quiet`; the row's median and
                   min are of (wall time - time_s), time_s being the solve time that
                   RESULT.json reports: start-up, scene reading and result writing
  solve-mpi1       the same with RODNET_MPI=1: MPI initialised as a singleton, as
                   every run did before rodnet initialised MPI only under a launcher
                   (docs/cli.md, "MPI")

Runs alternate between the cases so that the machine's load affects them alike.
A run that fails or does not converge makes the script fail; times are never
asserted.  CSV columns: commit, compiler, flags, ranks, bench (startup), case, size
(vertices; 0 for version), repeats, median, min, then wall_median, wall_min and
solve_median (the time_s median).  commit, compiler and flags come from the
benchmarks' bench_config.h of the build that holds the rodnet binary (--commit
overrides the commit, e.g. for a build of an older tree).
"""
import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_csv  # noqa: E402


def write_cantilever(path, n):
    EI = 1e7 * math.pi * 0.01 ** 4 / 4.0
    P = 5.0 * EI  # alpha = P L^2 / (E I) = 5, L = 1
    scene = {
        "description": f"the issue's cantilever, {n} vertices, P L^2 / EI = 5",
        "materials": {"steel": {"E": 1.0e7, "nu": 0.5}},
        "sections": {"wire": {"shape": "circle", "radius": 0.01}},
        "rods": [{"name": "beam", "material": "steel", "section": "wire",
                  "line": {"from": [0, 0, 0], "to": [1, 0, 0], "vertices": n},
                  "d1": [0, 1, 0]}],
        "constraints": [{"type": "clamp", "rod": "beam", "end": "start"}],
        "loads": [{"type": "force", "rod": "beam", "vertex": -1, "value": [0, 0, -P]}],
    }
    with open(path, "w") as f:
        json.dump(scene, f)


def run(cmd, env=None):
    t0 = time.perf_counter()
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        sys.exit(f"bench_startup: {' '.join(cmd)} exited with {p.returncode}:\n"
                 f"{p.stderr.decode(errors='replace')}")
    return wall


def make_jobs(rodnet, tmp, sizes, cases):
    """The commands to time: (case, size, command, environment, result path or None);
    the cantilever scenes written into tmp."""
    env_serial = dict(os.environ)
    env_serial.pop("RODNET_MPI", None)
    env_mpi = dict(env_serial, RODNET_MPI="1")
    jobs = []
    if "version" in cases:
        jobs.append(("version", 0, [rodnet, "--version"], env_serial, None))
    for n in sizes:
        scene = os.path.join(tmp, f"cantilever_{n}.json")
        write_cantilever(scene, n)
        for case, env in (("solve", env_serial), ("solve-mpi1", env_mpi)):
            if case in cases:
                res = os.path.join(tmp, f"{case}_{n}.json")
                jobs.append((case, n, [rodnet, "solve", scene, "-o", res, "--quiet"], env,
                             res))
    return jobs


def time_jobs(jobs, repeats):
    """Every job repeats times, interleaved: per (case, size) the wall times and the
    solves' time_s (0 for jobs without a result); exits if a solve did not converge."""
    walls = {j[:2]: [] for j in jobs}
    solves = {j[:2]: [] for j in jobs}
    for _ in range(repeats):
        for case, n, cmd, env, res in jobs:
            wall = run(cmd, env)
            solve = 0.0
            if res:
                with open(res) as f:
                    result = json.load(f)
                if not result.get("converged"):
                    sys.exit(f"bench_startup: {case} {n}: not converged")
                solve = float(result["time_s"])
            walls[(case, n)].append(wall)
            solves[(case, n)].append(solve)
    return walls, solves


def summary_row(prov, case, n, repeats, w, s):
    """The CSV row of one (case, size) from its wall times w and solve times s
    (printed as a line on stderr too)."""
    over = [a - b for a, b in zip(w, s)]
    print(f"bench_startup: {case:11s} {n:6d} vertices: wall - time_s median "
          f"{statistics.median(over) * 1e3:8.1f} ms (min {min(over) * 1e3:.1f}), "
          f"wall median {statistics.median(w) * 1e3:.1f} ms, solve median "
          f"{statistics.median(s) * 1e3:.1f} ms", file=sys.stderr)
    return [prov["commit"], prov["compiler"], prov["flags"], 1, "startup", case, n, repeats,
            f"{statistics.median(over):.6e}", f"{min(over):.6e}",
            f"{statistics.median(w):.6e}", f"{min(w):.6e}", f"{statistics.median(s):.6e}"]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rodnet", default="build/rodnet", help="the rodnet command")
    ap.add_argument("--sizes", default="401", help="cantilever vertex counts, e.g. 401,3201")
    ap.add_argument("--repeats", type=int, default=21)
    ap.add_argument("--cases", default="version,solve,solve-mpi1")
    ap.add_argument("--commit", help="commit to record instead of the build's")
    ap.add_argument("--out", help="CSV to write (default: standard output)")
    args = ap.parse_args()
    sizes = [int(s) for s in args.sizes.split(",")]
    cases = args.cases.split(",")
    unknown = set(cases) - {"version", "solve", "solve-mpi1"}
    if unknown or args.repeats < 1 or min(sizes) < 3:
        sys.exit(f"bench_startup: bad --cases {sorted(unknown)}, --repeats or --sizes")
    prov = bench_csv.provenance(args.rodnet, args.commit)
    with tempfile.TemporaryDirectory(prefix="rodnet_startup_") as tmp:
        jobs = make_jobs(args.rodnet, tmp, sizes, cases)
        walls, solves = time_jobs(jobs, args.repeats)
        rows = [summary_row(prov, case, n, args.repeats, walls[(case, n)],
                            solves[(case, n)]) for case, n, _, _, _ in jobs]
    out = open(args.out, "w", newline="") if args.out else sys.stdout
    wr = csv.writer(out)
    wr.writerow(["commit", "compiler", "flags", "ranks", "bench", "case", "size", "repeats",
                 "median", "min", "wall_median", "wall_min", "solve_median"])
    wr.writerows(rows)
    if args.out:
        out.close()

if __name__ == "__main__":
    main()
