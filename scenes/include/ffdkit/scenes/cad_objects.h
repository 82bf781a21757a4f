#pragma once
// Objects read from CAD files (STEP, IGES): a scene names the file like a mesh file
// ("mesh": {"path": "part.step"}), and its triangles come from a reader the program registers.
// The scenes module does not link OpenCASCADE: a program built with the cad module (the app with
// FFDKIT_WITH_CAD) registers a reader that tessellates the B-rep; without one, such an object is
// a read error saying so (docs/cad.md).

#include <filesystem>
#include <functional>

#include "ffdkit/meshio/read_limits.h"
#include "ffdkit/scenes/mesh_io.h"

namespace ffdkit::scenes {

/// Reads a CAD file as an object's triangles; charges what it builds to `budget`.
/// Throws (a MeshIoError or the reader's own error) naming the file on a bad file.
using CadMeshReader = std::function<MeshData(const std::filesystem::path& path, meshio::ReadBudget& budget)>;

/// Whether `path` names a CAD file by its extension (case-insensitive): .step .stp .iges .igs.
bool isCadFile(const std::filesystem::path& path);

/// Sets the reader of CAD files for every later read in this process (an empty function removes
/// it). Programs call it once at start, before they read scenes.
void setCadMeshReader(CadMeshReader reader);

/// Whether a CAD reader is registered.
bool hasCadMeshReader();

/// Reads a CAD file with the registered reader.
/// @throws MeshIoError naming the file when no reader is registered (a build without the cad
///         module, or a program that registers none), and whatever the reader throws on a bad file.
MeshData readCadMesh(const std::filesystem::path& path, meshio::ReadBudget& budget);

}  // namespace ffdkit::scenes
