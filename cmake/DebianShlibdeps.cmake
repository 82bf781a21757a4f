# The Debian package's run-time library dependencies (CPACK_PRE_BUILD_SCRIPTS of the top-level
# CMakeLists.txt; runs in cpack after the files are installed into its staging folder, before the
# package is made): dpkg-shlibdeps over the package's ELF programs and shared objects, whose
# "Depends" it adds to CPACK_DEBIAN_PACKAGE_DEPENDS. This is what CPACK_DEBIAN_PACKAGE_SHLIBDEPS
# does, but that option first runs `file` once for every installed file to find the ELF ones
# (about 240 processes, 3.4 s of CPU per package); here the first bytes of each file tell.
set(stage "${CPACK_TEMPORARY_DIRECTORY}")
file(GLOB_RECURSE files LIST_DIRECTORIES false RELATIVE "${stage}" "${stage}/*")
set(binaries "")
foreach(file IN LISTS files)
  if(IS_SYMLINK "${stage}/${file}")
    continue()
  endif()
  # ELF magic, then e_type (offset 16, little-endian): 02 an executable, 03 a shared object.
  file(READ "${stage}/${file}" header LIMIT 17 HEX)
  if(header MATCHES "^7f454c46.*0[23]$")
    list(APPEND binaries "./${file}")
  endif()
endforeach()
if(NOT binaries)
  message(FATAL_ERROR "DebianShlibdeps: no ELF program or shared object in ${stage}")
endif()
# dpkg-shlibdeps wants a debian/control beside the files it reads (an empty one does).
file(MAKE_DIRECTORY "${stage}/debian")
file(TOUCH "${stage}/debian/control")
execute_process(COMMAND dpkg-shlibdeps --ignore-missing-info -O ${binaries}
                WORKING_DIRECTORY "${stage}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(REMOVE_RECURSE "${stage}/debian")
if(NOT rc EQUAL 0 OR NOT out MATCHES "shlibs:Depends=([^\n]+)")
  message(FATAL_ERROR "DebianShlibdeps: dpkg-shlibdeps ${binaries} failed (${rc}):\n${out}${err}")
endif()
set(CPACK_DEBIAN_PACKAGE_DEPENDS "${CPACK_DEBIAN_PACKAGE_DEPENDS}, ${CMAKE_MATCH_1}")
message(STATUS "DebianShlibdeps: ${binaries}: ${CMAKE_MATCH_1}")
