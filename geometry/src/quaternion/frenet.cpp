#include "ffdkit/geometry/quaternion/frenet.h"

#include <algorithm>

#include <Eigen/Geometry>

namespace ffdkit::geometry::quaternion {

double torsionFromTangentDerivatives(const Eigen::Vector3d& T, const Eigen::Vector3d& Tt, const Eigen::Vector3d& Ttt,
                                     double L) {
  const double n2 = Tt.squaredNorm();
  if (n2 < 1e-16) {
    return 0.0;
  }
  return T.dot(Tt.cross(Ttt)) / (L * n2);
}

Eigen::Vector3d fivePointDerivative(const std::function<Eigen::Vector3d(double)>& f, double t, double h) {
  if (t >= 2 * h && t <= 1.0 - 2 * h) {
    return (f(t - 2 * h) - 8.0 * f(t - h) + 8.0 * f(t + h) - f(t + 2 * h)) / (12.0 * h);
  }
  // One-sided fourth-order stencils near the ends.
  const double sign = t < 2 * h ? 1.0 : -1.0;
  const double s = sign * h;
  return (-25.0 * f(t) + 48.0 * f(t + s) - 36.0 * f(t + 2 * s) + 16.0 * f(t + 3 * s) - 3.0 * f(t + 4 * s)) /
         (12.0 * s);
}

}  // namespace ffdkit::geometry::quaternion
