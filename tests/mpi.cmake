# The `rodnet` command under mpirun (label mpi, 2 or 3 ranks, with a timeout): a bad
# scene, an error only some ranks see, a solver that cannot run distributed, more
# ranks than rods: one clear error (one line on stderr, from rank 0) and the same
# exit status on every rank, never a hang.
if(NOT RN_WITH_TRILINOS OR NOT MPIEXEC_EXECUTABLE)
  return()
endif()
set(RN_MPI_DATA ${CMAKE_CURRENT_SOURCE_DIR}/data/mpi)
set(RN_MPI_OUT ${CMAKE_CURRENT_BINARY_DIR}/mpi_cli)
file(MAKE_DIRECTORY ${RN_MPI_OUT})
set(RN_MPI_ENV
    "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")

# rn_mpi_cli(NAME NP RC REGEX ARGS...): rodnet on NP ranks exits with RC on every
# rank (mpirun returns it), prints one line on stderr matching REGEX (mpirun -q:
# Open MPI's own notice about the non-zero status is not printed), writes no result
# file.
function(rn_mpi_cli name np rc regex)
  string(REPLACE ";" "@@" args "${ARGN}")
  add_test(NAME ${name}
           COMMAND ${CMAKE_COMMAND} -DCMD=${MPIEXEC_EXECUTABLE}
                   "-DARGS=-q@@${MPIEXEC_NUMPROC_FLAG}@@${np}@@${CMAKE_BINARY_DIR}/rodnet@@${args}"
                   -DEXPECT_RC=${rc} "-DEXPECT_REGEX=${regex}" -DSTDERR_LINES=1
                   -DREMOVE=${RN_MPI_OUT}/${name}.json
                   -DEXPECT_ABSENT=${RN_MPI_OUT}/${name}.json
                   -P ${CMAKE_CURRENT_SOURCE_DIR}/unit/problems_run.cmake)
  set_tests_properties(${name} PROPERTIES LABELS mpi TIMEOUT 120 PROCESSORS ${np}
                       ENVIRONMENT "${RN_MPI_ENV}")
endfunction()

# rn_mpi_usage_once(NAME REGEX ARGS...): rodnet on 2 ranks prints a usage error
# once (its two lines, from rank 0, matching REGEX) and exits 2 on every rank.
function(rn_mpi_usage_once name regex)
  string(REPLACE ";" "@@" args "${ARGN}")
  add_test(NAME ${name}
           COMMAND ${CMAKE_COMMAND} -DCMD=${MPIEXEC_EXECUTABLE}
                   "-DARGS=-q@@${MPIEXEC_NUMPROC_FLAG}@@2@@${CMAKE_BINARY_DIR}/rodnet@@${args}"
                   -DEXPECT_RC=2 "-DEXPECT_REGEX=${regex}" -DSTDERR_LINES=2
                   -P ${CMAKE_CURRENT_SOURCE_DIR}/unit/problems_run.cmake)
  set_tests_properties(${name} PROPERTIES LABELS mpi TIMEOUT 120 PROCESSORS 2
                       ENVIRONMENT "${RN_MPI_ENV}")
endfunction()

rn_mpi_cli(mpi_cli_malformed 2 3 "malformed JSON"
           solve ${CMAKE_CURRENT_SOURCE_DIR}/data/bad/malformed.json -o ${RN_MPI_OUT}/mpi_cli_malformed.json)
rn_mpi_cli(mpi_cli_coincident 2 3 "joints 0 .'J1'. and 1 .'J2'. are coincident"
           solve ${RN_MPI_DATA}/coincident_joints.json -o ${RN_MPI_OUT}/mpi_cli_coincident.json)
rn_mpi_cli(mpi_cli_gap_joint 2 3 "rod ends do not meet"
           solve ${RN_MPI_DATA}/gap_joint.json -o ${RN_MPI_OUT}/mpi_cli_gap_joint.json)
rn_mpi_cli(mpi_cli_unwritable 2 3 "cannot"
           solve ${RN_MPI_DATA}/chain.json -o /nonexistent-dir/result.json)
