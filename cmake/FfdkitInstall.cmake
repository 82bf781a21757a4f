# Installation and the CMake package, in one place. Every library made with
# ffdkit_add_module_library() is installed and exported as ffdkit::<module> through
# ffdkit_install_library(); programs through ffdkit_install_programs(). The package files
# (ffdkitConfig.cmake and one ffdkit-<component>-targets.cmake per component) are written once by
# ffdkit_install_package(), after every module has been added.
#
# Components of the package (find_package(ffdkit COMPONENTS ...)), each with its targets:
#   ffd        ffdkit::ffd
#   widgets    ffdkit::widgets
#   geometry   ffdkit::geometry, ffdkit::geometry_core, ffdkit::geometry_<topic>
#   meshio     ffdkit::meshio
#   scenes     ffdkit::scenes
#   exporters  ffdkit::exporters
#   app        ffdkit::interaction, ffdkit::parts (the application's headless libraries)
#   cad        ffdkit::cad (built with OpenCASCADE, FFDKIT_WITH_CAD: its consumers find OpenCASCADE)
# A component's targets link only targets of the components it needs; the packages each needs
# are found in cmake/ffdkitConfig.cmake.in.

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(FFDKIT_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/ffdkit" CACHE STRING
    "Install folder of ffdkit's CMake package files, relative to the prefix")

# Every component, dependencies before the components that need them (the config file loads them
# in this order).
set(FFDKIT_PACKAGE_COMPONENT_ORDER ffd geometry widgets meshio scenes exporters app cad)

# ffdkit_component_of(module out_var): the package component a module's target belongs to.
function(ffdkit_component_of module out_var)
  if(module MATCHES "^geometry")
    set(${out_var} geometry PARENT_SCOPE)
  elseif(module STREQUAL "interaction" OR module STREQUAL "parts")
    set(${out_var} app PARENT_SCOPE)
  else()
    set(${out_var} ${module} PARENT_SCOPE)
  endif()
endfunction()

# ffdkit_install_library(target module [HEADERS dir]): installs a library target (static or
# INTERFACE) into its component's export set as ffdkit::<module>, and the public headers under
# `dir` (<dir>/ffdkit/... -> <prefix>/include/ffdkit/...). The target's usage requirements say
# C++20, so a project that links it needs no CMAKE_CXX_STANDARD of its own.
function(ffdkit_install_library target module)
  cmake_parse_arguments(ARG "" "HEADERS" "" ${ARGN})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${module})
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    set(scope INTERFACE)
  else()
    set(scope PUBLIC)
  endif()
  target_include_directories(${target} ${scope} $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(${target} ${scope} cxx_std_20)
  ffdkit_component_of(${module} component)
  install(TARGETS ${target} EXPORT ffdkit-${component}-targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  if(ARG_HEADERS AND EXISTS "${ARG_HEADERS}")
    install(DIRECTORY "${ARG_HEADERS}/" DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
  endif()
  set_property(GLOBAL APPEND PROPERTY FFDKIT_INSTALLED_MODULES ${module})
  set_property(GLOBAL APPEND PROPERTY FFDKIT_INSTALLED_TARGETS ${target})
endfunction()

# ffdkit_install_programs(target...): executables into <prefix>/bin.
function(ffdkit_install_programs)
  install(TARGETS ${ARGN} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

# ffdkit_install_package(): one export set per component and ffdkitConfig.cmake. What each
# component needs of the others is read from its targets' links (ffdkit::<module> entries), so the
# config file loads exactly the components a project asks for and the ones they link.
function(ffdkit_install_package)
  get_property(modules GLOBAL PROPERTY FFDKIT_INSTALLED_MODULES)
  get_property(targets GLOBAL PROPERTY FFDKIT_INSTALLED_TARGETS)
  set(components "")
  foreach(target module IN ZIP_LISTS targets modules)
    ffdkit_component_of(${module} component)
    list(APPEND components ${component})
    list(APPEND targets_of_${component} ffdkit::${module})
    get_target_property(links ${target} LINK_LIBRARIES)
    get_target_property(interface_links ${target} INTERFACE_LINK_LIBRARIES)
    foreach(link IN LISTS links interface_links)
      if(link MATCHES "^ffdkit::(.+)$")
        ffdkit_component_of(${CMAKE_MATCH_1} needed)
        if(NOT needed STREQUAL component)
          list(APPEND needs_of_${component} ${needed})
        endif()
      endif()
    endforeach()
  endforeach()
  # The config file's table: each component's targets (a comment) and the components they link.
  set(FFDKIT_PACKAGE_COMPONENTS "")
  set(FFDKIT_PACKAGE_COMPONENT_TABLE "")
  foreach(component IN LISTS FFDKIT_PACKAGE_COMPONENT_ORDER)
    if(NOT component IN_LIST components)
      continue()
    endif()
    list(APPEND FFDKIT_PACKAGE_COMPONENTS ${component})
    list(REMOVE_DUPLICATES needs_of_${component})
    foreach(needed IN LISTS needs_of_${component})
      list(FIND FFDKIT_PACKAGE_COMPONENT_ORDER ${needed} needed_at)
      list(FIND FFDKIT_PACKAGE_COMPONENT_ORDER ${component} component_at)
      if(needed_at GREATER component_at)
        message(FATAL_ERROR "ffdkit component '${component}' links '${needed}', which FFDKIT_PACKAGE_COMPONENT_ORDER "
                            "(cmake/FfdkitInstall.cmake) puts after it")
      endif()
    endforeach()
    string(REPLACE ";" ", " targets_text "${targets_of_${component}}")
    string(APPEND FFDKIT_PACKAGE_COMPONENT_TABLE
      "# ${component}: ${targets_text}\n"
      "set(_ffdkit_needs_${component} ${needs_of_${component}})\n")
    install(EXPORT ffdkit-${component}-targets NAMESPACE ffdkit:: DESTINATION ${FFDKIT_INSTALL_CMAKEDIR})
  endforeach()
  foreach(component IN LISTS components)
    if(NOT component IN_LIST FFDKIT_PACKAGE_COMPONENT_ORDER)
      message(FATAL_ERROR "ffdkit component '${component}' is missing from FFDKIT_PACKAGE_COMPONENT_ORDER (cmake/FfdkitInstall.cmake)")
    endif()
  endforeach()
  set(FFDKIT_PACKAGE_WITH_VTK ${FFDKIT_WITH_VTK})
  configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/ffdkitConfig.cmake.in"
    "${PROJECT_BINARY_DIR}/ffdkitConfig.cmake" INSTALL_DESTINATION ${FFDKIT_INSTALL_CMAKEDIR})
  write_basic_package_version_file("${PROJECT_BINARY_DIR}/ffdkitConfigVersion.cmake"
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
  install(FILES "${PROJECT_BINARY_DIR}/ffdkitConfig.cmake" "${PROJECT_BINARY_DIR}/ffdkitConfigVersion.cmake"
    DESTINATION ${FFDKIT_INSTALL_CMAKEDIR})
endfunction()
