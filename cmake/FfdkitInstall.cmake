# Installation and the CMake package, in one place. Every library made with
# ffdkit_add_module_library() is installed and exported as ffdkit::<module> through
# ffdkit_install_library(); programs through ffdkit_install_programs(). The package files
# (ffdkitConfig.cmake, ffdkitTargets.cmake) are written once by ffdkit_install_package(), after
# every module has been added.

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(FFDKIT_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/ffdkit" CACHE STRING
    "Install folder of ffdkit's CMake package files, relative to the prefix")

# ffdkit_install_library(target module [HEADERS dir]): installs a library target (static or
# INTERFACE) into the export set as ffdkit::<module>, and the public headers under `dir`
# (<dir>/ffdkit/... -> <prefix>/include/ffdkit/...).
function(ffdkit_install_library target module)
  cmake_parse_arguments(ARG "" "HEADERS" "" ${ARGN})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${module})
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    target_include_directories(${target} INTERFACE $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  else()
    target_include_directories(${target} PUBLIC $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  endif()
  install(TARGETS ${target} EXPORT ffdkitTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  if(ARG_HEADERS AND EXISTS "${ARG_HEADERS}")
    install(DIRECTORY "${ARG_HEADERS}/" DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
  endif()
  set_property(GLOBAL APPEND PROPERTY FFDKIT_INSTALLED_MODULES ${module})
endfunction()

# ffdkit_install_programs(target...): executables into <prefix>/bin.
function(ffdkit_install_programs)
  install(TARGETS ${ARGN} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

# ffdkit_install_package(): the export set and ffdkitConfig.cmake, which finds the packages the
# exported (static) libraries link: Eigen, threads, OpenMP and, with the scenes module, the VTK
# components and nlohmann-json of the top-level find_package calls (FFDKIT_VTK_COMPONENTS).
function(ffdkit_install_package)
  get_property(modules GLOBAL PROPERTY FFDKIT_INSTALLED_MODULES)
  set(FFDKIT_PACKAGE_MODULES "${modules}")
  if(TARGET ffdkit_scenes)
    set(FFDKIT_PACKAGE_VTK_COMPONENTS "${FFDKIT_VTK_COMPONENTS}")
  else()
    set(FFDKIT_PACKAGE_VTK_COMPONENTS "")
  endif()
  install(EXPORT ffdkitTargets NAMESPACE ffdkit:: DESTINATION ${FFDKIT_INSTALL_CMAKEDIR})
  configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/ffdkitConfig.cmake.in"
    "${PROJECT_BINARY_DIR}/ffdkitConfig.cmake" INSTALL_DESTINATION ${FFDKIT_INSTALL_CMAKEDIR})
  write_basic_package_version_file("${PROJECT_BINARY_DIR}/ffdkitConfigVersion.cmake"
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
  install(FILES "${PROJECT_BINARY_DIR}/ffdkitConfig.cmake" "${PROJECT_BINARY_DIR}/ffdkitConfigVersion.cmake"
    DESTINATION ${FFDKIT_INSTALL_CMAKEDIR})
endfunction()
