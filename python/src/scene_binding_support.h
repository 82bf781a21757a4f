// Helpers shared by the ffdkit.scenes and ffdkit.app binding files (animation_bindings.cpp,
// app_bindings.cpp).
#pragma once

#include <string>
#include <utility>

#include <pybind11/pybind11.h>

#include "ffdkit/scenes/scene.h"

namespace ffdkit::python {

namespace py = pybind11;

/// An object read from the mesh file `path` (relative to the working folder), as
/// Scene.addMeshFile and Document.addMeshFile add it; `up` is the file's up axis, "z" or "y" (a
/// Y-up file is turned upright). The file is read without the GIL.
/// @throws py::value_error for another `up`; the reader's MeshIoError for a bad file.
inline scenes::SceneObject meshFileObject(const std::string& name, const std::string& path, const std::string& up) {
  if (up != "z" && up != "y") throw py::value_error("up must be 'z' or 'y', got '" + up + "'");
  scenes::SceneObject object;
  object.name = name;
  object.source = scenes::MeshFileSource{path, up == "y" ? scenes::UpAxis::Y : scenes::UpAxis::Z};
  {
    py::gil_scoped_release release;
    object.mesh = scenes::buildObjectMesh(object.source, ".");
  }
  return object;
}

}  // namespace ffdkit::python
