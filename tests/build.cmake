# Build-infrastructure tests (label unit): layering of the folders, install + outside
# consumer, and the clang-format check.  They test the tree and the build itself, so
# they are registered only in plain (non-sanitizer) builds: a sanitized kernels archive
# needs __asan_* symbols and a sanitized library cannot be linked by a plain consumer.
if(RN_SANITIZE)
  return()
endif()

find_program(RN_BASH bash REQUIRED)
set(RN_BUILD_TEST_DIR ${CMAKE_CURRENT_SOURCE_DIR}/build)

# (a) layering: include lines per folder and `nm -u` of the kernels archive.
add_test(NAME layering
  COMMAND ${RN_BASH} ${RN_BUILD_TEST_DIR}/check_layering.sh ${PROJECT_SOURCE_DIR}
          $<TARGET_FILE:rodnet_kernels_static> ${CMAKE_NM})
set_tests_properties(layering PROPERTIES LABELS "unit" TIMEOUT 120
  ENVIRONMENT "CC=${CMAKE_C_COMPILER}")
# The folder-order part of `layering` fails on a violation: a fixture tree with an
# upward include and one between independent folders (tests/build/folder_order_fixture/).
add_test(NAME layering_folder_order_fixture
  COMMAND ${RN_BASH} ${RN_BUILD_TEST_DIR}/check_folder_order_fixture.sh ${RN_BUILD_TEST_DIR})
set_tests_properties(layering_folder_order_fixture PROPERTIES LABELS "unit" TIMEOUT 120)

# (b) install into a temporary prefix, then build and run tests/build/consumer/
# against it with find_package(rodnet) and with pkg-config.
if(TARGET rodnet_cli)
  set(RN_HAVE_CLI 1)
else()
  set(RN_HAVE_CLI 0)
endif()
add_test(NAME install_consumer
  COMMAND ${RN_BASH} ${RN_BUILD_TEST_DIR}/check_install.sh ${PROJECT_BINARY_DIR}
          ${PROJECT_SOURCE_DIR} ${CMAKE_C_COMPILER} ${RN_HAVE_CLI})
set_tests_properties(install_consumer PROPERTIES LABELS "unit" TIMEOUT 300)

# (b') the shared libraries export their C API only: librodnet rn_* names
# (cmake/librodnet.map);
# librodnet_scene exports exactly the functions of rodnet_scene.h.
add_test(NAME exported_symbols
  COMMAND ${RN_BASH} ${RN_BUILD_TEST_DIR}/check_exports.sh ${CMAKE_NM} $<TARGET_FILE:rodnet>)
set_tests_properties(exported_symbols PROPERTIES LABELS "unit" TIMEOUT 60)
if(TARGET rodnet_scene)
  add_test(NAME exported_symbols_scene
    COMMAND ${RN_BASH} ${RN_BUILD_TEST_DIR}/check_exports.sh ${CMAKE_NM}
            $<TARGET_FILE:rodnet_scene> ${PROJECT_SOURCE_DIR}/problems/include/rodnet_scene.h)
  set_tests_properties(exported_symbols_scene PROPERTIES LABELS "unit" TIMEOUT 60)
endif()

# (c) every C/C++ source follows .clang-format.
find_program(RN_CLANG_FORMAT NAMES clang-format clang-format-14)
if(RN_CLANG_FORMAT)
  add_test(NAME format_check
    COMMAND ${RN_BASH} ${RN_BUILD_TEST_DIR}/check_format.sh ${PROJECT_SOURCE_DIR}
            ${RN_CLANG_FORMAT})
  set_tests_properties(format_check PROPERTIES LABELS "unit" TIMEOUT 120)
else()
  message(WARNING "clang-format not found: the format_check test is not registered "
                  "(scripts/setup.sh installs it)")
endif()
