#pragma once

// Curves shared by the render tests.

#include <cmath>
#include <numbers>

#include <Eigen/Core>

namespace ffdkit::app::testing {

/// n points of a circle of `radius` about `centre` in a plane z = centre.z, counter-clockwise.
inline Eigen::MatrixX3d circle(double radius, int n, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  Eigen::MatrixX3d points(n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * std::numbers::pi * i / n;
    points.row(i) = (centre + radius * Eigen::Vector3d(std::cos(t), std::sin(t), 0.0)).transpose();
  }
  return points;
}

}  // namespace ffdkit::app::testing
