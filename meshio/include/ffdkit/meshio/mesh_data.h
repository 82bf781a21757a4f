#pragma once

#include <stdexcept>
#include <string>

#include <Eigen/Core>

namespace ffdkit::meshio {

/// The points a lattice deforms, with the connectivity that is drawn and written back.
/// A point cloud has no triangles and no segments; a polyline has segments.
struct MeshData {
  Eigen::MatrixX3d points;     ///< #P x 3, world coordinates
  Eigen::MatrixX3i triangles;  ///< #T x 3 point indices (polygons are fan-triangulated on read)
  Eigen::MatrixX2i segments;   ///< #S x 2 point indices (poly-lines are split on read)
  bool hasNormals = false;     ///< the file had normals: writers recompute them from `points`
};

/// A mesh or point file that cannot be read or written; what() names the file, the element
/// (`face 12`, `vertex 7`) and, for text formats, the line: `bunny.obj:14: face 3: ...`.
class MeshIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Checks shapes, index ranges and finiteness; `what` names the mesh in the message.
/// @throws MeshIoError naming the first offending point or element.
void validateMesh(const MeshData& mesh, const std::string& what);

/// Area-weighted vertex normals of `triangles` over `points` (#P x 3, unit length; a point on
/// no triangle, or only on degenerate ones, gets (0, 0, 0)).
Eigen::MatrixX3d vertexNormals(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles);

}  // namespace ffdkit::meshio
