# `cmake --install build --prefix P`: headers (P/include/stiffsoft/...), the static libraries,
# the `stiffsoft` program and a CMake package, so that a project outside this tree can write
#   find_package(stiffsoft CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE stiffsoft::stiffsoft)
# (examples/embed). The package finds the same Debian packages this build used
# (cmake/stiffsoftConfig.cmake.in).
include(CMakePackageConfigHelpers)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/stiffsoft/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/stiffsoft
        FILES_MATCHING PATTERN "*.hpp")

get_property(stiffsoft_targets GLOBAL PROPERTY STIFFSOFT_EXPORTED_TARGETS)
install(TARGETS ${stiffsoft_targets} stiffsoft_cholmod stiffsoft_gmsh EXPORT stiffsoftTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
set(stiffsoft_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/stiffsoft)
install(EXPORT stiffsoftTargets NAMESPACE stiffsoft:: DESTINATION ${stiffsoft_cmake_dir})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/stiffsoftConfig.cmake.in
  ${PROJECT_BINARY_DIR}/stiffsoftConfig.cmake INSTALL_DESTINATION ${stiffsoft_cmake_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/stiffsoftConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/stiffsoftConfig.cmake ${PROJECT_BINARY_DIR}/stiffsoftConfigVersion.cmake
        DESTINATION ${stiffsoft_cmake_dir})
