#pragma once

#include <filesystem>

#include "ffdkit/scenes/mesh_io.h"

namespace ffdkit::cli {

/// scenes::readMesh, stricter for .xyz point files: a line that is neither blank, a comment,
/// nor three finite numbers is an error (with its line number) rather than skipped.
/// @throws scenes::MeshIoError.
scenes::MeshData readInputMesh(const std::filesystem::path& path);

}  // namespace ffdkit::cli
