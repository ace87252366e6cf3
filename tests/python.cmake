# The Python package (docs/python.md; label python): pytest on tests/python/ with
# Debian's python3 (numpy, scipy, pytest: scripts/setup.sh installs them), the
# build tree's package on PYTHONPATH and the build's `rodnet` command for the
# comparisons; and every example of examples/python/, as a user runs it.
if(NOT TARGET rodnet_python)
  return()
endif()
find_program(RN_PY3 NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT RN_PY3)
  message(WARNING "no /usr/bin/python3: the python tests are not registered")
  return()
endif()
set(RN_PY_ENV "PYTHONPATH=${PROJECT_BINARY_DIR}/python"
              "RODNET_CLI=$<TARGET_FILE:rodnet_cli>" "MPLBACKEND=Agg")
set(RN_PY_OUT ${CMAKE_CURRENT_BINARY_DIR}/python_out)
file(MAKE_DIRECTORY ${RN_PY_OUT})
add_test(NAME python_pytest
  COMMAND ${RN_PY3} -m pytest -q -p no:cacheprovider ${CMAKE_CURRENT_SOURCE_DIR}/python
  WORKING_DIRECTORY ${RN_PY_OUT})
add_test(NAME python_example_cantilever
  COMMAND ${RN_PY3} ${PROJECT_SOURCE_DIR}/examples/python/cantilever.py
  WORKING_DIRECTORY ${RN_PY_OUT})
add_test(NAME python_example_lattice
  COMMAND ${RN_PY3} ${PROJECT_SOURCE_DIR}/examples/python/lattice.py
          ${RN_PY_OUT}/lattice.png
  WORKING_DIRECTORY ${RN_PY_OUT})
add_test(NAME python_example_homogenization_sweep
  COMMAND ${RN_PY3} ${PROJECT_SOURCE_DIR}/examples/python/homogenization_sweep.py
          ${RN_PY_OUT}/homogenization_sweep.png
  WORKING_DIRECTORY ${RN_PY_OUT})
# (the smoke suite in the tests; the quick suite's table is in docs/python.md)
add_test(NAME python_example_scipy_vs_rodnet
  COMMAND ${RN_PY3} ${PROJECT_SOURCE_DIR}/examples/python/scipy_vs_rodnet.py
          --suite smoke -o ${RN_PY_OUT}/scipy_vs_rodnet
  WORKING_DIRECTORY ${RN_PY_OUT})
set_tests_properties(python_pytest python_example_cantilever python_example_lattice
                     python_example_homogenization_sweep python_example_scipy_vs_rodnet
                     PROPERTIES LABELS python TIMEOUT 600 ENVIRONMENT "${RN_PY_ENV}")
set_tests_properties(python_example_lattice PROPERTIES
                     PASS_REGULAR_EXPRESSION "wrote .*lattice.png")