rn_mpi_cli(mpi_cli_serial_solver 2 2 "solver 'tr-minres' .*cannot run on 2 MPI ranks"
           solve ${RN_MPI_DATA}/chain.json --solver tr-minres
           -o ${RN_MPI_OUT}/mpi_cli_serial_solver.json)
# ---- issue 22 item 5: the one-process commands under mpirun ------------------------
# homogenize, path, generate, check and bench on 2 ranks used to run the whole
# job on every rank (every message twice, both ranks writing the same files); they
# refuse: one line from rank 0, exit status 2 on every rank, nothing written, no hang.
# (sweep and homogenize run distributed since issue 24: mpi_sweep and
# mpi_periodic below; a scene that is not periodic is refused once.)
set(RN_MPI_REFUSE "runs on one process, not on 2 MPI ranks.*run it without mpirun")
rn_mpi_cli(mpi_cli_homogenize_not_periodic 2 3 "chain.json: the scene is not periodic"
           homogenize ${RN_MPI_DATA}/chain.json -o ${RN_MPI_OUT}/mpi_cli_homogenize_not_periodic.json)
rn_mpi_cli(mpi_cli_one_process_path 2 2 "rodnet path: ${RN_MPI_REFUSE}"
           path ${RN_MPI_DATA}/chain.json -o ${RN_MPI_OUT}/mpi_cli_one_process_path.json)
rn_mpi_cli(mpi_cli_one_process_generate 2 2 "rodnet generate: ${RN_MPI_REFUSE}"
           generate square --cells 2 -o ${RN_MPI_OUT}/mpi_cli_one_process_generate.json)
rn_mpi_cli(mpi_cli_one_process_check 2 2 "rodnet check: ${RN_MPI_REFUSE}"
           check ${RN_MPI_DATA}/chain.json --random 0)
rn_mpi_cli(mpi_cli_one_process_bench 2 2 "rodnet bench: ${RN_MPI_REFUSE}"
           bench --suite smoke --no-plot -o ${RN_MPI_OUT}/mpi_cli_one_process_bench.json)
# ---- issue 24 section 4: sweeps spread over the ranks ------------------------------
# The same CSV on 1 and 2 ranks (a path to the first instability per point), one
# progress bar, resumes, failing points reported once (tests/unit/check_sweep_mpi.py).
add_test(NAME mpi_sweep
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_sweep_mpi.py
                 ${CMAKE_BINARY_DIR}/rodnet ${MPIEXEC_EXECUTABLE} 2 ${RN_MPI_OUT}/sweep)
set_tests_properties(mpi_sweep PROPERTIES LABELS mpi TIMEOUT 300 PROCESSORS 2
                     ENVIRONMENT "${RN_MPI_ENV}")
# ---- issue 24 section 1: periodic cells in the distributed solver -----------------
# homogenize and solve of periodic cells and supercells (2D, 3D, elastic and rigid
# joints, mixed strain / stress control) on 1 and 2 ranks: the same C, strain and
# stress to 1e-10, the partition recorded (tests/unit/check_periodic_mpi.py).
add_test(NAME mpi_periodic
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_periodic_mpi.py
                 ${CMAKE_BINARY_DIR}/rodnet ${MPIEXEC_EXECUTABLE} 2 ${RN_MPI_OUT}/periodic)
set_tests_properties(mpi_periodic PROPERTIES LABELS mpi TIMEOUT 300 PROCESSORS 2
                     ENVIRONMENT "${RN_MPI_ENV}")
add_test(NAME mpi_path
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_path_mpi.py
                 ${CMAKE_BINARY_DIR}/rodnet ${MPIEXEC_EXECUTABLE} 2 ${RN_MPI_OUT}/path)
set_tests_properties(mpi_path PROPERTIES LABELS mpi TIMEOUT 300 PROCESSORS 2
                     ENVIRONMENT "${RN_MPI_ENV}")
# A usage error of sweep is printed once, a bad sweep file once (rank 0).
rn_mpi_usage_once(mpi_cli_sweep_usage_once "missing -o DIR"
                  sweep ${CMAKE_CURRENT_SOURCE_DIR}/data/periodic/sweep_hc.json)
