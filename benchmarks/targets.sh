#!/usr/bin/env bash
# targets.sh: whole solves for issue 7's targets on the triangular lattice (the
# honeycomb and octet series are precond.sh's part 2 and compress_solve.csv), then
# targets.py over all of them.
#
#   bash benchmarks/targets.sh [BUILD_DIR]            # default build/
#   RN_TARGETS_LARGE=0 bash benchmarks/targets.sh     # without the ~10^6-vertex run
#
# bench_lattice, 8 edges per rod, rigid joints, one process per size (its own peak
# resident size), RODNET_MPI=1 (the DD's multigrid coarse solve needs the MPI runtime):
# - uniaxial stretch 1e-3, tr-krylov + dd from 10^4 to 10^6 vertices, and the exact
#   trust region (tr-minres) as the reference while affordable;
# - compression past buckling (compress-y:5e-2; the flat lattice leaves its plane),
#   both solvers and tr-krylov on the factor preconditioner.
# Writes results/targets_solve.csv (bench_lattice's columns) and prints the tables.
set -euo pipefail
cd "$(dirname "$0")/.."
. benchmarks/solve_env.sh "${1:-build}"

n=0
solve() {
  n=$((n + 1))
  nice "$build/benchmarks/bench_lattice" --kind triangular --edges-per-rod 8 --models rigid \
    --out "$tmp/s$n.csv" "$@"
}
stretch=(20 40 80 120)
[ "${RN_TARGETS_LARGE:-1}" = 1 ] && stretch+=(190)
for c in "${stretch[@]}"; do solve --cells "$c" --load stretch-x:1e-3 --solver tr-krylov --preconditioner dd; done
for c in 20 40 80; do solve --cells "$c" --load stretch-x:1e-3 --solver tr-minres; done
# compression: 10x10 only (tr-krylov with dd took 931 Newton steps there, and 20x20
# ran past 18 min; docs/solvers.md), with tr-krylov on the factor preconditioner's
# norm (the shifted H + sigma D) to separate the DD's norm from the Krylov step, and
# the honeycomb 10x10 likewise (its dd and tr-minres rows: compress_solve.csv)
solve --cells 10 --load compress-y:5e-2 --solver tr-krylov --preconditioner dd
solve --cells 10 --load compress-y:5e-2 --solver tr-minres
solve --cells 10 --load compress-y:5e-2 --solver tr-krylov --preconditioner factor
n=$((n + 1))
nice "$build/benchmarks/bench_lattice" --kind honeycomb --cells 10 --edges-per-rod 8 \
  --models rigid --load compress-y:5e-2 --solver tr-krylov --preconditioner factor \
  --out "$tmp/s$n.csv"
first=1
for f in $(ls "$tmp"/s*.csv | sort -V); do
  if [ $first = 1 ]; then cat "$f"; first=0; else tail -n +2 "$f"; fi
done > "$res/targets_solve.csv.tmp"
mv "$res/targets_solve.csv.tmp" "$res/targets_solve.csv"

"$py" benchmarks/targets.py "$res/precond_solve.csv" "$res/compress_solve.csv" \
  "$res/targets_solve.csv" -o "$res/targets_summary.csv" --plot "$res/targets.png"
