#!/usr/bin/env bash
# bench_dist.sh - work per rank of a distributed Newton step at 1 and 2 ranks
# (issue 7, section 5): owned DOFs and stencils, bytes communicated per step, wall
# time per step (timed runs) and instructions per rank (callgrind, the step loop
# only; mpi_instructions: those spent in MPI, mostly polling while a rank waits for
# the other: work = instructions - mpi_instructions).  Writes benchmarks/results/dist.csv, dist_instructions.csv and dist.png.
#   bash benchmarks/bench_dist.sh [build-dir]        (RN_DIST_CELLS: "30 100")
# Run it from the repository root after building (bench_dist, rodnet).  These 2-core
# machines give little wall-clock speed-up from 2 ranks: compare instructions.
set -euo pipefail
build=${1:-build}
out=benchmarks/results
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
  OMPI_MCA_rmaps_base_oversubscribe=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
csv=$out/dist.csv
icsv=$out/dist_instructions.csv
rm -f "$csv"
echo "case,ranks,rank,instructions,mpi_instructions" >"$icsv"
for cells in ${RN_DIST_CELLS:-30 100}; do
  scene=$tmp/honeycomb-$cells.json
  "$build"/rodnet generate honeycomb --cells "$cells" --joint-model rigid \
    --load stretch-x:1e-3 -o "$scene" >/dev/null
  label=honeycomb-rigid-$cells
  for np in 1 2; do
    mpirun -q -np $np "$build"/benchmarks/bench_dist "$scene" --repeats 5 \
      --label "$label" --out "$csv"
    rm -f "$tmp"/cg.*
    mpirun -q -np $np valgrind -q --tool=callgrind --instr-atstart=no \
      --callgrind-out-file="$tmp/cg.%q{OMPI_COMM_WORLD_RANK}" \
      "$build"/benchmarks/bench_dist "$scene" --repeats 1 --callgrind --label "$label" \
      --out /dev/null >/dev/null
    for f in "$tmp"/cg.*; do
      r=${f##*.}
      n=$(awk '/^totals:/ {print $2; exit}' "$f")
      # instructions in MPI (mostly polling while waiting for the other rank)
      m=$(callgrind_annotate --threshold=100 "$f" 2>/dev/null |
        awk '/openmpi|libopen-pal|libmpi|libpmix|libevent/ {gsub(",", "", $1); s += $1}
             END {print s + 0}')
      echo "$label,$np,$r,$n,$m" >>"$icsv"
    done
  done
done
/usr/bin/python3 benchmarks/plot_dist.py "$csv" "$icsv" -o "$out/dist.png"
echo "wrote $csv $icsv $out/dist.png"