rn_mpi_cli(mpi_cli_sweep_bad 2 3 "sweep_bad.json: unknown key 'density'"
           sweep ${CMAKE_CURRENT_SOURCE_DIR}/data/periodic/sweep_bad.json
           -o ${RN_MPI_OUT}/mpi_cli_sweep_bad)
# A usage error of solve is printed once (by rank 0): its two lines, not four.
rn_mpi_usage_once(mpi_cli_usage_once "missing -o RESULT.json" solve ${RN_MPI_DATA}/chain.json)

# No solver asked for: under mpirun the default is the distributed tr-krylov (dd).
add_test(NAME mpi_cli_default_solver
         COMMAND ${CMAKE_COMMAND} -DCMD=${MPIEXEC_EXECUTABLE}
                 "-DARGS=-q@@${MPIEXEC_NUMPROC_FLAG}@@2@@${CMAKE_BINARY_DIR}/rodnet@@solve@@${RN_MPI_DATA}/chain.json@@-o@@${RN_MPI_OUT}/mpi_cli_default_solver.json"
                 -DEXPECT_RC=0
                 "-DEXPECT_REGEX=solver +tr-krylov .*preconditioner dd.*partition +2 ranks"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/unit/problems_run.cmake)
set_tests_properties(mpi_cli_default_solver PROPERTIES LABELS mpi TIMEOUT 120
                     PROCESSORS 2 ENVIRONMENT "${RN_MPI_ENV}")

# The same scenes on 1 and 2 ranks with the distributed solver (tr-krylov, with the
# load-step predictor, distributed on 2 ranks): a single rod, independent
# rods, a honeycomb with rigid joints, an octet block, a chain with elastic and rigid
# joints, a buckled column, closed rods (a loaded twisted ring, which one rank of two
# owns; two rings, one per rank) (tests/unit/check_mpi_solve.py):
#  - mpi_solve_<scene>: the gathered preconditioner on both (the factor
#    preconditioner's matrix, also on 2 ranks): energy and positions agree to 1e-10,
#    Newton iterations and load steps are equal;
#  - mpi_solve_dd_<scene>: the rod-level domain decomposition (the default) on both,
#    gradient tolerance 1e-14 (down to the round-off floor, the stopping test's own
#    limit): the preconditioner does not depend on the partition (rod blocks, exact
#    coarse problem on the joints), so energy and positions agree to 1e-10 and the
#    Newton iterations and load steps are equal;
# and in both the partition adds up and no rank owns more than 55 %.
set(RN_DIST_SOLVER "tr-krylov" CACHE STRING "distributed solver kind of the mpi tests")
set(RN_MPI_SCENES ${RN_MPI_OUT}/scenes)
file(MAKE_DIRECTORY ${RN_MPI_SCENES})
add_test(NAME mpi_solve_scenes
         COMMAND sh -c "${CMAKE_BINARY_DIR}/rodnet generate honeycomb --cells 4 --edges-per-rod 4 --joint-model rigid --load stretch-x:1e-3 -o ${RN_MPI_SCENES}/honeycomb.json && ${CMAKE_BINARY_DIR}/rodnet generate octet --cells 2 --edges-per-rod 3 --load compress-z:1e-3 -o ${RN_MPI_SCENES}/octet.json")
set_tests_properties(mpi_solve_scenes PROPERTIES LABELS mpi TIMEOUT 60
                     FIXTURES_SETUP rn_mpi_scenes)
