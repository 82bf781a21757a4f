# Project-wide compile settings, applied per target so that VTK and Qt headers
# (found as SYSTEM include directories) do not flood the build with warnings.

if(FFDKIT_SANITIZE OR FFDKIT_FUZZ)
  # halt_on_error: the first report fails the test (ASan halts by default; UBSan needs this).
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
  # FFDKIT_ASAN: tests that expect something else under ASan (it reports an absurd allocation
  # itself) check this macro. GCC defines __SANITIZE_ADDRESS__, clang 14 (the sanitizer stages'
  # compiler) does not: it answers __has_feature(address_sanitizer), as the sources ask it.
  add_compile_definitions(FFDKIT_ASAN)
endif()
if(FFDKIT_SANITIZE)
  # Optimization in the sanitizer stages: scripts/test.sh compiles them at -O0
  # (CMAKE_CXX_FLAGS_RELEASE), and the targets below at -O1. ASan and UBSan check the same at both
  # levels; -O0 compiles in about 40 % of the CPU time of -O1, but code that computes through
  # Eigen runs three to twenty times slower. At -O1: the libraries and test programs whose core
  # tests are that kind of code (ffd, geometry, cad: Newton embeddings, fold checks, fits, CAD
  # approximation; meshio's cell-quality sweeps and their reference in meshio_tests, the
  # exporters' skin fits and exporters_tests' skinned positions recomputed from the written
  # files (its tests 9 s of CPU instead of 18, its one compile 10 s instead of 5), scenes_tests'
  # brute-force nearest-point checks). At -O0: the rest (widgets, scenes, the CLI, the window's
  # libraries, the other test programs and the fuzz targets), whose tests run about as long
  # either way.
  # Measured per target (compile CPU from a cold build, test CPU per test): docs/robustness.md.
  set(ffdkit_sanitize_o1_targets
      ffdkit_ffd ffdkit_geometry_core ffdkit_geometry_quaternion ffdkit_geometry_g3
      ffdkit_geometry_cardinal ffdkit_geometry_polyhedron ffdkit_geometry_curvenet ffdkit_cad
      ffdkit_meshio ffdkit_exporters
      ffd_tests geometry_quaternion_tests geometry_polyhedron_tests geometry_curvenet_tests cad_tests
      scenes_tests meshio_tests exporters_tests)
  function(ffdkit_sanitize_o1_targets)
    foreach(target IN LISTS ffdkit_sanitize_o1_targets)
      if(TARGET ${target})
        target_compile_options(${target} PRIVATE -O1)
      endif()
    endforeach()
  endfunction()
  # Called once every target is defined: at the end of the top directory's CMakeLists.txt.
  cmake_language(DEFER DIRECTORY ${PROJECT_SOURCE_DIR} CALL ffdkit_sanitize_o1_targets)
endif()
if(FFDKIT_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "FFDKIT_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang")
  endif()
  # Coverage for libFuzzer in every library; the fuzz targets themselves link -fsanitize=fuzzer.
  add_compile_options(-fsanitize=fuzzer-no-link)
  # ...but not in third-party headers (nlohmann-json, the standard library, Eigen): the list
  # says why. It is copied under a name carrying its hash, so that a changed list changes every
  # compile line: ninja then rebuilds, and ccache (which does not hash the list's contents)
  # cannot return an object compiled with the old one.
  set(ffdkit_coverage_ignorelist ${PROJECT_SOURCE_DIR}/tests/fuzz/coverage_ignorelist.txt)
  file(SHA256 ${ffdkit_coverage_ignorelist} ffdkit_coverage_ignorelist_hash)
  string(SUBSTRING ${ffdkit_coverage_ignorelist_hash} 0 16 ffdkit_coverage_ignorelist_hash)
  set(ffdkit_coverage_ignorelist_copy ${PROJECT_BINARY_DIR}/coverage_ignorelist-${ffdkit_coverage_ignorelist_hash}.txt)
  configure_file(${ffdkit_coverage_ignorelist} ${ffdkit_coverage_ignorelist_copy} COPYONLY)
  add_compile_options(-fsanitize-coverage-ignorelist=${ffdkit_coverage_ignorelist_copy})
endif()

# The linker: LLVM's lld where the compiler can use it (scripts/setup-deps.sh installs it). The
# test programs link VTK and Qt; lld links each about ten times quicker than the default ld.bfd
# (monkey_gui_test: 0.16 s of CPU against 1.7 s), and a build links about 200 programs.
option(FFDKIT_USE_LLD "Link with lld when the compiler accepts -fuse-ld=lld" ON)
if(FFDKIT_USE_LLD)
  include(CheckLinkerFlag)
  check_linker_flag(CXX "-fuse-ld=lld" FFDKIT_LINKER_ACCEPTS_LLD)
  if(FFDKIT_LINKER_ACCEPTS_LLD)
    add_link_options(-fuse-ld=lld)
  endif()
