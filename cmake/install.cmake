# install.cmake - installation and packaging of rodnet (included by the top-level
# CMakeLists.txt after all targets exist).
#
# Installs: the shared library librodnet, the public headers rodnet.h and
# rodnet_solve.h, the scene library librodnet_scene and rodnet_scene.h (with the
# solver), the `rodnet` command, the example scenes (share/rodnet/scenes),
# a CMake package (find_package(rodnet) -> target rodnet::rodnet) and a pkg-config
# file (rodnet.pc).  Trilinos, MPI, METIS and LAPACK are PRIVATE dependencies of the
# shared library: a consumer needs none of them to compile or link against rodnet.
include(CMakePackageConfigHelpers)

set(RN_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/rodnet"
    CACHE STRING "Where rodnetConfig.cmake is installed (relative to the prefix)")

# The installed command finds the installed library next to it.
set(RN_INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")

install(TARGETS rodnet EXPORT rodnetTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${PROJECT_SOURCE_DIR}/c_api/include/rodnet.h ${PROJECT_SOURCE_DIR}/c_api/include/rodnet_solve.h
              ${PROJECT_SOURCE_DIR}/c_api/include/rodnet_model.h
              ${PROJECT_SOURCE_DIR}/c_api/include/rodnet_contact.h
              ${PROJECT_SOURCE_DIR}/c_api/include/rodnet_couple.h
              ${PROJECT_SOURCE_DIR}/c_api/include/rodnet_ring.h
              ${PROJECT_SOURCE_DIR}/c_api/include/rodnet_ramp.h
              ${PROJECT_SOURCE_DIR}/c_api/include/rodnet_registry.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# The scene reader and result writers (rodnet_scene.h), with the solver only.
if(TARGET rodnet_scene)
  install(TARGETS rodnet_scene EXPORT rodnetTargets
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(FILES ${PROJECT_SOURCE_DIR}/problems/include/rodnet_scene.h
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()

if(TARGET rodnet_cli)
  set_target_properties(rodnet_cli PROPERTIES INSTALL_RPATH "${RN_INSTALL_RPATH}")
  install(TARGETS rodnet_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

install(DIRECTORY ${PROJECT_SOURCE_DIR}/problems/scenes/
        DESTINATION ${CMAKE_INSTALL_DATADIR}/rodnet/scenes
        FILES_MATCHING PATTERN "*.json" PATTERN "*.obj")

# ---- CMake package ---------------------------------------------------------------
install(EXPORT rodnetTargets NAMESPACE rodnet:: FILE rodnetTargets.cmake
        DESTINATION ${RN_INSTALL_CMAKEDIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/rodnetConfig.cmake.in
  ${PROJECT_BINARY_DIR}/rodnetConfig.cmake
  INSTALL_DESTINATION ${RN_INSTALL_CMAKEDIR})
# 0.x: minor versions may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/rodnetConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/rodnetConfig.cmake
              ${PROJECT_BINARY_DIR}/rodnetConfigVersion.cmake
        DESTINATION ${RN_INSTALL_CMAKEDIR})

# ---- pkg-config --------------------------------------------------------------------
# The prefix is found relative to the .pc file (pkg-config's ${pcfiledir}), so the file
# stays right for `cmake --install --prefix DIR` and a relocated tree.
file(RELATIVE_PATH RN_PC_PREFIX_REL "/rn/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/rn")
if(RN_WITH_TRILINOS)
  set(RN_PC_CFLAGS "-DRN_HAVE_SOLVER=1")
else()
  set(RN_PC_CFLAGS "")
endif()
configure_file(${CMAKE_CURRENT_LIST_DIR}/rodnet.pc.in ${PROJECT_BINARY_DIR}/rodnet.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/rodnet.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
if(TARGET rodnet_scene)
  configure_file(${CMAKE_CURRENT_LIST_DIR}/rodnet-scene.pc.in
                 ${PROJECT_BINARY_DIR}/rodnet-scene.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/rodnet-scene.pc
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endif()
