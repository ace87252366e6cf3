# Solver shim (shim_cxx/): rn_solve with every solver kind, load stepping, negative
# curvature, runtime initialisation.  Needs LAPACK for the dense reference solutions.
if(NOT RN_WITH_TRILINOS)
  return()
endif()
rn_add_test(shim_solve SOURCES unit/shim_solve.c
            LIBS rodnet ${LAPACK_LIBRARIES} LABELS unit)
# ROL L-BFGS (rol-lbfgs): gradients only, reaches tr-minres's solution.
rn_add_test(shim_lbfgs SOURCES unit/shim_lbfgs.c LIBS rodnet m LABELS unit)
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
# The stability report (lowest eigenvalues, zero modes) against dense dsyev: every
# solver kind, banded and sparse, a free rod (6 zero modes), a saddle left by NOX.
rn_add_test(shim_stability SOURCES unit/shim_stability.c
            LIBS rodnet ${LAPACK_LIBRARIES} m LABELS unit)
# Networks with joints: the three solver kinds agree (rigid rotation reset on every
# path), sparse vs banded factorisation, continuation with cut-backs.
rn_add_test(shim_networks SOURCES unit/shim_networks.c
            LIBS rodnet ${LAPACK_LIBRARIES} m LABELS unit)
# The load-step predictor: lattice under stretch (same state, fewer iterations) and
# a strongly nonlinear cantilever (same state).
rn_add_test(shim_predictor SOURCES unit/shim_predictor.c LIBS rodnet m LABELS unit)
# The stopping test certifies equilibrium on a physical scale (strip with a moved
# clamp: starting gradient 5.5e7; reactions, gtol_abs as a requirement).
rn_add_test(shim_equilibrium SOURCES unit/shim_equilibrium.c LIBS rodnet m LABELS unit)
# An unloaded, self-stressed ring (Michell's twisted ring) converges by default: the
# scale of the stopping test includes the internal moment of the state (issue 22).
rn_add_test(shim_ring_stop SOURCES unit/shim_ring_stop.c LIBS rodnet m LABELS unit)
# State snapshots: bit-identical evaluations after solving away and restoring.
rn_add_test(shim_state SOURCES unit/shim_state.c LIBS rodnet m LABELS unit)
# The sparse Cholesky factorisation on its own against dense LAPACK (C++: it tests
# an internal class of the shim through the shared library).
rn_add_test(shim_sparse_cholesky SOURCES unit/shim_sparse_cholesky.cpp
            LIBS rodnet_internal ${LAPACK_LIBRARIES} LABELS unit)
target_include_directories(shim_sparse_cholesky PRIVATE ${PROJECT_SOURCE_DIR}/shim_cxx)
# The shifted factorisation's search where the Hessian has outgrown the metric (a rod
# folded to 179 degrees; shifts far above 1e10): the smallest decade, a clear error
# on a non-finite metric (C++: shim internals through the shared library).
rn_add_test(shim_shift_search SOURCES unit/shim_shift_search.cpp
            LIBS rodnet_internal LABELS unit)
target_include_directories(shim_shift_search PRIVATE ${PROJECT_SOURCE_DIR}/shim_cxx)
# The rod-level domain-decomposition preconditioner (C++: internal classes of the shim
# through the shared library), on one rank and under mpirun on two.
rn_add_test(shim_dd SOURCES unit/shim_dd.cpp LIBS rodnet_problems_internal rodnet_shim_deps
            LABELS unit)
target_include_directories(shim_dd PRIVATE ${PROJECT_SOURCE_DIR}/shim_cxx
                                           ${PROJECT_SOURCE_DIR}/problems)
target_include_directories(shim_dd SYSTEM PRIVATE ${Trilinos_INCLUDE_DIRS}
                                                  ${Trilinos_TPL_INCLUDE_DIRS})
# rn_solve's tr-krylov with every preconditioner on lattices: the exact equilibrium.
rn_add_test(shim_dd_solve SOURCES unit/shim_dd_solve.c LIBS rodnet rodnet_problems m
            LABELS unit)
target_include_directories(shim_dd_solve PRIVATE ${PROJECT_SOURCE_DIR}/problems)
add_test(NAME shim_dd_solve_mpi_runtime COMMAND shim_dd_solve mpi)
set_tests_properties(shim_dd_solve_mpi_runtime PROPERTIES LABELS unit TIMEOUT 600
  ENVIRONMENT "RODNET_MPI=1")
