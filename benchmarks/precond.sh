#!/usr/bin/env bash
# precond.sh: the preconditioner study of docs/solvers.md ("Preconditioners for
# networks") on honeycomb and octet lattices from 10^3 to 10^6 vertices (8 edges per
# rod, uniaxial stretch 1e-3), then plot_precond.py.
#
#   bash benchmarks/precond.sh [BUILD_DIR]          # default build/
#   RN_PRECOND_QUICK=1 bash benchmarks/precond.sh   # up to ~10^5 vertices only
#
# 1. bench_precond: one Newton system (at the displaced initial state) per
#    preconditioner: every one while the exact factorisation is affordable, then the
#    DD (automatic coarse solve, and AMG coarse solve) alone -> results/precond.csv.
# 2. bench_lattice: whole rn_solve runs, tr-krylov with the default preconditioner
#    (dd) at every size, and the exact trust region (tr-minres) as the reference
#    while affordable -> results/precond_solve.csv (with the peak resident size).
# The runs set RODNET_MPI=1: MueLu (the DD's AMG coarse solve) needs the MPI runtime
# in Trilinos 13.2.  The large cases need ~10 GB and minutes each on a 2-core machine.
set -euo pipefail
cd "$(dirname "$0")/.."
. benchmarks/solve_env.sh "${1:-build}"

hc_small=(10 20 40) hc_large=(80 120 190)
oc_small=(3 4 6) oc_large=(8 11 14 16)
if [ "${RN_PRECOND_QUICK:-0}" = 1 ]; then hc_large=(80); oc_large=(8); fi

# 1. One Newton system per preconditioner.
rm -f "$res/precond.csv"
sys() { nice "$build/benchmarks/bench_precond" --edges-per-rod 8 --load stretch-x:1e-3 \
          --out "$res/precond.csv" "$@"; }
for c in "${hc_small[@]}"; do
  sys --kind honeycomb --cells "$c" --models rigid,elastic \
    --precond dd,dd-direct,dd-amg,muelu,ifpack2,factor
done
for c in "${oc_small[@]}"; do
  sys --kind octet --cells "$c" --models rigid,elastic \
    --precond dd,dd-direct,dd-amg,muelu,ifpack2,factor
done
for c in "${hc_large[@]}"; do sys --kind honeycomb --cells "$c" --models rigid --precond dd,dd-amg; done
for c in "${oc_large[@]}"; do sys --kind octet --cells "$c" --models rigid --precond dd,dd-amg; done

# 2. Whole solves (one bench_lattice process per size: its own peak resident size).
n=0
solve() {
  n=$((n + 1))
  nice "$build/benchmarks/bench_lattice" --edges-per-rod 8 --load stretch-x:1e-3 \
    --models rigid --out "$tmp/s$n.csv" "$@"
}
for c in "${hc_small[@]}" "${hc_large[@]}"; do
  solve --kind honeycomb --cells "$c" --solver tr-krylov --preconditioner dd
done
for c in "${oc_small[@]}" "${oc_large[@]}"; do
  solve --kind octet --cells "$c" --solver tr-krylov --preconditioner dd
done
for c in "${hc_small[@]}" 80; do solve --kind honeycomb --cells "$c" --solver tr-minres; done
for c in "${oc_small[@]}" 8; do solve --kind octet --cells "$c" --solver tr-minres; done
first=1
for f in $(ls "$tmp"/s*.csv | sort -V); do
  if [ $first = 1 ]; then cat "$f"; first=0; else tail -n +2 "$f"; fi
done > "$res/precond_solve.csv"

"$py" benchmarks/plot_precond.py "$res/precond.csv" --solve "$res/precond_solve.csv" \
  -o "$res/precond.png"
