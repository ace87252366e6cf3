#!/usr/bin/env bash
# fuzz.sh: fuzzing at depth (docs/fuzzing.md).  Builds the libFuzzer targets (clang,
# ASan + UBSan, build-fuzz/ as in scripts/test.sh), then runs each target for RUNS
# executions on the corpus kept in the repository, tests/fuzz/corpus/TARGET/, plus
# the seeds the short ctest runs use.  Afterwards the inputs that add coverage are
# merged into tests/fuzz/corpus/TARGET/ (libFuzzer -merge=1: only new coverage, so
# the corpus stays small); every crash, leak or timeout is copied to
# tests/fuzz/findings/TARGET/ to become a regression test (docs/fuzzing.md says how).
#
#   bash scripts/fuzz.sh [--runs N] [--max-time S] [--no-merge] [TARGET...]
#
# TARGETs: scene (JSON scenes), periodic (periodic cells through the scene target),
# obj (OBJ line graphs); default all three, one after the other.  --runs defaults to
# 10^7 executions per target, --max-time (seconds per target) to none.  Writes one
# line per target to build-fuzz/fuzz-deep/summary.csv (commit, target, runs,
# seconds, exec_per_s, coverage, corpus_before, corpus_after, findings).  Exits 1 if
# any target found something.
set -euo pipefail
cd "$(dirname "$0")/.."
runs=10000000
max_time=0
merge=1
targets=()
while [ $# -gt 0 ]; do
  case $1 in
    --runs) runs=$2; shift 2 ;;
    --max-time) max_time=$2; shift 2 ;;
    --no-merge) merge=0; shift ;;
    -h|--help) sed -n '2,18p' "$0"; exit 0 ;;
    scene|periodic|obj) targets+=("$1"); shift ;;
    *) echo "fuzz.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ ${#targets[@]} -gt 0 ] || targets=(scene periodic obj)

build=build-fuzz
cmake -S . -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DRN_FUZZ=ON -DRN_WITH_TRILINOS=OFF -DRN_BUILD_BENCHMARKS=OFF -DRN_WERROR=ON >/dev/null
cmake --build "$build" -j"${RN_JOBS:-2}" --target fuzz_targets >/dev/null
out=$build/fuzz-deep
mkdir -p "$out"
summary=$out/summary.csv
[ -f "$summary" ] ||
  echo "commit,target,runs,seconds,exec_per_s,coverage,corpus_before,corpus_after,findings" \
    >"$summary"
commit=$(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)
found=0

for t in "${targets[@]}"; do
  corpus=tests/fuzz/corpus/$t
  mkdir -p "$corpus"
  case $t in
    scene)
      exe=$build/tests/fuzz_scene dict=tests/fuzz/scene.dict
      seeds=(problems/scenes tests/data/bad tests/data/fuzz_regressions) ;;
    periodic)
      exe=$build/tests/fuzz_scene dict=tests/fuzz/scene.dict
      seeds=(tests/data/periodic) ;;
    obj)
      exe=$build/tests/fuzz_obj dict=tests/fuzz/obj.dict
      seeds=(tests/data/obj) ;;
  esac
  work=$out/$t
  rm -rf "$work"
  mkdir -p "$work/new"
  before=$(find "$corpus" -type f | wc -l)
  args=(-runs="$runs" -timeout=20 -rss_limit_mb=2048 -max_len=16384
        -print_final_stats=1 -dict="$dict" -artifact_prefix="$work/")
  [ "$max_time" -gt 0 ] && args+=(-max_total_time="$max_time")
  echo "fuzz.sh: $t: $runs executions from $before corpus inputs (log: $work/log)"
  t0=$(date +%s)
  # New inputs go to work/new (the first directory); the others are read only.
  "$exe" "${args[@]}" "$work/new" "$corpus" "${seeds[@]}" >"$work/log" 2>&1 || true
  secs=$(($(date +%s) - t0))
  done_runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log" | tail -n1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$work/log" | tail -n1)
  cov=$(grep -oE 'cov: [0-9]+' "$work/log" | tail -n1 | grep -oE '[0-9]+' || echo 0)
  findings=$(find "$work" -maxdepth 1 -type f \
    \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  if [ "$findings" -gt 0 ]; then
    found=1
    mkdir -p "tests/fuzz/findings/$t"
    find "$work" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' -o \
      -name 'timeout-*' -o -name 'oom-*' \) -exec cp {} "tests/fuzz/findings/$t/" \;
    echo "fuzz.sh: $t: $findings finding(s) copied to tests/fuzz/findings/$t/" \
         "(reproduce: $exe FILE)"
  fi
  if [ "$merge" = 1 ]; then
    "$exe" -merge=1 -timeout=20 -rss_limit_mb=2048 -max_len=16384 "$corpus" "$work/new" \
      >"$work/merge.log" 2>&1 || echo "fuzz.sh: $t: merge failed (see $work/merge.log)"
  fi
  after=$(find "$corpus" -type f | wc -l)
  echo "$commit,$t,${done_runs:-0},$secs,${rate:-0},$cov,$before,$after,$findings" >>"$summary"
  echo "fuzz.sh: $t: ${done_runs:-0} executions in $secs s (${rate:-0}/s), coverage $cov," \
       "corpus $before -> $after, $findings finding(s)"
done
exit "$found"
