# The add-on as `cmake --install` lays it out: install the build into a fresh prefix, then run
# test_installed.py in a Blender that reads add-ons from <prefix>/share/blender/scripts (its user
# scripts folder, BLENDER_USER_SCRIPTS; Debian's Blender reads /usr/share/blender/scripts as
# its system folder, for the .deb) and has no FFDKIT_PYTHONPATH:
# the add-on must find the module in <prefix>/lib/python3/dist-packages by itself.
#   cmake -DBUILD=... -DPREFIX=... -DBLENDER=... -DSCRIPT=... -P installed_addon.cmake
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD}" --prefix "${PREFIX}" OUTPUT_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD} --prefix ${PREFIX} failed (${rc})")
endif()
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env --unset=FFDKIT_PYTHONPATH "BLENDER_USER_SCRIPTS=${PREFIX}/share/blender/scripts"
          "FFDKIT_PREFIX=${PREFIX}" ${BLENDER} -b --factory-startup --python-exit-code 1 --python "${SCRIPT}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "Blender with the installed add-on failed (${rc})")
endif()
