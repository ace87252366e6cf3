#!/usr/bin/env python3
"""bench_sweep.py - issue 24 section 4's throughput of `rodnet sweep` on 1 and N
ranks: the whole command as a user waits for it (`rodnet sweep` or `mpirun -n N
rodnet sweep` into a fresh folder, plot not drawn), median and minimum of
--repeats runs, points per second, and the points each rank computed.

Cases:
  honeycomb-paths  the honeycomb sweep of 20 relative densities (0.02 to 0.3, log),
                   rigid joints, 16 edges per strut, each point homogenised and
                   followed along equibiaxial compression to -0.02 in 20 steps
                   (in-plane Bloch modes) to its first instability
  honeycomb-C      the same 20 points without the path (C only)

CSV columns: commit, compiler, flags, ranks, bench (sweep), case, size (points),
repeats, median, min (seconds of the whole command), points_per_s (from the
median), speedup (1-rank median over this median, same run), peak_rss_mb (the
largest rank), exit_status.

    /usr/bin/python3 benchmarks/bench_sweep.py --rodnet build/rodnet \\
        --out benchmarks/results/sweep.csv [--ranks 1,2] [--repeats 3]
"""
import argparse
import csv
import json
import os
import shutil
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_csv  # noqa: E402

BASE = {"lattice": "honeycomb", "joint_model": "rigid",
        "relative_density": {"from": 0.02, "to": 0.3, "count": 20, "scale": "log"},
        "edges_per_rod": 16}
CASES = {
    "honeycomb-paths": dict(BASE, path={"strain": [-0.02, -0.02, 0], "steps": 20,
                                        "modes": "in-plane"}),
    "honeycomb-C": BASE,
}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rodnet", default="build/rodnet")
    ap.add_argument("--mpiexec", default="mpiexec")
    ap.add_argument("--out", required=True)
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cases", default=",".join(CASES))
    a = ap.parse_args()
    ranks = [int(r) for r in a.ranks.split(",")]
    names = bench_csv.pick_cases(a.cases, CASES, "bench_sweep")
    env = bench_csv.mpi_env()
    prov = bench_csv.provenance(a.rodnet)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            spec = os.path.join(tmp, name + ".json")
            with open(spec, "w") as f:
                json.dump(CASES[name], f)
            npoints = CASES[name]["relative_density"]["count"]
            one = None
            for n in ranks:
                folder = os.path.join(tmp, "%s_%d" % (name, n))
                cmd = ([a.rodnet] if n == 1 else [a.mpiexec, "-n", str(n), a.rodnet]) + \
                    ["sweep", spec, "-o", folder, "-q"]
                times, rss, status = [], 0.0, 0
                for _ in range(a.repeats):
                    shutil.rmtree(folder, ignore_errors=True)  # every point computed
                    wall, status, mb = bench_csv.run_once(cmd, env)
                    times.append(wall)
                    rss = max(rss, mb)
                med = statistics.median(times)
                one = med if n == 1 else one
                rows.append([prov["commit"], prov["compiler"], prov["flags"], n, "sweep",
                             name, npoints, a.repeats, "%.4f" % med, "%.4f" % min(times),
                             "%.3f" % (npoints / med), "%.3f" % (one / med) if one else "",
                             "%.1f" % rss, status])
                print("bench_sweep: %s on %d rank(s): median %.3f s (min %.3f, %d runs), "
                      "%.2f points/s, exit %d" % (name, n, med, min(times), a.repeats,
                                                  npoints / med, status), file=sys.stderr)
    tmp_out = a.out + ".tmp"
    with open(tmp_out, "w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(["commit", "compiler", "flags", "ranks", "bench", "case", "size",
                     "repeats", "median", "min", "points_per_s", "speedup", "peak_rss_mb",
                     "exit_status"])
        wr.writerows(rows)
    os.replace(tmp_out, a.out)


if __name__ == "__main__":
    main()
