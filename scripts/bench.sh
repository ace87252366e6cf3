#!/usr/bin/env bash
# bench.sh: build (scripts/setup.sh), run the benchmarks at full size and plot them.
# Writes benchmarks/results/{kernels,joints,solve,lattice,startup,io}.{csv,png},
# benchmarks/results/bench_suite/ (rodnet bench) and benchmarks/results/pareto/.
#
#   bash scripts/bench.sh            # full: kernels 1e2..1e5 vertices, solve 101/401/3201,
#                                    # honeycombs 10x10 and 30x30, rigid and elastic joints
#   RN_BENCH_QUICK=1 bash scripts/bench.sh   # a quick pass with fewer repeats
#   RN_BENCH_LARGE=1 bash scripts/bench.sh   # adds the 100x100 honeycomb (1e6 DOFs,
#                                            # ~2 GB and several minutes per solve)
set -euo pipefail
cd "$(dirname "$0")/.."
# Reconfigure so that the commit recorded in the CSV is the current one.
bash scripts/setup.sh
# matplotlib comes with Debian's python3 (scripts/setup.sh).
py=/usr/bin/python3
[ -x "$py" ] || py=python3
out=benchmarks/results
mkdir -p "$out"
if [ "${RN_BENCH_QUICK:-0}" = 1 ]; then
  kargs=(--repeats 5 --min-time 0.05); sargs=(--repeats 1); lcells=10
else
  kargs=(--repeats 11 --min-time 0.3); sargs=(--repeats 3); lcells=10,30
fi
[ "${RN_BENCH_LARGE:-0}" = 1 ] && lcells=$lcells,100
./build/benchmarks/bench_kernels --sizes 100,1000,10000,100000 "${kargs[@]}" \
  --out "$out/kernels.csv"
"$py" benchmarks/plot.py "$out/kernels.csv" -o "$out/kernels.png"
# Whole-joint kernels by valence, closed forms against the jets (the test oracle).
./build/benchmarks/bench_joints --repeats "$([ "${RN_BENCH_QUICK:-0}" = 1 ] && echo 3 || echo 7)" \
  --out "$out/joints.csv"
"$py" benchmarks/plot_joints.py "$out/joints.csv" -o "$out/joints.png"
if [ -x ./build/benchmarks/bench_solve ]; then
  ./build/benchmarks/bench_solve --sizes 101,401,3201 "${sargs[@]}" --out "$out/solve.csv"
  "$py" benchmarks/plot.py "$out/solve.csv" -o "$out/solve.png"
fi
if [ -x ./build/benchmarks/bench_lattice ]; then
  ./build/benchmarks/bench_lattice --cells "$lcells" "${sargs[@]}" --out "$out/lattice.csv"
  "$py" benchmarks/plot.py "$out/lattice.csv" -o "$out/lattice.png"
fi
# Whole-process start-up of `rodnet solve` (the issue's 401-vertex cantilever) and
# scene reading / result writing on honeycombs of 1e4, 1e5 (and, with RN_BENCH_LARGE,
# 1e6) vertices.
if [ -x ./build/benchmarks/bench_io ]; then
  "$py" benchmarks/bench_startup.py --rodnet build/rodnet --sizes 401,3201 \
    --repeats "$([ "${RN_BENCH_QUICK:-0}" = 1 ] && echo 5 || echo 21)" \
    --out "$out/startup.csv"
  "$py" benchmarks/plot_startup_io.py "$out/startup.csv" -o "$out/startup.png"
  iocells=21,66
  [ "${RN_BENCH_LARGE:-0}" = 1 ] && iocells=$iocells,208
  ./build/benchmarks/bench_io --cells "$iocells" --solve "${sargs[@]}" --out "$out/io.csv"
  "$py" benchmarks/plot_startup_io.py "$out/io.csv" -o "$out/io.png"
fi
# The optimiser benchmark (docs/benchmarking.md): every problem of the suite against
# every solver, performance and data profiles; quick suite with RN_BENCH_QUICK=1.
./build/rodnet bench --suite "$([ "${RN_BENCH_QUICK:-0}" = 1 ] && echo quick || echo full)" \
  --repeats "$([ "${RN_BENCH_QUICK:-0}" = 1 ] && echo 1 || echo 3)" -o "$out/bench_suite"
# Speed against error (section 1 of docs/benchmarking.md): cantilever and end moment.
"$py" benchmarks/pareto.py --rodnet build/rodnet -o "$out/pareto" \
  $([ "${RN_BENCH_QUICK:-0}" = 1 ] && echo --quick)
echo "bench.sh: results in $out/"
