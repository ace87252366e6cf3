# Fuzzing of the JSON scene reader.
#  - fuzz_regressions (label unit, every build): the inputs the fuzzer found,
#    tests/data/fuzz_regressions/*.json, keep the reader's contract
#    (fuzz/scene_check.h) and give the outcome the manifest expected.tsv states.
#  - fuzz_scene (RN_FUZZ=ON with clang): libFuzzer target
#    (-fsanitize=fuzzer,address,undefined) over an instrumented copy of the
#    kernels, the C API and problems/; the ctest fuzz_scene_run (label fuzz)
#    runs it for a fixed number of executions on a fresh copy of the seed
#    corpus (problems/scenes/*.json, tests/data/bad/*.json and the regression
#    inputs) with a dictionary of the format's keys (fuzz/scene.dict).
set(RN_FUZZ_SRC ${CMAKE_CURRENT_SOURCE_DIR}/fuzz)
set(RN_FUZZ_REG ${CMAKE_CURRENT_SOURCE_DIR}/data/fuzz_regressions)

file(GLOB RN_FUZZ_REG_FILES ${RN_FUZZ_REG}/*.json)
rn_add_test(fuzz_regressions SOURCES fuzz/fuzz_regressions.c fuzz/scene_check.c
            LIBS rodnet_problems LABELS unit
            ARGS ${RN_FUZZ_REG}/expected.tsv ${RN_FUZZ_REG_FILES})
target_include_directories(fuzz_regressions PRIVATE ${RN_FUZZ_SRC})

# The OBJ reader: fuzz_obj_replay (label unit, every build) runs the seed
# corpus tests/data/obj/*.obj through the contract of fuzz/fuzz_obj.c; with
# RN_FUZZ the libFuzzer target fuzz_obj and its ctest fuzz_obj_run (below).
file(GLOB RN_FUZZ_OBJ_SEEDS ${CMAKE_CURRENT_SOURCE_DIR}/data/obj/*.obj
     ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/corpus/obj/*
     ${PROJECT_SOURCE_DIR}/problems/scenes/*.obj)
rn_add_test(fuzz_obj_replay SOURCES fuzz/fuzz_obj.c LIBS rodnet_problems LABELS unit
            ARGS ${RN_FUZZ_OBJ_SEEDS})

if(NOT RN_FUZZ)
  return()
endif()
if(NOT CMAKE_C_COMPILER_ID MATCHES "Clang")
  message(WARNING "RN_FUZZ=ON needs clang as the C compiler (found "
                  "${CMAKE_C_COMPILER_ID}): the libFuzzer targets are not built")
  return()
endif()

# Absolute source files of a target.
function(rn_fuzz_target_sources target out)
  get_target_property(srcs ${target} SOURCES)
  get_target_property(dir ${target} SOURCE_DIR)
  set(abs)
  foreach(s ${srcs})
    if(NOT s MATCHES "\\$<")
      get_filename_component(a ${s} ABSOLUTE BASE_DIR ${dir})
      list(APPEND abs ${a})
    endif()
  endforeach()
  set(${out} ${abs} PARENT_SCOPE)
endfunction()

set(RN_FUZZ_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=all
    -fno-omit-frame-pointer)
rn_fuzz_target_sources(rodnet_kernels kernel_srcs)
rn_fuzz_target_sources(rodnet_core core_srcs)
rn_fuzz_target_sources(rodnet_problems_obj problems_srcs)

# The code under test, with coverage instrumentation for libFuzzer.
add_library(rn_fuzz_lib STATIC ${kernel_srcs} ${core_srcs} ${problems_srcs})
target_include_directories(rn_fuzz_lib PUBLIC ${PROJECT_SOURCE_DIR}/kernels
                           ${PROJECT_SOURCE_DIR}/c_api ${PROJECT_SOURCE_DIR}/c_api/include ${PROJECT_SOURCE_DIR}/problems ${PROJECT_SOURCE_DIR}/problems/include
                           ${CJSON_INCLUDE_DIR})
target_compile_options(rn_fuzz_lib PRIVATE ${RN_FUZZ_FLAGS} -fsanitize=fuzzer-no-link)
target_link_libraries(rn_fuzz_lib PUBLIC ${CJSON_LIBRARY} m)

add_executable(fuzz_scene fuzz/fuzz_scene.c fuzz/scene_check.c)
target_include_directories(fuzz_scene PRIVATE ${RN_FUZZ_SRC})
target_compile_options(fuzz_scene PRIVATE ${RN_FUZZ_FLAGS} -fsanitize=fuzzer)
target_link_options(fuzz_scene PRIVATE -fsanitize=fuzzer,address,undefined)
target_link_libraries(fuzz_scene PRIVATE rn_fuzz_lib)
# Every libFuzzer target joins fuzz_targets (what scripts/test.sh builds).
add_executable(fuzz_obj fuzz/fuzz_obj.c)
target_compile_definitions(fuzz_obj PRIVATE RN_LIBFUZZER=1)
target_compile_options(fuzz_obj PRIVATE ${RN_FUZZ_FLAGS} -fsanitize=fuzzer)
target_link_options(fuzz_obj PRIVATE -fsanitize=fuzzer,address,undefined)
target_link_libraries(fuzz_obj PRIVATE rn_fuzz_lib)
add_custom_target(fuzz_targets)
add_dependencies(fuzz_targets fuzz_scene fuzz_obj)

set(RN_FUZZ_RUNS 20000 CACHE STRING "Executions of each fuzz target in its ctest")
set(RN_FUZZ_MAX_TIME 150 CACHE STRING "Cap on the seconds of each fuzz ctest")
# Seeds: the shipped scenes, the bad inputs, the regression inputs and the corpus
# the long runs of scripts/fuzz.sh keep in tests/fuzz/corpus/ (docs/fuzzing.md).
set(RN_FUZZ_CORPUS ${RN_FUZZ_SRC}/corpus)
file(GLOB RN_FUZZ_SEEDS ${PROJECT_SOURCE_DIR}/problems/scenes/*.json
     ${CMAKE_CURRENT_SOURCE_DIR}/data/bad/*.json ${RN_FUZZ_REG}/*.json
     ${RN_FUZZ_CORPUS}/scene/*)
string(REPLACE ";" "@@" seeds "${RN_FUZZ_SEEDS}")
add_test(NAME fuzz_scene_run
         COMMAND ${CMAKE_COMMAND} -DFUZZER=$<TARGET_FILE:fuzz_scene>
                 -DWORK=${CMAKE_CURRENT_BINARY_DIR}/fuzz_scene_work -DSEEDS=${seeds}
                 -DDICT=${RN_FUZZ_SRC}/scene.dict -DRUNS=${RN_FUZZ_RUNS}
                 -DMAX_TIME=${RN_FUZZ_MAX_TIME} -P ${RN_FUZZ_SRC}/run_fuzz.cmake)
math(EXPR rn_fuzz_timeout "${RN_FUZZ_MAX_TIME} + 120")
set_tests_properties(fuzz_scene_run PROPERTIES LABELS fuzz TIMEOUT ${rn_fuzz_timeout})

# Periodic cells: the scene target (its contract checks a cell's description,
# strain, stress and relative density) on a corpus of periodic cells of every
# kind `rodnet generate --periodic` writes.
file(GLOB RN_FUZZ_PERIODIC_SEEDS ${CMAKE_CURRENT_SOURCE_DIR}/data/periodic/*.json
     ${RN_FUZZ_CORPUS}/periodic/*)
string(REPLACE ";" "@@" periodic_seeds "${RN_FUZZ_PERIODIC_SEEDS}")
add_test(NAME fuzz_periodic_run
         COMMAND ${CMAKE_COMMAND} -DFUZZER=$<TARGET_FILE:fuzz_scene>
                 -DWORK=${CMAKE_CURRENT_BINARY_DIR}/fuzz_periodic_work
                 -DSEEDS=${periodic_seeds} -DDICT=${RN_FUZZ_SRC}/scene.dict
                 -DRUNS=${RN_FUZZ_RUNS} -DMAX_TIME=${RN_FUZZ_MAX_TIME}
                 -P ${RN_FUZZ_SRC}/run_fuzz.cmake)
set_tests_properties(fuzz_periodic_run PROPERTIES LABELS fuzz TIMEOUT ${rn_fuzz_timeout})

# The OBJ reader (fuzz/fuzz_obj.c) on the OBJ seed corpus.
string(REPLACE ";" "@@" obj_seeds "${RN_FUZZ_OBJ_SEEDS}")
add_test(NAME fuzz_obj_run
         COMMAND ${CMAKE_COMMAND} -DFUZZER=$<TARGET_FILE:fuzz_obj>
                 -DWORK=${CMAKE_CURRENT_BINARY_DIR}/fuzz_obj_work -DSEEDS=${obj_seeds}
                 -DDICT=${RN_FUZZ_SRC}/obj.dict -DRUNS=${RN_FUZZ_RUNS}
                 -DMAX_TIME=${RN_FUZZ_MAX_TIME} -P ${RN_FUZZ_SRC}/run_fuzz.cmake)
set_tests_properties(fuzz_obj_run PROPERTIES LABELS fuzz TIMEOUT ${rn_fuzz_timeout})
