# The registries of preconditioners and solver kinds (rodnet_registry.h): the rows
# and their names (also in the scene reader), then everything that lists them (the
# command's help and errors, rodnet bench's solvers, the docs' tables) against the
# rows.  In both builds (the registry and the scene reader need no solver).
rn_add_test(registry_rows SOURCES unit/registry_lists.c LIBS rodnet_problems
            LABELS unit)
if(RN_WITH_TRILINOS)
  set(rn_registry_solver solver)
else()
  set(rn_registry_solver "")
endif()
add_test(NAME registry_lists
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_registry_lists.py
                 $<TARGET_FILE:registry_rows> $<TARGET_FILE:rodnet_cli>
                 ${PROJECT_SOURCE_DIR}/docs
                 ${PROJECT_SOURCE_DIR}/problems/scenes/cantilever.json
                 ${CMAKE_CURRENT_BINARY_DIR}/registry_lists ${rn_registry_solver})
set_tests_properties(registry_lists PROPERTIES LABELS unit TIMEOUT 120)
# The conformance suite of the preconditioners (docs/solvers.md, "Preconditioners for
# networks"), driven by the registries: on one process every kind that takes a
# preconditioner with every preconditioner, in the serial runtime and in the MPI one
# (shim_dd_solve, shim_dd_solve_mpi_runtime: tests/shim.cmake); here the same rows on
# 2 ranks (label mpi): `rodnet solve` under mpirun against tr-minres's energy (1e-9
# relative), the one-rank-only rows refused.
if(RN_WITH_TRILINOS AND MPIEXEC_EXECUTABLE)
  add_test(NAME mpi_conformance
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_conformance_mpi.py
                   $<TARGET_FILE:registry_rows> $<TARGET_FILE:rodnet_cli>
                   ${MPIEXEC_EXECUTABLE} 2 ${CMAKE_CURRENT_BINARY_DIR}/mpi_cli/scenes/honeycomb.json
                   ${CMAKE_CURRENT_BINARY_DIR}/mpi_conformance)
  set_tests_properties(mpi_conformance PROPERTIES LABELS mpi TIMEOUT 1200 PROCESSORS 2
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1"
    FIXTURES_REQUIRED rn_mpi_scenes)
endif()