foreach(case "cantilever|${RN_SCENES}/cantilever.json|1.0"
             "independent|${RN_MPI_DATA}/independent.json|0.55"
             "honeycomb|${RN_MPI_SCENES}/honeycomb.json|0.55"
             "octet|${RN_MPI_SCENES}/octet.json|0.55"
             "chain|${RN_MPI_DATA}/chain.json|0.55"
             "buckled_column|${RN_SCENES}/pinned_column.json|1.0"
             "loaded_ring|${RN_MPI_DATA}/loaded_ring.json|1.0"
             "two_rings|${RN_MPI_DATA}/two_rings.json|0.55")
  string(REPLACE "|" ";" case "${case}")
  list(GET case 0 name)
  list(GET case 1 scene)
  list(GET case 2 share)
  set(rn_check ${RN_VTK_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_mpi_solve.py
      --rodnet ${CMAKE_BINARY_DIR}/rodnet --mpiexec ${MPIEXEC_EXECUTABLE} --np 2
      --scene ${scene} --solver ${RN_DIST_SOLVER} --out ${RN_MPI_OUT}/solve
      --max-share ${share})
  add_test(NAME mpi_solve_${name}
           COMMAND ${rn_check} "--args=--preconditioner gathered"
                   --same-iterations)
  add_test(NAME mpi_solve_dd_${name}
           COMMAND ${rn_check} "--args=--preconditioner dd --gtol 1e-14" --label .dd
                   --same-iterations)
  foreach(t mpi_solve_${name} mpi_solve_dd_${name})
    set_tests_properties(${t} PROPERTIES LABELS mpi TIMEOUT 600 PROCESSORS 2
                         ENVIRONMENT "${RN_MPI_ENV}" FIXTURES_REQUIRED rn_mpi_scenes)
  endforeach()
endforeach()
# The loop of two rods through a smooth and a rigid joint (problems/scenes/loop_joint.json,
# issue 22): its trust region reaches the energy's round-off (|g| ~ 1e-7) long before
# the stopping test's floor, where its decisions are noise and the one- and two-rank
# paths may part; until then (|g| >= 1e-6 on one rank: the load-step predictor and 14
# Newton iterations) the two runs take the same steps (--same-path-above), and both
# converge to the same equilibrium.  Both at the default tolerance: the loop rolls
# freely about its centre line (a symmetry, the stability check's), along which the
# Newton step is undetermined, so the round-off band of --gtol 1e-14, which asks for
# a short Newton step (docs/solvers.md "Stopping tests"), is not reached.
foreach(pre gathered dd)
  set(rn_t mpi_solve_loop_joint)
  set(rn_a "--args=--preconditioner ${pre}")
  if(pre STREQUAL "dd")
    set(rn_t mpi_solve_dd_loop_joint)
  endif()
  add_test(NAME ${rn_t}
           COMMAND ${RN_VTK_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_mpi_solve.py
                   --rodnet ${CMAKE_BINARY_DIR}/rodnet --mpiexec ${MPIEXEC_EXECUTABLE}
                   --np 2 --scene ${RN_SCENES}/loop_joint.json --solver ${RN_DIST_SOLVER}
                   --out ${RN_MPI_OUT}/solve --label .${pre} --max-share 0.55 "${rn_a}"
                   --same-path-above 1e-6)
  set_tests_properties(${rn_t} PROPERTIES LABELS mpi TIMEOUT 600 PROCESSORS 2
                       ENVIRONMENT "${RN_MPI_ENV}")
endforeach()
# The LOBPCG stability check forced on one rank too (stability_method): the same
# lowest eigenvalue, zero modes and verdict on 1 and 2 ranks.
foreach(name honeycomb octet)
  add_test(NAME mpi_stability_lobpcg_${name}
           COMMAND ${RN_VTK_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_mpi_solve.py
                   --rodnet ${CMAKE_BINARY_DIR}/rodnet --mpiexec ${MPIEXEC_EXECUTABLE}
                   --np 2 --scene ${RN_MPI_SCENES}/${name}.json --solver tr-krylov
                   --out ${RN_MPI_OUT}/solve --label .lobpcg
                   "--args=--preconditioner dd --gtol 1e-14 --stability-method lobpcg"
                   --same-iterations)
  set_tests_properties(mpi_stability_lobpcg_${name} PROPERTIES LABELS mpi TIMEOUT 600
                       PROCESSORS 2 ENVIRONMENT "${RN_MPI_ENV}"
                       FIXTURES_REQUIRED rn_mpi_scenes)
endforeach()
# FROSch (two-level Schwarz, an alternative preconditioner measured against dd) on
# 2 ranks, two subdomains with their coarse space: the one-rank equilibrium (energy
# and positions to 1e-10; an inexact preconditioner, so the iterations may differ).
# The default stability check: LOBPCG preconditioned by FROSch breaks down on 2 ranks
# (Anasazi's Cholesky of the basis fails, docs/solvers.md); the check then reports
# "not checked" and rodnet solve checks the gathered state by Cholesky on rank 0,
# with nothing of Anasazi's on standard output (check_mpi_solve.py).
foreach(case "honeycomb|${RN_MPI_SCENES}/honeycomb.json" "octet|${RN_MPI_SCENES}/octet.json")
  string(REPLACE "|" ";" case "${case}")
  list(GET case 0 name)
  list(GET case 1 scene)
  add_test(NAME mpi_solve_frosch_${name}
           COMMAND ${RN_VTK_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_mpi_solve.py
                   --rodnet ${CMAKE_BINARY_DIR}/rodnet --mpiexec ${MPIEXEC_EXECUTABLE}
                   --np 2 --scene ${scene} --solver ${RN_DIST_SOLVER}
                   --out ${RN_MPI_OUT}/solve --max-share 0.55
                   "--args=--preconditioner frosch --gtol 1e-14"
                   --label .frosch)
  # the one-rank run needs the MPI runtime too (FROSch, TRILINOS.md)
  set_tests_properties(mpi_solve_frosch_${name} PROPERTIES LABELS mpi TIMEOUT 600
                       PROCESSORS 2 ENVIRONMENT "${RN_MPI_ENV};RODNET_MPI=1"
                       FIXTURES_REQUIRED rn_mpi_scenes)
endforeach()
# More ranks than rods: a single rod on 3 ranks (two ranks own nothing) gives the
# one-rank result (default solver and preconditioner), no error and no hang.
add_test(NAME mpi_solve_more_ranks
         COMMAND ${RN_VTK_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_mpi_solve.py
                 --rodnet ${CMAKE_BINARY_DIR}/rodnet --mpiexec ${MPIEXEC_EXECUTABLE}
                 --np 3 --scene ${RN_SCENES}/cantilever.json --solver tr-krylov
                 --out ${RN_MPI_OUT}/solve --max-share 1.0 --label .more
                 --same-iterations)
set_tests_properties(mpi_solve_more_ranks PROPERTIES LABELS mpi TIMEOUT 300 PROCESSORS 2
                     ENVIRONMENT "${RN_MPI_ENV}")

# Prescribed displacements larger than the edges next to them (issue 10 section 2):
# a 4x4 square lattice compressed by 5 % (the face moves by 0.2, edges 0.125) ramped in
# sub-steps on 2 ranks (tr-krylov distributed), past bar buckling to a verified minimum.
if(RN_VTK_PYTHON)
  add_test(NAME mpi_ramp_square_compress
           COMMAND ${RN_VTK_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_ramp.py
                   ${CMAKE_BINARY_DIR}/rodnet ${RN_MPI_OUT}/ramp --solvers tr-krylov
                   --edges 8 --cells 4,4 --strain 0.05 "--mpiexec=${MPIEXEC_EXECUTABLE} -q ${MPIEXEC_NUMPROC_FLAG} 2")
  set_tests_properties(mpi_ramp_square_compress PROPERTIES LABELS mpi TIMEOUT 600
                       PROCESSORS 2 ENVIRONMENT "${RN_MPI_ENV}")
endif()

# The planar model against the 3D model (docs/model.md): positions, energies,
# reactions, the homogenised C and a strain path to 1e-10 on lattices and single
# rods, tr-minres, tr-krylov and tr-krylov on 2 ranks; the scene checks of
# "model": "planar" and the detection report.
add_test(NAME problems_cli_planar
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_planar.py
                 ${CMAKE_BINARY_DIR}/rodnet ${RN_MPI_OUT}/planar ${MPIEXEC_EXECUTABLE})
set_tests_properties(problems_cli_planar PROPERTIES LABELS "unit;mpi" TIMEOUT 600
                     PROCESSORS 2 ENVIRONMENT "${RN_MPI_ENV}")
