#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <string_view>

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/meshio/mesh_format.h"
#include "ffdkit/meshio/path_confinement.h"
#include "ffdkit/meshio/read_limits.h"

namespace ffdkit::meshio {

/// The byte layout of a written PLY file.
enum class PlyEncoding { BinaryLittleEndian, BinaryBigEndian, Ascii };

/// Options of writeMesh.
struct MeshWriteOptions {
  PlyEncoding plyEncoding = PlyEncoding::BinaryLittleEndian;  ///< PLY only: binary little-endian (default), big-endian or ASCII
  /// Path writes only: flush the file to disk (fsync) before the rename, so that a power loss
  /// cannot leave a renamed but empty file. A killed process never leaves a partial file either way.
  bool durable = true;
};

/// How a mesh file is read: its resource budget and the rule for the files it names.
struct MeshReadOptions {
  ReadLimits limits{};            ///< the read's limits when `budget` is null
  ReadBudget* budget = nullptr;   ///< a budget shared with an enclosing read (a scene's), or null
  PathConfinement confinement{};  ///< external files a mesh file names (glTF buffers)
};

/// Reads a mesh or point file; the format comes from the extension (see MeshFormat).
/// Every reader validates while it parses: counts are checked against the bytes left before
/// anything is allocated, indices are in range, numbers finite, and truncated or over-long
/// files are errors. A result always passes validateMesh.
/// @throws MeshIoError naming the file, the element and (text formats) the line.
/// Everything the file makes the reader allocate is charged to the options' budget first
/// (ReadLimits: 4 GiB, 50M points by default); over it, a MeshIoError names the file and what.
MeshData readMesh(const std::filesystem::path& path);
MeshData readMesh(const std::filesystem::path& path, const MeshReadOptions& options);

/// Reads a mesh of `format` from a stream (glTF: no external buffers). `sourceName` names the
/// stream in messages.
MeshData readMesh(std::istream& in, MeshFormat format, const std::string& sourceName = "<stream>");
MeshData readMesh(std::istream& in, MeshFormat format, const std::string& sourceName, const MeshReadOptions& options);

/// Reads a mesh of `format` from bytes in memory (what the stream and path overloads call).
MeshData readMeshBytes(std::string_view bytes, MeshFormat format, const std::string& sourceName = "<memory>");
MeshData readMeshBytes(std::string_view bytes, MeshFormat format, const std::string& sourceName,
                       const MeshReadOptions& options);

/// Writes a mesh; the format comes from the extension: .obj, .ply, .stl (binary, triangles
/// only), .xyz and .npy (points only), .vtp, .vtk. Normals are recomputed from the points when
/// `mesh.hasNormals`. Atomic: the bytes go to a hidden temporary file beside `path` that is
/// renamed over it, so `path` is either the old file or the complete new one; temporaries
/// left by killed writers are removed by the next write into the folder.
/// @throws MeshIoError for an unknown extension, a mesh that fails validateMesh, or a failed write.
void writeMesh(const std::filesystem::path& path, const MeshData& mesh, const MeshWriteOptions& options = {});

/// writeMesh without the final rename: the complete file waits in its temporary beside `path`
/// until commit() (a batch renames all its files only once every one is written). Text formats
/// stream: slices go to the file while later ones are formatted. @throws MeshIoError as writeMesh.
StagedFile stageMesh(const std::filesystem::path& path, const MeshData& mesh, const MeshWriteOptions& options = {});

/// Writes a mesh of `format` to a stream.
void writeMesh(std::ostream& out, const MeshData& mesh, MeshFormat format, const MeshWriteOptions& options = {});

/// The bytes of `mesh` in `format` (what the stream and path overloads write).
std::string meshFileBytes(const MeshData& mesh, MeshFormat format, const MeshWriteOptions& options = {});

}  // namespace ffdkit::meshio
