# Installing shoal: the static library (position-independent) and libshoal_c.so.1 with their
# public headers (include/shoal/, private headers beside their sources in src/ stay out), a relocatable CMake
# package (find_package(Shoal 0.2 CONFIG): targets Shoal::shoal and Shoal::shoal_c) and the
# pkg-config files shoal.pc and shoal_c.pc. Modelled on GEOS's install rules and geos-config.cmake.
include(CMakePackageConfigHelpers)

set(SHOAL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Shoal)

install(TARGETS shoal shoal_c EXPORT ShoalTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS shoal_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The `shoal` executable loads every command but a probe of a grid file from this module, found
# relative to itself (cli/CMakeLists.txt: SHOAL_CLI_MODULE_DIR, ../lib/shoal).
install(TARGETS shoal_cli_full LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/shoal)
# libshoal_c.so.1 loads PROJ only for a grid in a user's CRS, through this module, found in
# shoal/ beside itself (src/geo/crs_loader.cpp).
install(TARGETS shoal_crs LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/shoal)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/shoal DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h")
install(FILES ${PROJECT_BINARY_DIR}/include/shoal/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/shoal)

install(EXPORT ShoalTargets NAMESPACE Shoal:: DESTINATION ${SHOAL_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ShoalConfig.cmake.in ${PROJECT_BINARY_DIR}/ShoalConfig.cmake
  INSTALL_DESTINATION ${SHOAL_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/ShoalConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/ShoalConfig.cmake ${PROJECT_BINARY_DIR}/ShoalConfigVersion.cmake DESTINATION ${SHOAL_CMAKE_DIR})

# The .pc files find the prefix from where they lie (${pcfiledir}), so the install relocates.
string(REGEX MATCHALL "[^/]+" _libdir_parts "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
set(SHOAL_PC_UP "")
foreach(_part IN LISTS _libdir_parts)
  string(APPEND SHOAL_PC_UP "../")
endforeach()
string(REGEX REPLACE "/$" "" SHOAL_PC_UP "${SHOAL_PC_UP}")
foreach(pc shoal shoal_c)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/${pc}.pc.in ${PROJECT_BINARY_DIR}/${pc}.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/${pc}.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endforeach()