endif()

find_program(FFDKIT_CCACHE ccache)
if(FFDKIT_CCACHE)
  set(CMAKE_C_COMPILER_LAUNCHER "${FFDKIT_CCACHE}")
  set(CMAKE_CXX_COMPILER_LAUNCHER "${FFDKIT_CCACHE}")
endif()

# Precompiled headers (FFDKIT_PCH, default ON): a target's common headers are compiled once into
# a precompiled header instead of being parsed again for each file (or unity batch).
# GCC builds: the window's library and test programs include the same Qt, Qt Test, VTK and Eigen
# headers, and parsing them was most of each file's compile time (a window test's batch: 3.8 s of
# its 5.4 s of CPU); programs with the same compile flags share one (REUSE_FROM).
# Clang sanitizer builds (scripts/test.sh's sanitizer stages): the core libraries and their test
# programs share a few precompiled headers of the standard library, Eigen and GoogleTest
# (cmake/pch/, mode SHARED). The fuzz build (FFDKIT_FUZZ) uses none.
option(FFDKIT_PCH "Precompile the common headers of the window's, the libraries' and the tests' files" ON)

# ffdkit_precompile_headers(target HEADER header.h) compiles header.h for target (GCC builds);
# ffdkit_precompile_headers(target REUSE_FROM other) uses other's (GCC builds; same compile flags
# needed: GCC ignores a precompiled header compiled with other options, -Winvalid-pch says so);
# ffdkit_precompile_headers(target SHARED header.h) (clang sanitizer builds) compiles header.h once
# per group of targets whose compile flags it needs to be the same: clang refuses a precompiled
# header compiled at another optimization level, with another -fPIC/-fPIE or without -fopenmp.
# The group's first target compiles it, the others reuse it. Call it once the target's libraries
# (OpenMP) and its files' own compile options are set.
function(ffdkit_precompile_headers target mode what)
  if(NOT FFDKIT_PCH OR FFDKIT_FUZZ)
    return()
  endif()
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND NOT mode STREQUAL "SHARED")
    if(mode STREQUAL "REUSE_FROM")
      target_precompile_headers(${target} REUSE_FROM ${what})
    else()
      target_precompile_headers(${target} PRIVATE ${what})
    endif()
    # ccache caches a compile that uses a precompiled header only with -fpch-preprocess and with the
    # settings cmake/ccache-pch.sh gives it (set here, for these targets, so that a fresh machine
    # without a ccache configuration of its own gets cache hits).
    target_compile_options(${target} PRIVATE -fpch-preprocess)
  elseif(CMAKE_CXX_COMPILER_ID STREQUAL "Clang" AND FFDKIT_SANITIZE AND mode STREQUAL "SHARED")
    get_target_property(pic ${target} POSITION_INDEPENDENT_CODE)
    get_target_property(libraries ${target} LINK_LIBRARIES)
    set(group "${what}|pic=${pic}")
    if(target IN_LIST ffdkit_sanitize_o1_targets)
      string(APPEND group "|O1")
    endif()
    if("OpenMP::OpenMP_CXX" IN_LIST libraries)
      string(APPEND group "|openmp")
    endif()
    string(MAKE_C_IDENTIFIER "${group}" group)
    get_property(donor GLOBAL PROPERTY ffdkit_pch_${group})
    if(donor)
      target_precompile_headers(${target} REUSE_FROM ${donor})
    else()
      target_precompile_headers(${target} PRIVATE ${what})
      set_property(GLOBAL PROPERTY ffdkit_pch_${group} ${target})
    endif()
    # A file with compile options of its own (meshio's cell_quality.cpp: -fno-math-errno) compiles
    # without it: clang would refuse it.
    get_target_property(sources ${target} SOURCES)
    foreach(source IN LISTS sources)
      get_source_file_property(options ${source} COMPILE_OPTIONS)
      if(options)
        set_source_files_properties(${source} PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
      endif()
    endforeach()
    # ccache caches a precompiled header clang compiled without its timestamp only (and the
    # compiles that use it with the settings cmake/ccache-pch.sh gives it).
    target_compile_options(${target} PRIVATE "SHELL:-Xclang -fno-pch-timestamp")
  else()
    return()
  endif()
  if(FFDKIT_CCACHE)
    set_target_properties(${target} PROPERTIES CXX_COMPILER_LAUNCHER
      "${PROJECT_SOURCE_DIR}/cmake/ccache-pch.sh;${FFDKIT_CCACHE}")
  endif()
endfunction()

include(FfdkitInstall)

# ffdkit_target_defaults(target): warnings on for project code.
function(ffdkit_target_defaults target)
  # -Wshadow=local is GCC's spelling; clang (fuzz builds) has no such option.
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic $<$<CXX_COMPILER_ID:GNU>:-Wshadow=local>
                         -Wno-unused-parameter)
