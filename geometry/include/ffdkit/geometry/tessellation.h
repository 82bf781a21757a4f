#pragma once

#include <Eigen/Core>

namespace ffdkit::geometry {

/// What a curve generator hands to scenes as a deformable object.
struct Polyline {
  Eigen::MatrixX3d points;  ///< #points x 3, one sample per row, in order along the curve
  bool closed = false;      ///< true: the last point connects back to the first
};

/// What a surface generator hands to scenes as a deformable object: a crack-free triangle
/// mesh whose shared boundary vertices are welded.
struct TriangleMesh {
  Eigen::MatrixX3d vertices;   ///< #V x 3
  Eigen::MatrixX3i triangles;  ///< #F x 3, counter-clockwise seen from outside
};

}  // namespace ffdkit::geometry
