#!/usr/bin/env bash
# precond.sh: the preconditioner study of docs/solvers.md ("Preconditioners for
# networks"): bench_precond on honeycomb and octet lattices from 10^3 to 10^6
# vertices (8 edges per rod, uniaxial stretch 1e-3), one Newton system per
# preconditioner and whole Newton solves, then plot_precond.py.
#
#   bash benchmarks/precond.sh [BUILD_DIR]     # default build/
#   RN_PRECOND_QUICK=1 bash benchmarks/precond.sh   # up to ~10^5 vertices only
#
# Writes benchmarks/results/precond.csv (appends; remove it for a fresh run) and
# benchmarks/results/precond.png.  Each lattice size runs in its own process, so the
# peak resident size in the CSV is that case's.  The large cases need ~10 GB and
# several minutes each on a 2-core machine.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
bench=$build/benchmarks/bench_precond
out=benchmarks/results/precond.csv
py=/usr/bin/python3
[ -x "$py" ] || py=python3
mkdir -p benchmarks/results
run() { nice "$bench" --edges-per-rod 8 --load stretch-x:1e-3 --out "$out" "$@"; }

hc_small=(10 20 40) hc_large=(80 120 190)
oc_small=(3 4 6) oc_large=(8 11 14 16)
if [ "${RN_PRECOND_QUICK:-0}" = 1 ]; then hc_large=(80); oc_large=(8); fi

# One Newton system: every preconditioner while the exact factorisation is
# affordable, then the DD alone.
for c in "${hc_small[@]}"; do
  run --kind honeycomb --cells "$c" --models rigid,elastic \
    --precond dd,dd-direct,dd-amg,muelu,ifpack2,factor
done
for c in "${oc_small[@]}"; do
  run --kind octet --cells "$c" --models rigid,elastic \
    --precond dd,dd-direct,dd-amg,muelu,ifpack2,factor
done
for c in "${hc_large[@]}"; do
  run --kind honeycomb --cells "$c" --models rigid --precond dd,dd-direct,dd-amg
done
for c in "${oc_large[@]}"; do
  run --kind octet --cells "$c" --models rigid --precond dd,dd-direct,dd-amg
done
# Whole solves to equilibrium with the default (dd) and the exact factorisation.
for c in "${hc_small[@]}" "${hc_large[@]}"; do
  run --kind honeycomb --cells "$c" --models rigid --newton --precond dd
done
for c in "${oc_small[@]}" "${oc_large[@]}"; do
  run --kind octet --cells "$c" --models rigid --newton --precond dd
done
"$py" benchmarks/plot_precond.py "$out" -o benchmarks/results/precond.png
