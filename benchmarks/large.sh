#!/usr/bin/env bash
# large.sh: issue 7's size targets, whole solves from 10^4 to 10^6 vertices under
# uniaxial stretch (1e-3) with tr-krylov and the default preconditioner (dd), the
# honeycomb and the octet block, 8 edges per rod, rigid joints; one bench_lattice
# process per size (its own peak resident size), RODNET_MPI=1 (the DD's multigrid
# coarse solve past 5e10 flops of the direct one needs the MPI runtime).
#
#   bash benchmarks/large.sh [BUILD_DIR]               # default build/
#   RN_LARGE_HUGETLB=1 bash benchmarks/large.sh        # with transparent huge pages
#
# Writes results/large_solve.csv (bench_lattice's columns), then targets.py over it:
# results/large_summary.csv (MINRES per Newton step, fitted exponents of time and
# memory against DOFs) and results/large.png.  About 5 minutes, 7 GB at the largest.
set -euo pipefail
cd "$(dirname "$0")/.."
. benchmarks/solve_env.sh "${1:-build}"
if [ "${RN_LARGE_HUGETLB:-0}" = 1 ]; then export GLIBC_TUNABLES=glibc.malloc.hugetlb=1; fi
n=0
solve() {
  n=$((n + 1))
  "$build/benchmarks/bench_lattice" --edges-per-rod 8 --models rigid \
    --load stretch-x:1e-3 --solver tr-krylov --preconditioner dd --out "$tmp/s$n.csv" "$@"
}
for c in 20 40 80 120 190; do solve --kind honeycomb --cells "$c"; done
for c in 4 6 8 10 12 14 16; do solve --kind octet --cells "$c"; done
first=1
for f in $(ls "$tmp"/s*.csv | sort -V); do
  if [ $first = 1 ]; then cat "$f"; first=0; else tail -n +2 "$f"; fi
done > "$res/large_solve.csv.tmp"
mv "$res/large_solve.csv.tmp" "$res/large_solve.csv"
"$py" benchmarks/targets.py "$res/large_solve.csv" -o "$res/large_summary.csv" \
  --plot "$res/large.png"
