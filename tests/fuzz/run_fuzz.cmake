# run_fuzz.cmake: run a libFuzzer target for a fixed number of executions on a
# fresh copy of its seed corpus (so the source tree is never written).
#   cmake -DFUZZER=exe -DWORK=dir -DSEEDS=a.json@@b.json [-DDICT=file]
#         -DRUNS=n -DMAX_TIME=s -P run_fuzz.cmake
# Crashing inputs are kept as WORK/crash-* (the reproducer is printed); the
# test fails on any crash, leak, sanitizer report or timeout.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/corpus)
string(REPLACE "@@" ";" seeds "${SEEDS}")
foreach(s ${seeds})
  file(COPY ${s} DESTINATION ${WORK}/corpus)
endforeach()
set(args -runs=${RUNS} -max_total_time=${MAX_TIME} -timeout=20 -rss_limit_mb=2048
    -max_len=16384 -print_final_stats=1 -artifact_prefix=${WORK}/)
if(DICT)
  list(APPEND args -dict=${DICT})
endif()
execute_process(COMMAND ${FUZZER} ${args} ${WORK}/corpus RESULT_VARIABLE rc)
file(GLOB artifacts ${WORK}/crash-* ${WORK}/leak-* ${WORK}/timeout-* ${WORK}/oom-*)
if(NOT rc EQUAL 0 OR artifacts)
  message(FATAL_ERROR "fuzzer failed (exit ${rc}); reproduce with: ${FUZZER} ${artifacts}")
endif()
