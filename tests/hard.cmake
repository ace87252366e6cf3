# The hard-case suite of issue 10 section 6 (label `hard`, docs/hard-cases.md): each
# case converges to a verified local minimum (rn_solve_report.stability) and is
# checked against a closed form or the elastica.  Cases of hard_cases.c, one ctest
# each, and a large lattice compressed past buckling through the CLI.
if(NOT RN_WITH_TRILINOS)
  return()
endif()
add_executable(hard_cases unit/hard_cases.c)
target_link_libraries(hard_cases PRIVATE rn_testutil rodnet m)
foreach(c folded ratio saddle scale rest)
  add_test(NAME hard_${c} COMMAND hard_cases ${c})
  set_tests_properties(hard_${c} PROPERTIES LABELS "hard" TIMEOUT 300)
endforeach()

# A lattice with thousands of joints past buckling (the CLI; about 45 s of CPU): a
# 32 x 32 honeycomb (2176 joints) compressed by 5 % buckles out of its plane; the
# result is a verified local minimum without zero modes.
set(hard_dir ${CMAKE_CURRENT_BINARY_DIR}/hard)
file(MAKE_DIRECTORY ${hard_dir})
rn_cli_test(hard_lattice_generate 0 ""
  ARGS generate honeycomb --cells 32,32 --edges-per-rod 2 --load compress-x:0.05
       -o ${hard_dir}/lattice.json -q
  FIXTURE_SETUP hard_lattice_scene)
rn_cli_test(hard_lattice_solve 0 "stability +verified local minimum"
  ARGS solve ${hard_dir}/lattice.json -o ${hard_dir}/lattice_result.json -q
  REMOVE ${hard_dir}/lattice_result.json FIXTURE_SETUP hard_lattice_result TIMEOUT 900)
set_tests_properties(hard_lattice_solve PROPERTIES FIXTURES_REQUIRED hard_lattice_scene)
add_test(NAME hard_lattice_check
  COMMAND ${RN_VTK_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_stability.py
          ${hard_dir}/lattice_result.json --verified true --zero-modes 0 --min-abs-z 1.0)
set_tests_properties(hard_lattice_check PROPERTIES FIXTURES_REQUIRED hard_lattice_result)
set_tests_properties(hard_lattice_generate hard_lattice_solve hard_lattice_check
                     PROPERTIES LABELS "hard")

# Issue 10 section 7: solvers that can stop at a saddle say so.  A flat 4 x 4
# honeycomb compressed by 5 %: rol-ls-newton and nox stop at the flat stationary
# point ("converged: stationary, not a verified minimum", verified_minimum false),
# tr-minres buckles it (verified).  Label unit: fractions of a second.
rn_cli_test(stability_honeycomb_generate 0 ""
  ARGS generate honeycomb --cells 4,4 --load compress-x:0.05 -o ${hard_dir}/hc4.json -q
  FIXTURE_SETUP stability_honeycomb)
foreach(solver rol-ls-newton nox tr-minres)
  if(solver STREQUAL "tr-minres")
    set(expect "status +converged .stopped.*stability +verified local minimum")
    set(verified true)
  else()
    set(expect "status +converged: stationary, not a verified minimum")
    set(verified false)
  endif()
  rn_cli_test(stability_honeycomb_${solver} 0 "${expect}"
    ARGS solve ${hard_dir}/hc4.json -o ${hard_dir}/hc4_${solver}.json -q --solver ${solver}
    REMOVE ${hard_dir}/hc4_${solver}.json FIXTURE_SETUP stability_honeycomb_${solver})
  set_tests_properties(stability_honeycomb_${solver} PROPERTIES
                       FIXTURES_REQUIRED stability_honeycomb)
  add_test(NAME stability_honeycomb_${solver}_check
    COMMAND ${RN_VTK_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_stability.py
            ${hard_dir}/hc4_${solver}.json --verified ${verified} --zero-modes 0)
  set_tests_properties(stability_honeycomb_${solver}_check PROPERTIES LABELS unit
                       FIXTURES_REQUIRED stability_honeycomb_${solver})
  # the LOBPCG check forced: the same verdict, zero modes and lowest eigenvalue
  rn_cli_test(stability_honeycomb_lobpcg_${solver} 0 "${expect}"
    ARGS solve ${hard_dir}/hc4.json -o ${hard_dir}/hc4_lobpcg_${solver}.json -q
         --solver ${solver} --stability-method lobpcg
    REMOVE ${hard_dir}/hc4_lobpcg_${solver}.json
    FIXTURE_SETUP stability_honeycomb_lobpcg_${solver})
  set_tests_properties(stability_honeycomb_lobpcg_${solver} PROPERTIES
                       FIXTURES_REQUIRED stability_honeycomb)
  add_test(NAME stability_honeycomb_lobpcg_${solver}_check
    COMMAND ${RN_VTK_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_stability.py
            ${hard_dir}/hc4_lobpcg_${solver}.json --verified ${verified} --zero-modes 0
            --method lobpcg --same-as ${hard_dir}/hc4_${solver}.json)
  set_tests_properties(stability_honeycomb_lobpcg_${solver}_check PROPERTIES LABELS unit
    FIXTURES_REQUIRED "stability_honeycomb_${solver};stability_honeycomb_lobpcg_${solver}")
endforeach()

# Under mpirun (2 ranks, tr-krylov) the solve checks the stability on the parts
# (LOBPCG): the same verdict as one process.
if(MPIEXEC_EXECUTABLE)
  add_test(NAME stability_honeycomb_mpi
           COMMAND ${CMAKE_COMMAND} -DCMD=${MPIEXEC_EXECUTABLE}
                   "-DARGS=-q@@${MPIEXEC_NUMPROC_FLAG}@@2@@${CMAKE_BINARY_DIR}/rodnet@@solve@@${hard_dir}/hc4.json@@-o@@${hard_dir}/hc4_mpi.json@@-q"
                   -DEXPECT_RC=0 "-DEXPECT_REGEX=stability +verified local minimum"
                   -DREMOVE=${hard_dir}/hc4_mpi.json
                   -P ${CMAKE_CURRENT_SOURCE_DIR}/unit/problems_run.cmake)
  set_tests_properties(stability_honeycomb_mpi PROPERTIES LABELS mpi TIMEOUT 120
    PROCESSORS 2 FIXTURES_REQUIRED stability_honeycomb FIXTURES_SETUP stability_honeycomb_mpi
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")
  add_test(NAME stability_honeycomb_mpi_check
    COMMAND ${RN_VTK_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_stability.py
            ${hard_dir}/hc4_mpi.json --verified true --zero-modes 0)
  set_tests_properties(stability_honeycomb_mpi_check PROPERTIES LABELS mpi
                       FIXTURES_REQUIRED stability_honeycomb_mpi)
endif()

# Contact (docs/contact.md): hard_contact.c, one ctest per case.
add_executable(hard_contact unit/hard_contact.c)
target_link_libraries(hard_contact PRIVATE rn_testutil rodnet rodnet_scene m)
foreach(c crossed plectoneme lattice knot plectoneme_dd lattice_dd)
  add_test(NAME hard_contact_${c} COMMAND hard_contact ${c}
           ${CMAKE_CURRENT_SOURCE_DIR}/data/contact/honeycomb_dense.json)
  set_tests_properties(hard_contact_${c} PROPERTIES LABELS "hard" TIMEOUT 900)
endforeach()
