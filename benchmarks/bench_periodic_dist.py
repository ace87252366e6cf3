#!/usr/bin/env python3
"""bench_periodic_dist.py - issue 24 section 1: periodic supercells on 1 and N ranks,
the whole command as a user waits for it, median and minimum of --repeats runs.

For each supercell (written once by `rodnet generate KIND --periodic --cells ...`,
rigid joints; the generate time is measured too, as the `generate` step):
  homogenize  `rodnet homogenize CELL -o R.json -q` (1 rank: the one-process sparse
              Cholesky of the fluctuation block) or `mpirun -n N rodnet homogenize`
              (the distributed Schur complement: MINRES with the rod-level DD)
  solve       `rodnet solve` of the cell under a uniaxial macroscopic stress (the
              other components free), default solver on 1 rank (`tr-minres`) and on N
              (`tr-krylov` with `dd`); stability check and RESULT.json included
  path        `rodnet homogenize CELL --path P --steps N` (--path; the whole path with
              its first instability: on 1 rank the Bloch search over the supercell's
              zone, on N the cell-periodic and long-wavelength tests on the parts)

CSV columns: commit, compiler, flags, ranks, bench (periodic), case (the cell),
step (generate, homogenize, solve), size (reduced DOFs), repeats, median, min
(seconds of the whole command), speedup (the 1-rank median of the same step over
this median, same run), peak_rss_mb (the largest rank), exit_status.

    /usr/bin/python3 benchmarks/bench_periodic_dist.py --rodnet build/rodnet \\
        --out benchmarks/results/periodic_dist.csv [--ranks 1,2] [--repeats 3] \\
        [--cases hc25,hc50,hc100,octet6] [--steps homogenize,solve,path] \\
        [--path=-0.004,-0.004,0 --path-steps 10]

The dhc cases are disordered honeycomb supercells on the planar model (joints moved
by up to 2 % of the bar length, sections scattered by 5 %: `--perturb 0.02
--section-scatter 0.05 --model planar`), for the paths through buckling.
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_csv  # noqa: E402

CASES = {
    "hc25": ["honeycomb", "--cells", "25,25", "--edges-per-rod", "4"],
    "hc50": ["honeycomb", "--cells", "50,50", "--edges-per-rod", "4"],
    "hc100": ["honeycomb", "--cells", "100,100", "--edges-per-rod", "4"],
    "octet6": ["octet", "--cells", "6,6,6", "--edges-per-rod", "2"],
    "dhc25": ["honeycomb", "--cells", "25,25", "--edges-per-rod", "4", "--perturb", "0.02",
              "--section-scatter", "0.05", "--model", "planar"],
    "dhc50": ["honeycomb", "--cells", "50,50", "--edges-per-rod", "4", "--perturb", "0.02",
              "--section-scatter", "0.05", "--model", "planar"],
    "dhc100": ["honeycomb", "--cells", "100,100", "--edges-per-rod", "4", "--perturb",
               "0.02", "--section-scatter", "0.05", "--model", "planar"],
}
DEFAULT_CASES = "hc25,hc50,hc100,octet6"


def timed(cmd, env, repeats):
    times, rss, status = [], 0.0, 0
    for _ in range(repeats):
        wall, status, mb = bench_csv.run_once(cmd, env)
        times.append(wall)
        rss = max(rss, mb)
    return statistics.median(times), min(times), rss, status


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rodnet", default="build/rodnet")
    ap.add_argument("--mpiexec", default="mpiexec")
    ap.add_argument("--out", required=True)
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cases", default=DEFAULT_CASES)
    ap.add_argument("--steps", default="homogenize,solve")
    ap.add_argument("--path", default="-0.004,-0.004,0")
    ap.add_argument("--path-steps", type=int, default=10)
    a = ap.parse_args()
    ranks = [int(r) for r in a.ranks.split(",")]
    names = bench_csv.pick_cases(a.cases, CASES, "bench_periodic_dist")
    env = bench_csv.mpi_env()
    prov = bench_csv.provenance(a.rodnet)
    rows = []

    def row(n, name, step, size, med, mn, one, rss, status):
        rows.append([prov["commit"], prov["compiler"], prov["flags"], n, "periodic", name,
                     step, size, a.repeats, "%.4f" % med, "%.4f" % mn,
                     "%.3f" % (one / med) if one else "", "%.1f" % rss, status])
        print("bench_periodic_dist: %s %s on %d rank(s): median %.3f s (min %.3f), "
              "exit %d" % (name, step, n, med, mn, status), file=sys.stderr)

    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            cell = os.path.join(tmp, name + ".json")
            gen = [a.rodnet, "generate", CASES[name][0], "--periodic"] + \
                CASES[name][1:] + ["--joint-model", "rigid", "-o", cell]
            med, mn, rss, status = timed(gen, env, a.repeats)
            out = os.path.join(tmp, "r.json")
            subprocess.run([a.rodnet, "homogenize", cell, "-o", out, "-q"], env=env,
                           check=True, capture_output=True)
            h = json.load(open(out))
            size = h["fluctuation_dofs"] + len(h["C"])
            row(1, name, "generate", size, med, mn, med, rss, status)
            stressed = os.path.join(tmp, name + "_stress.json")
            scene = json.load(open(cell))
            ns = len(h["C"])
            scene["periodic"]["stress"] = [1e-4 * h["C"][0][0]] + [0.0] * (ns - 1)
            json.dump(scene, open(stressed, "w"))
            steps = {"homogenize": ["homogenize", cell], "solve": ["solve", stressed],
                     "path": ["homogenize", cell, "--path", a.path, "--steps",
                              str(a.path_steps)]}
            for step in a.steps.split(","):
                args = steps[step]
                one = None
                for n in ranks:
                    cmd = ([a.rodnet] if n == 1 else
                           [a.mpiexec, "-n", str(n), a.rodnet]) + args + ["-o", out, "-q"]
                    med, mn, rss, status = timed(cmd, env, a.repeats)
                    one = med if n == 1 else one
                    row(n, name, step, size, med, mn, one, rss, status)
    tmp_out = a.out + ".tmp"
    with open(tmp_out, "w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(["commit", "compiler", "flags", "ranks", "bench", "case", "step",
                     "size", "repeats", "median", "min", "speedup", "peak_rss_mb",
                     "exit_status"])
        wr.writerows(rows)
    os.replace(tmp_out, a.out)


if __name__ == "__main__":
    main()
