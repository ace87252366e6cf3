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
