#pragma once

// Closed triangle meshes shared by the shape-constraint tests.

#include <cmath>

#include <Eigen/Core>

#include "ffdkit/ffd/closed_surface.h"

namespace ffdkit::ffd::testing {

struct TestMesh {
  Eigen::MatrixX3d points;
  TriangleMatrix triangles;
};

/// The box [lo, hi] as 8 corners and 12 outward, counter-clockwise triangles.
inline TestMesh boxMesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  TestMesh mesh;
  mesh.points.resize(8, 3);
  for (int c = 0; c < 8; ++c)
    mesh.points.row(c) << (c & 1 ? hi : lo)[0], (c & 2 ? hi : lo)[1], (c & 4 ? hi : lo)[2];
  mesh.triangles.resize(12, 3);
  mesh.triangles << 0, 2, 1, 1, 2, 3,  // z = lo
      4, 5, 6, 5, 7, 6,                // z = hi
      0, 1, 4, 1, 5, 4,                // y = lo
      2, 6, 3, 3, 6, 7,                // y = hi
      0, 4, 2, 2, 4, 6,                // x = lo
      1, 3, 5, 3, 7, 5;                // x = hi
  return mesh;
}

/// A UV sphere (rings x segments quads around two poles), outward triangles.
inline TestMesh sphereMesh(const Eigen::Vector3d& centre, double radius, int rings, int segments) {
  TestMesh mesh;
  const int n = 2 + (rings - 1) * segments;
  mesh.points.resize(n, 3);
  mesh.points.row(0) = (centre + Eigen::Vector3d(0, 0, radius)).transpose();
  mesh.points.row(n - 1) = (centre - Eigen::Vector3d(0, 0, radius)).transpose();
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double theta = M_PI * r / rings, phi = 2 * M_PI * s / segments;
      mesh.points.row(1 + (r - 1) * segments + s) =
          (centre + radius * Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                             std::cos(theta)))
              .transpose();
    }
  const auto at = [segments](int ring, int s) { return 1 + (ring - 1) * segments + (s % segments); };
  std::vector<Eigen::Vector3i> tris;
  for (int s = 0; s < segments; ++s) tris.emplace_back(0, at(1, s), at(1, s + 1));
  for (int r = 1; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      tris.emplace_back(at(r, s), at(r + 1, s), at(r + 1, s + 1));
      tris.emplace_back(at(r, s), at(r + 1, s + 1), at(r, s + 1));
    }
  for (int s = 0; s < segments; ++s) tris.emplace_back(n - 1, at(rings - 1, s + 1), at(rings - 1, s));
  mesh.triangles.resize(Eigen::Index(tris.size()), 3);
  for (std::size_t t = 0; t < tris.size(); ++t) mesh.triangles.row(Eigen::Index(t)) = tris[t].transpose();
  return mesh;
}

}  // namespace ffdkit::ffd::testing
