#pragma once
// Scenes hold meshes read and written by meshio (ffdkit/meshio/mesh_io.h); these names let scene
// code and its users say scenes::MeshData and scenes::readMesh for the same things.

#include "ffdkit/meshio/mesh_io.h"

namespace ffdkit::scenes {

using meshio::MeshData;
using meshio::MeshIoError;
using meshio::readMesh;
using meshio::validateMesh;
using meshio::writeMesh;

}  // namespace ffdkit::scenes
