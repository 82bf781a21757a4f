# cmake -DBUILD_DIR=... -DPREFIX=... -P install_tree.cmake: a fresh install, then the files a user
# needs must be there.
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${PREFIX}" RESULT_VARIABLE rc
                OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
foreach(file
    include/ffdkit/ffd/lattice.h include/ffdkit/widgets/widget_model.h include/ffdkit/scenes/scene.h
    include/ffdkit/geometry/gauss_legendre.h include/ffdkit/geometry/quaternion/qi_interpolation.h
    lib/libffdkit_ffd.a lib/libffdkit_widgets.a lib/libffdkit_scenes.a lib/libffdkit_geometry_core.a
    lib/libffdkit_interaction.a lib/libffdkit_parts.a include/ffdkit/app/interaction_controller.h
    lib/cmake/ffdkit/ffdkitConfig.cmake lib/cmake/ffdkit/ffdkitTargets.cmake
    bin/ffdkit bin/ffdkit-cli share/ffdkit/scenes/press/scene.json share/ffdkit/widgets/fig6-8.json)
  if(NOT EXISTS "${PREFIX}/${file}")
    message(FATAL_ERROR "not installed: ${PREFIX}/${file}")
  endif()
endforeach()
file(GLOB private_headers "${PREFIX}/include/ffdkit/scenes/json_text.h" "${PREFIX}/include/*/src/*")
if(private_headers)
  message(FATAL_ERROR "private headers installed: ${private_headers}")
endif()