if(MPIEXEC_EXECUTABLE)
  add_test(NAME shim_dd_2ranks
           COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2 $<TARGET_FILE:shim_dd>)
  set_tests_properties(shim_dd_2ranks PROPERTIES LABELS "mpi" TIMEOUT 600 PROCESSORS 2
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")
endif()
# The runtime uses MPI exactly in an MPI job (launcher variables, RODNET_MPI, or MPI
# initialised by the program); same solution either way; finalize / re-initialize.
rn_add_test(shim_runtime SOURCES unit/shim_runtime.c LIBS rodnet MPI::MPI_C
            ARGS serial LABELS unit)
set_tests_properties(shim_runtime PROPERTIES ENVIRONMENT "RODNET_MPI=")
add_test(NAME shim_runtime_forced_mpi COMMAND shim_runtime mpi)
add_test(NAME shim_runtime_program_mpi COMMAND shim_runtime program-mpi)
set_tests_properties(shim_runtime_forced_mpi PROPERTIES ENVIRONMENT "RODNET_MPI=1")
set_tests_properties(shim_runtime_program_mpi PROPERTIES ENVIRONMENT "RODNET_MPI=")
set_tests_properties(shim_runtime_forced_mpi shim_runtime_program_mpi PROPERTIES
  LABELS unit TIMEOUT 120)
if(MPIEXEC_EXECUTABLE)
  set(rn_mpi_env "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1"
                 "OMPI_MCA_rmaps_base_oversubscribe=1")
  add_test(NAME shim_runtime_mpirun
           COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2
                   $<TARGET_FILE:shim_runtime> mpi)
  set_tests_properties(shim_runtime_mpirun PROPERTIES PROCESSORS 2
                       ENVIRONMENT "${rn_mpi_env};RODNET_MPI=")
  add_test(NAME shim_runtime_mpirun_forced_serial
           COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 1
                   $<TARGET_FILE:shim_runtime> serial)
  set_tests_properties(shim_runtime_mpirun_forced_serial PROPERTIES PROCESSORS 1
                       ENVIRONMENT "${rn_mpi_env};RODNET_MPI=0")
  set_tests_properties(shim_runtime_mpirun shim_runtime_mpirun_forced_serial PROPERTIES
    LABELS "unit;mpi" TIMEOUT 120)
endif()
# Translating a whole scene leaves energies, gradient and solve unchanged (load
# potentials measured from the initial state).
rn_add_test(shim_translation SOURCES unit/shim_translation.c LIBS rodnet m LABELS unit)
# SerialSystem (Tpetra CrsMatrix Hessian, blocks, snapshots) and the factor
# preconditioner, through the shim's internal classes (C++, Trilinos headers).
rn_add_test(shim_system SOURCES unit/shim_system.cpp unit/shim_system_nets.c
            LIBS rodnet_internal rodnet_shim_deps m LABELS unit)
target_include_directories(shim_system PRIVATE ${PROJECT_SOURCE_DIR}/shim_cxx
                                               ${PROJECT_SOURCE_DIR}/tests/unit)
target_include_directories(shim_system SYSTEM PRIVATE ${Trilinos_INCLUDE_DIRS}
                                                      ${Trilinos_TPL_INCLUDE_DIRS})
# Newton iteration counts of issue 8's scenes (counts, never times).
rn_add_test(shim_newton_counts SOURCES unit/shim_newton_counts.c
            LIBS rodnet_problems LABELS unit
            ARGS ${PROJECT_SOURCE_DIR}/problems/scenes ${CMAKE_CURRENT_BINARY_DIR})
target_include_directories(shim_newton_counts PRIVATE ${PROJECT_SOURCE_DIR}/problems)
# The distributed evaluation layer (parts, Tpetra maps, Import/Export, CrsMatrix)
# against the whole network on 1, 2 and 3 ranks (label mpi; 3 ranks: more ranks than
# rods for some networks).
add_executable(mpi_system unit/mpi_system.cpp)
target_include_directories(mpi_system PRIVATE ${PROJECT_SOURCE_DIR}/shim_cxx
                                              ${PROJECT_SOURCE_DIR}/c_api/include)
target_include_directories(mpi_system SYSTEM PRIVATE ${Trilinos_INCLUDE_DIRS}
                                                     ${Trilinos_TPL_INCLUDE_DIRS})
target_link_libraries(mpi_system PRIVATE rodnet_internal rodnet_shim_deps)
target_compile_options(mpi_system PRIVATE -O2)
if(MPIEXEC_EXECUTABLE)
  foreach(np 1 2 3)
    add_test(NAME mpi_system_np${np}
             COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${np} $<TARGET_FILE:mpi_system>)
    set_tests_properties(mpi_system_np${np} PROPERTIES LABELS "mpi" TIMEOUT 300
      PROCESSORS ${np} ENVIRONMENT
      "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")
  endforeach()
endif()
# The METIS partition of the rod graph (rn_partition_rods): balance, contiguity,
# determinism, the special cases (one part, more parts than rods, no joints).
rn_add_test(shim_partition SOURCES unit/shim_partition.c LIBS rodnet LABELS unit)
