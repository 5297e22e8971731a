# SPDX-License-Identifier: MIT
# cmake --install: the runtime library and headers, a CMake package
# (find_package(posemorph) -> posemorph::runtime, and posemorph::bake when it
# was built), a pkg-config file (posemorph-runtime.pc) and the tools.
include(CMakePackageConfigHelpers)
set(posemorph_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/posemorph)

install(TARGETS posemorph_runtime EXPORT posemorph-runtime-targets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/runtime/include/posemorph DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT posemorph-runtime-targets NAMESPACE posemorph:: DESTINATION ${posemorph_cmake_dir})
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/THIRD_PARTY.md
  DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/posemorph)

set(POSEMORPH_CONFIG_HAS_BAKE OFF)
if(TARGET posemorph_bake)
  set(POSEMORPH_CONFIG_HAS_BAKE ON)
  set_target_properties(posemorph_bake PROPERTIES EXPORT_NAME bake)
  target_include_directories(posemorph_bake PUBLIC $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  set_target_properties(posemorph_tool_base PROPERTIES EXPORT_NAME tool_base)
  target_include_directories(posemorph_tool_base PUBLIC $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  install(TARGETS posemorph_bake posemorph_tool_base EXPORT posemorph-bake-targets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/bake/include/posemorph DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT posemorph-bake-targets NAMESPACE posemorph:: DESTINATION ${posemorph_cmake_dir})
  install(TARGETS posemorph-bake RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
if(TARGET posemorph-view)
  install(TARGETS posemorph-view RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/posemorph-config.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/posemorph-config.cmake INSTALL_DESTINATION ${posemorph_cmake_dir})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/posemorph-config-version.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/posemorph-config.cmake ${CMAKE_CURRENT_BINARY_DIR}/posemorph-config-version.cmake
  DESTINATION ${posemorph_cmake_dir})

# pkg-config: a C or C++ program links -lposemorph. The static library
# also needs the C++ runtime: it is in Libs, so that plain `pkg-config
# --libs` links a C program (a shared library brings its own, so there it
# is only in Libs.private).
get_target_property(posemorph_runtime_type posemorph_runtime TYPE)
set(POSEMORPH_PC_CFLAGS "")
set(POSEMORPH_PC_LIBS "-lposemorph -lstdc++ -lm")
set(POSEMORPH_PC_LIBS_PRIVATE "")
if(posemorph_runtime_type STREQUAL "SHARED_LIBRARY")
  set(POSEMORPH_PC_CFLAGS "-DPOSEMORPH_SHARED")
  set(POSEMORPH_PC_LIBS "-lposemorph")
  set(POSEMORPH_PC_LIBS_PRIVATE "-lstdc++ -lm")
endif()
# Relocatable: the prefix is found from the .pc file's own folder, so
# `cmake --install --prefix DIR` works without reconfiguring.
file(RELATIVE_PATH POSEMORPH_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
configure_file(${CMAKE_CURRENT_LIST_DIR}/posemorph-runtime.pc.in ${CMAKE_CURRENT_BINARY_DIR}/posemorph-runtime.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/posemorph-runtime.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
