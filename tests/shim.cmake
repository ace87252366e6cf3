# Solver shim (shim_cxx/): rn_solve with every solver kind, load stepping, negative
# curvature, runtime initialisation.  Needs LAPACK for the dense reference solutions.
if(NOT RN_WITH_TRILINOS)
  return()
endif()
rn_add_test(shim_solve SOURCES unit/shim_solve.c
            LIBS rodnet ${LAPACK_LIBRARIES} LABELS unit)
