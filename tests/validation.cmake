# Validation tests need the solver (shim_cxx/).
if(RN_WITH_TRILINOS)
  add_library(rn_valutil STATIC validation/valutil.c)
  target_link_libraries(rn_valutil PUBLIC rodnet rn_testutil m)
  foreach(v val_cantilever val_end_moment val_buckling val_rest_curvature val_ribbon val_networks)
    rn_add_test(${v} SOURCES validation/${v}.c LIBS rn_valutil rodnet m LABELS validation)
  endforeach()
endif()
