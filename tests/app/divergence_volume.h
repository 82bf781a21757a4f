#pragma once

// The tests' own volume of a closed triangulated surface, independent of the engine's
// (ffd::enclosedVolume, the shape guard's polynomial): the divergence theorem, sum over the
// triangles (a, b, c) of det[a, b, c] / 6, for outward-wound triangles.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ffdkit::test {

inline double divergenceVolume(const Eigen::MatrixX3d& p, const Eigen::MatrixX3i& t) {
  double v = 0.0;
  for (Eigen::Index i = 0; i < t.rows(); ++i) {
    const Eigen::Vector3d a = p.row(t(i, 0)), b = p.row(t(i, 1)), c = p.row(t(i, 2));
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

}  // namespace ffdkit::test
