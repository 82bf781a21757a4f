#include "ffdkit/geometry/polyhedron/ring_targets.h"

#include <stdexcept>

namespace ffdkit::geometry::polyhedron {

Eigen::MatrixX3d ringTargets(const Eigen::MatrixX3d& r) {
  const int n = static_cast<int>(r.rows());
  if (n < 1) throw std::invalid_argument("ringTargets: expected at least one ring edge, got 0");
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(n, 3);
  auto at = [n](int i) { return ((i % n) + n) % n; };
  if (n % 2 == 1) {
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < n; ++k) g.row(i) += ((k % 2) ? -0.5 : 0.5) * r.row(at(i - k));
    }
    return g;
  }
  Eigen::RowVector3d dif = Eigen::RowVector3d::Zero();  // sum_i (-1)^i R_i, 1-based i
  for (int i = 0; i < n; ++i) dif += ((i % 2) ? 1.0 : -1.0) * r.row(i);
  Eigen::MatrixX3d projected = r;
  for (int i = 0; i < n; ++i) projected.row(i) += ((i % 2) ? -1.0 : 1.0) / n * dif;
  for (int i = 0; i < n; ++i) {
    for (int k = 1; k < n; ++k) g.row(i) -= ((k % 2) ? -1.0 : 1.0) * k / n * projected.row(at(i - k));
  }
  return g;
}

}  // namespace ffdkit::geometry::polyhedron
