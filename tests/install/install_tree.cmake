# cmake -DBUILD_DIR -DPREFIX -DWITH_APP -DWITH_VTK -DPYTHON_DIR -P install_tree.cmake: a fresh
# install, then the files a user needs must be there, private headers must not, and in a build
# without the window (WITH_APP off) neither the CLI nor the Python module may link Qt (nor VTK,
# WITH_VTK off).
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${PREFIX}" RESULT_VARIABLE rc
                OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
set(expected
    include/ffdkit/ffd/lattice.h include/ffdkit/widgets/widget_model.h include/ffdkit/scenes/scene.h
    include/ffdkit/geometry/gauss_legendre.h include/ffdkit/geometry/quaternion/qi_interpolation.h
    include/ffdkit/meshio/mesh_io.h include/ffdkit/exporters/gltf_export.h include/ffdkit/interaction/interaction_controller.h
    lib/libffdkit_ffd.a lib/libffdkit_widgets.a lib/libffdkit_scenes.a lib/libffdkit_geometry_core.a
    lib/libffdkit_meshio.a lib/libffdkit_exporters.a lib/libffdkit_interaction.a lib/libffdkit_parts.a
    lib/cmake/ffdkit/ffdkitConfig.cmake lib/cmake/ffdkit/ffdkitConfigVersion.cmake
    bin/ffdkit-cli share/ffdkit/scenes/press/scene.json share/ffdkit/widgets/fig6-8.json
    share/blender/scripts/addons/ffdkit_blender/__init__.py)
foreach(component ffd geometry widgets meshio scenes exporters app)
  list(APPEND expected lib/cmake/ffdkit/ffdkit-${component}-targets.cmake)
endforeach()
if(WITH_APP)
  list(APPEND expected bin/ffdkit)
endif()
if(WITH_VTK)
  list(APPEND expected lib/ffdkit/ffdkit-cli-vtk.so)  # ffdkit-cli's VTK module (docs/cli.md)
endif()
foreach(file IN LISTS expected)
  if(NOT EXISTS "${PREFIX}/${file}")
    message(FATAL_ERROR "not installed: ${PREFIX}/${file}")
  endif()
endforeach()
file(GLOB private_headers "${PREFIX}/include/ffdkit/scenes/json_text.h" "${PREFIX}/include/*/src/*")
if(private_headers)
  message(FATAL_ERROR "private headers installed: ${private_headers}")
endif()
if(NOT WITH_APP)
  if(EXISTS "${PREFIX}/bin/ffdkit")
    message(FATAL_ERROR "a build without the window installed ${PREFIX}/bin/ffdkit")
  endif()
  file(GLOB python_module "${PREFIX}/${PYTHON_DIR}/ffdkit/_ffdkit*.so")
  foreach(binary "${PREFIX}/bin/ffdkit-cli" ${python_module})
    execute_process(COMMAND ldd "${binary}" OUTPUT_VARIABLE libraries RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "ldd ${binary} failed (${rc})")
    endif()
    if(libraries MATCHES "libQt")
      message(FATAL_ERROR "${binary} of a build without the window links Qt:\n${libraries}")
    endif()
    if(NOT WITH_VTK AND libraries MATCHES "libvtk")
      message(FATAL_ERROR "${binary} of a build without VTK links VTK:\n${libraries}")
    endif()
  endforeach()
endif()
# The installed ffdkit-cli finds its VTK module in lib/ffdkit: it writes a .vtp through it.
if(WITH_VTK)
  execute_process(COMMAND "${PREFIX}/bin/ffdkit-cli" deform --scene "${PREFIX}/share/ffdkit/scenes/press"
                          -o "${PREFIX}/press.vtp"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0 OR NOT EXISTS "${PREFIX}/press.vtp")
    message(FATAL_ERROR "the installed ffdkit-cli could not write a .vtp (${rc}):\n${out}")
  endif()
endif()
