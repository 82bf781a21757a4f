#pragma once

#include <filesystem>
#include <optional>
#include <string_view>

namespace ffdkit::meshio {

/// The mesh and point file formats ffdkit reads (all) and writes (all but glTF).
enum class MeshFormat {
  Obj,   ///< Wavefront OBJ (v, f, l, p; polygons fan-triangulated)
  Ply,   ///< Stanford PLY: ASCII, binary little or big endian
  Stl,   ///< STL, ASCII or binary (identical corners merged into one point)
  Xyz,   ///< text, one "x y z" point per line; '#' starts a comment
  Npy,   ///< numpy array of shape (N, 3), float32 or float64, either byte order
  Gltf,  ///< glTF 2.0 JSON (external buffers only beside the file)
  Glb,   ///< glTF 2.0 binary
  Vtp,   ///< VTK XML poly data (read and written through VTK, its output checked)
  Vtk,   ///< VTK legacy poly data (same)
};

/// The format of `path` by its extension (case-insensitive), or nullopt when unknown.
std::optional<MeshFormat> meshFormatOf(const std::filesystem::path& path);

/// The lower-case extension with its dot: ".obj", ".ply", ...
std::string_view meshFormatExtension(MeshFormat format);

/// Whether writeMesh can write `format` (every format but glTF).
bool isWritable(MeshFormat format);

}  // namespace ffdkit::meshio
