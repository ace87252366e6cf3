#!/usr/bin/env bash
# speed_table.sh - every row of issue 8's table, measured in one run:
#   kernels per vertex (bench_kernels, curved rod, 10^3 and 10^5 vertices),
#   the cantilever at 401 and 3201 vertices (bench_solve: Newton iterations, rn_solve
#   time), `rodnet solve` whole process minus its time_s (bench_startup.py, 401),
#   the honeycomb 20x20 past buckling (rodnet solve: Newton iterations, time_s),
#   the 215-degree arch at P = 4 and 8 EI/R^2 (bench_solve --problem arch),
#   scene reading and result writing at 10^6 vertices (bench_io, honeycomb 208^2).
# Writes benchmarks/results/speed_table.csv (one row per measurement: commit,
# compiler, flags, ranks, bench, case, size, repeats, median, min, unit, target) and
# prints the table as Markdown (benchmarks/speed_table.py).  Timings are reported,
# never asserted.
#   bash benchmarks/speed_table.sh [BUILD_DIR]          # default build/
#   RN_SPEED_QUICK=1 bash benchmarks/speed_table.sh      # fewer repeats, no 10^6 I/O
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
py=/usr/bin/python3
[ -x "$py" ] || py=python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
quick=${RN_SPEED_QUICK:-0}
if [ "$quick" = 1 ]; then rk=5; rs=1; rst=5; else rk=11; rs=5; rst=21; fi
b=$build/benchmarks
echo "speed_table: kernels" >&2
"$b"/bench_kernels --sizes 1000,100000 --shapes curved --repeats "$rk" --min-time 0.3 \
  --out "$tmp/kernels.csv"
echo "speed_table: cantilever" >&2
"$b"/bench_solve --sizes 401,3201 --repeats "$rs" --out "$tmp/cantilever.csv"
echo "speed_table: arch" >&2
for P in 4 8; do
  "$b"/bench_solve --problem arch --sizes 321 --load "$P" --repeats "$rs" \
    --out "$tmp/arch$P.csv"
done
echo "speed_table: start-up" >&2
"$py" benchmarks/bench_startup.py --rodnet "$build/rodnet" --sizes 401 \
  --repeats "$rst" --cases solve --out "$tmp/startup.csv"
echo "speed_table: honeycomb 20x20" >&2
"$build"/rodnet generate honeycomb --cells 20,20 --edges-per-rod 8 --joint-model rigid \
  --load compress-y:5e-2 -o "$tmp/hc20.json" >/dev/null
for r in $(seq "$([ "$quick" = 1 ] && echo 1 || echo 3)"); do
  "$build"/rodnet solve "$tmp/hc20.json" -q -o "$tmp/hc20-$r.json" >/dev/null
done
if [ "$quick" != 1 ]; then
  echo "speed_table: I/O at 10^6 vertices" >&2
  "$b"/bench_io --cells 208 --repeats 1 --out "$tmp/io.csv"
fi
"$py" benchmarks/speed_table.py --dir "$tmp" --commit "$(git rev-parse --short=12 HEAD)" \
  --out benchmarks/results/speed_table.csv
