#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/geometry/polyhedron/polygon_mesh.h"

namespace ffdkit::geometry::polyhedron::testing {

/// Applies x -> scale * R x + shift to every vertex.
inline PolygonMesh transformed(PolygonMesh mesh, const Eigen::Matrix3d& rotation, double scale,
                               const Eigen::Vector3d& shift) {
  for (int v = 0; v < mesh.vertices.rows(); ++v) {
    mesh.vertices.row(v) = (scale * rotation * mesh.vertices.row(v).transpose() + shift).transpose();
  }
  return mesh;
}

inline Eigen::Matrix3d someRotation() {
  return Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
}

/// Projection of x onto the plane perpendicular to n.
inline Eigen::Vector3d projectOntoPlane(const Eigen::Vector3d& x, const Eigen::Vector3d& n) {
  const Eigen::Vector3d u = n.normalized();
  return x - x.dot(u) * u;
}

}  // namespace ffdkit::geometry::polyhedron::testing
