#pragma once

#include <filesystem>
#include <iosfwd>
#include <stdexcept>
#include <string>

#include <Eigen/Core>

namespace ffdkit::scenes {

/// The points a lattice deforms, with the connectivity that is drawn and written back.
/// A point cloud has no triangles and no segments; a polyline has segments.
struct MeshData {
  Eigen::MatrixX3d points;     ///< #P x 3, world coordinates
  Eigen::MatrixX3i triangles;  ///< #T x 3 point indices (polygons are triangulated on read)
  Eigen::MatrixX2i segments;   ///< #S x 2 point indices (poly-lines are split on read)
  bool hasNormals = false;     ///< the file had normals: writers recompute them from `points`
};

/// A mesh or point file that cannot be read or written; what() names the file and the reason.
class MeshIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads a mesh by its extension: .obj, .ply, .stl, .vtp (VTK XML), .vtk (legacy poly data),
/// .gltf / .glb (glTF 2.0, all meshes of the default scene merged, node transforms applied),
/// .xyz (text, one "x y z" point per line; '#' starts a comment).
/// @throws MeshIoError for a missing file, an unknown extension, a file VTK cannot parse, a
///         file with no points, or non-finite coordinates (with the point index).
MeshData readMesh(const std::filesystem::path& path);

/// Writes a mesh by its extension: .obj, .ply (binary), .stl (binary; triangles only),
/// .vtp, .xyz. Normals are recomputed from the points when `mesh.hasNormals`.
/// Written atomically: a failure leaves no partial file and an existing file untouched.
/// @throws MeshIoError for an unknown extension, an empty mesh, indices out of range or
///         non-finite points, or a failed write.
void writeMesh(const std::filesystem::path& path, const MeshData& mesh);

/// Point files as text: one "x y z" per line. Stream overloads of the .xyz reader and writer.
MeshData readXyz(std::istream& in, const std::string& sourceName = "<stream>");
void writeXyz(std::ostream& out, const Eigen::MatrixX3d& points);

/// Checks shapes, index ranges and finiteness; `what` names the mesh in the message.
/// @throws MeshIoError naming the first offending point or element.
void validateMesh(const MeshData& mesh, const std::string& what);

}  // namespace ffdkit::scenes
