# Validation tests need the solver (shim_cxx/).
if(RN_WITH_TRILINOS)
  add_library(rn_valutil STATIC validation/valutil.c)
  target_link_libraries(rn_valutil PUBLIC rodnet rn_testutil m)
  foreach(v val_cantilever val_end_moment val_buckling val_rest_curvature val_ribbon val_networks
          val_homogenize)
    rn_add_test(${v} SOURCES validation/${v}.c LIBS rn_valutil rodnet m LABELS validation)
  endforeach()
  # Path following (docs/path-following.md): closed forms, and the strip hard case.
  set(RN_PATH_SCENES ${CMAKE_CURRENT_SOURCE_DIR}/../problems/scenes/path)
  rn_add_test(val_path SOURCES validation/val_path.c LIBS rn_valutil rodnet_problems m
              LABELS validation ARGS ${RN_PATH_SCENES} validation)
  add_test(NAME val_path_strip COMMAND val_path ${RN_PATH_SCENES} hard)
  set_tests_properties(val_path_strip PROPERTIES LABELS hard TIMEOUT 600)
  # The shallow arch's snap-through against the elastica (arch_elastica.py).
  add_test(NAME val_path_arch COMMAND val_path ${RN_PATH_SCENES} arch)
  set_tests_properties(val_path_arch PROPERTIES LABELS hard TIMEOUT 300)
  # Lattices of `rodnet generate` under stretch (frictionless grips) and grip.
  file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/val_lattice)
  rn_add_test(val_lattice_stretch SOURCES validation/val_lattice_stretch.c
              LIBS rn_valutil rodnet_problems m LABELS validation
              ARGS ${CMAKE_CURRENT_BINARY_DIR}/val_lattice)
  # Bloch-Floquet stability of periodic cells (cells written as scenes).
  file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/val_bloch_data)
  rn_add_test(val_bloch SOURCES validation/val_bloch.c
              LIBS rn_valutil rodnet_problems m LABELS validation
              ARGS ${CMAKE_CURRENT_BINARY_DIR}/val_bloch_data)
endif()