endfunction()

# Libraries and the Python module are unity builds (FFDKIT_UNITY_LIBS, default ON): up to
# FFDKIT_UNITY_BATCH of a target's source files compiled as one translation unit, so that the
# headers they share (Eigen, the standard library, VTK, Qt) are parsed, and the templates they
# share (Eigen's decompositions and products) instantiated and optimized, once per batch instead
# of once per file. A name a file defines for itself (anonymous namespace, static) must therefore
# differ from the names of the other files of its target. OFF compiles each file alone (one entry
# per file in compile_commands.json, for tools that read it; quicker after an edit of one file).
option(FFDKIT_UNITY_LIBS "Compile each library's files in unity batches" ON)
set(FFDKIT_UNITY_BATCH 8 CACHE STRING "Source files per unity batch of a library")
function(ffdkit_unity_library target)
  if(FFDKIT_UNITY_LIBS)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${FFDKIT_UNITY_BATCH})
  endif()
endfunction()

# ffdkit_add_module_library(module SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...]
#   [HEADER_ONLY_DEPS ...]): one library target per module, ffdkit_<module> with the alias
# ffdkit::<module>, public headers under <module>/include/ffdkit/<module>/; installed with its
# headers and exported in the ffdkit CMake package (cmake/FfdkitInstall.cmake). HEADER_ONLY_DEPS
# are used privately and only while building (nlohmann-json, fast_float): the installed package
# does not look for them.
function(ffdkit_add_module_library module)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS;HEADER_ONLY_DEPS" ${ARGN})
  add_library(ffdkit_${module} ${ARG_SOURCES})
  add_library(ffdkit::${module} ALIAS ffdkit_${module})
  target_include_directories(ffdkit_${module} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>)
  target_link_libraries(ffdkit_${module} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  foreach(dep IN LISTS ARG_HEADER_ONLY_DEPS)
    target_link_libraries(ffdkit_${module} PRIVATE $<BUILD_INTERFACE:${dep}>)
  endforeach()
  # Position-independent: the static libraries also go into the Python module (a shared object)
  # and into shared libraries of projects that use the installed package.
  set_target_properties(ffdkit_${module} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  ffdkit_target_defaults(ffdkit_${module})
  ffdkit_unity_library(ffdkit_${module})
  ffdkit_install_library(ffdkit_${module} ${module} HEADERS "${CMAKE_CURRENT_SOURCE_DIR}/include")
endfunction()

# ffdkit_relocatable_vtk_autoinit(): vtk_module_autoinit() hands its generated header to the
# compiler as a define holding the header's full path in the build folder
# (-DvtkRenderingCore_AUTOINIT_INCLUDE="<build>/CMakeFiles/vtkModuleAutoInit_<hash>.h"). ccache
# makes paths in include options relative to the build folder (CCACHE_BASEDIR, scripts/build.sh),
# but not paths inside a define: in another build folder (the no-app stage after the main build,
# the sanitizer app stage after the sanitizer stage) every source of those targets missed ccache's
# direct mode and was preprocessed again (about 1 s each) before its preprocessor-mode hit. Here
# the define names the header alone and its folder is an include directory of the target, so
# those compiles are direct hits. Call once, after every target is defined.
function(ffdkit_relocatable_vtk_autoinit)
  set(autoinit_dir "${CMAKE_BINARY_DIR}/CMakeFiles")
  set(dirs "${PROJECT_SOURCE_DIR}")
  while(dirs)
    list(POP_FRONT dirs dir)
    get_property(subdirs DIRECTORY "${dir}" PROPERTY SUBDIRECTORIES)
    list(APPEND dirs ${subdirs})
    get_property(targets DIRECTORY "${dir}" PROPERTY BUILDSYSTEM_TARGETS)
    foreach(target IN LISTS targets)
      get_target_property(definitions ${target} COMPILE_DEFINITIONS)
      if(NOT definitions)
        continue()
      endif()
      string(REPLACE "_AUTOINIT_INCLUDE=\"${autoinit_dir}/" "_AUTOINIT_INCLUDE=\"" relocated "${definitions}")
      if(NOT relocated STREQUAL definitions)
        set_property(TARGET ${target} PROPERTY COMPILE_DEFINITIONS "${relocated}")
        target_include_directories(${target} PRIVATE "${autoinit_dir}")
      endif()
    endforeach()
  endwhile()
endfunction()
