# Solver shim (shim_cxx/): rn_solve with every solver kind, load stepping, negative
# curvature, runtime initialisation.  Needs LAPACK for the dense reference solutions.
if(NOT RN_WITH_TRILINOS)
  return()
endif()
rn_add_test(shim_solve SOURCES unit/shim_solve.c
            LIBS rodnet ${LAPACK_LIBRARIES} LABELS unit)
rn_add_test(shim_buckling SOURCES unit/shim_buckling.c LIBS rodnet LABELS unit)
rn_add_test(shim_load_stepping SOURCES unit/shim_load_stepping.c LIBS rodnet LABELS unit)
# No rn_runtime_initialize: the first solve initialises the runtime; also under mpirun.
rn_add_test(shim_lazy_runtime SOURCES unit/shim_lazy_runtime.c LIBS rodnet LABELS unit)
if(MPIEXEC_EXECUTABLE)
  add_test(NAME shim_lazy_runtime_mpirun
           COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 1 $<TARGET_FILE:shim_lazy_runtime>)
  set_tests_properties(shim_lazy_runtime_mpirun PROPERTIES LABELS "unit;mpi" TIMEOUT 120
    PROCESSORS 1 ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1")
endif()
# Networks with joints: the three solver kinds agree (rigid rotation reset on every
# path), sparse vs banded factorisation, continuation with cut-backs.
rn_add_test(shim_networks SOURCES unit/shim_networks.c
            LIBS rodnet ${LAPACK_LIBRARIES} m LABELS unit)
# The load-step predictor: lattice under stretch (same state, fewer iterations) and
# a strongly nonlinear cantilever (same state).
rn_add_test(shim_predictor SOURCES unit/shim_predictor.c LIBS rodnet m LABELS unit)
# State snapshots: bit-identical evaluations after solving away and restoring.
rn_add_test(shim_state SOURCES unit/shim_state.c LIBS rodnet m LABELS unit)
# The sparse Cholesky factorisation on its own against dense LAPACK (C++: it tests
# an internal class of the shim through the shared library).
rn_add_test(shim_sparse_cholesky SOURCES unit/shim_sparse_cholesky.cpp
            LIBS rodnet ${LAPACK_LIBRARIES} LABELS unit)
target_include_directories(shim_sparse_cholesky PRIVATE ${PROJECT_SOURCE_DIR}/shim_cxx)
# The rod-level domain-decomposition preconditioner (C++: internal classes of the shim
# through the shared library), on one rank and under mpirun on two.
rn_add_test(shim_dd SOURCES unit/shim_dd.cpp LIBS rodnet rodnet_problems rodnet_shim_deps
            LABELS unit)
target_include_directories(shim_dd PRIVATE ${PROJECT_SOURCE_DIR}/shim_cxx
                                           ${PROJECT_SOURCE_DIR}/problems)
target_include_directories(shim_dd SYSTEM PRIVATE ${Trilinos_INCLUDE_DIRS}
                                                  ${Trilinos_TPL_INCLUDE_DIRS})
if(MPIEXEC_EXECUTABLE)
  add_test(NAME shim_dd_2ranks
           COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2 $<TARGET_FILE:shim_dd>)
  set_tests_properties(shim_dd_2ranks PROPERTIES LABELS "mpi" TIMEOUT 600 PROCESSORS 2
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")
endif()
