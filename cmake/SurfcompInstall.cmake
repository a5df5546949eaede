# Install rules and the CMake package a C++ user finds with find_package(surfcomp CONFIG):
# the eight static libraries as surfcomp::core, ::mesh, ::molsurf, ::harmonic, ::matching, ::docking,
# ::screening and ::report (with the 3Dmol.js viewer the report inlines, in share/surfcomp, when it was found),
# their public headers, the surfcomp program and its loadable modules (lib/surfcomp/), and
# lib/cmake/surfcomp/ with the config, its version file and the exported targets.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(SURFCOMP_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/surfcomp)

# The loadable modules (core/include/surfcomp/core/loadable_module.hpp) go into <libdir>/surfcomp,
# installed and in the build tree alike: the program (bin/ installed, tools/ in the build tree,
# both one folder down) finds them at the same relative path in both.
set(SURFCOMP_MODULE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/surfcomp)
set(SURFCOMP_MODULE_BUILD_DIR ${PROJECT_BINARY_DIR}/${SURFCOMP_MODULE_INSTALL_DIR})
file(RELATIVE_PATH SURFCOMP_MODULE_RELATIVE_DIR ${CMAKE_INSTALL_FULL_BINDIR}
     ${CMAKE_INSTALL_FULL_LIBDIR}/surfcomp)

# Makes `target` a loadable module: a shared object named lib<target>.so in the modules folder
# of the build tree and of the install, whose only exported symbols are those its code marks
# visible.
function(surfcomp_add_module target)
  add_library(${target} MODULE ${ARGN})
  set_target_properties(${target} PROPERTIES
    LIBRARY_OUTPUT_DIRECTORY ${SURFCOMP_MODULE_BUILD_DIR}
    CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
  install(TARGETS ${target} LIBRARY DESTINATION ${SURFCOMP_MODULE_INSTALL_DIR})
endfunction()

# Gives library `target` of the current module its public include/ tree (the source tree in the
# build, the installed include directory for a user), installs both, and exports the library
# as surfcomp::<export_name>.
function(surfcomp_install_library target export_name)
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                              $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name})
  install(TARGETS ${target} EXPORT surfcompTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

install(EXPORT surfcompTargets NAMESPACE surfcomp:: DESTINATION ${SURFCOMP_INSTALL_CMAKEDIR})
configure_package_config_file(
  ${CMAKE_CURRENT_LIST_DIR}/surfcompConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/surfcompConfig.cmake
  INSTALL_DESTINATION ${SURFCOMP_INSTALL_CMAKEDIR})
# Before 1.0 a minor version may change the API: only the same major.minor is compatible.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/surfcompConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/surfcompConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/surfcompConfigVersion.cmake
        DESTINATION ${SURFCOMP_INSTALL_CMAKEDIR})
