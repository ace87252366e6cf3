# Provenance of a build, fixed at configure time: RN_BENCH_COMMIT (short hash, "-dirty"
# with uncommitted changes to tracked files, "unknown" outside git), RN_BENCH_COMPILER
# and RN_BENCH_FLAGS (the C flags of the build type, sanitizers included).  Recorded in
# every benchmark CSV row (benchmarks/, rodnet bench).
if(DEFINED RN_BENCH_COMMIT)
  return()
endif()
execute_process(COMMAND git rev-parse --short=12 HEAD
  WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
  OUTPUT_VARIABLE RN_BENCH_COMMIT OUTPUT_STRIP_TRAILING_WHITESPACE
  RESULT_VARIABLE rn_git_rc ERROR_QUIET)
if(NOT rn_git_rc EQUAL 0 OR RN_BENCH_COMMIT STREQUAL "")
  set(RN_BENCH_COMMIT "unknown")
else()
  execute_process(COMMAND git status --porcelain --untracked-files=no
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    OUTPUT_VARIABLE rn_git_dirty OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT rn_git_dirty STREQUAL "")
    string(APPEND RN_BENCH_COMMIT "-dirty")
  endif()
endif()
set(RN_BENCH_COMPILER "${CMAKE_C_COMPILER_ID} ${CMAKE_C_COMPILER_VERSION}")
string(TOUPPER "${CMAKE_BUILD_TYPE}" rn_bt)
string(STRIP "${CMAKE_C_FLAGS} ${CMAKE_C_FLAGS_${rn_bt}}" RN_BENCH_FLAGS)
if(RN_SANITIZE)
  string(APPEND RN_BENCH_FLAGS " -fsanitize=${RN_SANITIZE}")
endif()
string(REPLACE "\"" "\\\"" RN_BENCH_FLAGS "${RN_BENCH_FLAGS}")
