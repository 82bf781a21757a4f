#include "ffdkit/scenes/lattice_fit.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace ffdkit::scenes {

namespace {

// The fitted box as its lower corner and size (the frame is made from these, not from a box's
// max - min, so that it is exact).
std::pair<Eigen::Vector3d, Eigen::Vector3d> fitted(const Eigen::AlignedBox3d& bounds, double padding) {
  if (bounds.isEmpty()) throw std::invalid_argument("lattice fit: no points to fit");
  if (!(padding >= 0.0) || !std::isfinite(padding))
    throw std::invalid_argument("lattice fit: padding must be finite and >= 0, got " + std::to_string(padding));
  const double diagonal = bounds.diagonal().norm();
  const double margin = padding * diagonal;
  const double minimum = kMinimumLatticeThickness * (diagonal > 0.0 ? diagonal : 1.0);
  Eigen::Vector3d lower = bounds.min().array() - margin;
  Eigen::Vector3d size = (bounds.sizes().array() + 2.0 * margin).matrix();
  for (int a = 0; a < 3; ++a) {
    if (size[a] < minimum) {  // widened about its centre
      lower[a] -= 0.5 * (minimum - size[a]);
      size[a] = minimum;
    }
  }
  return {lower, size};
}

}  // namespace

Eigen::AlignedBox3d fittedLatticeBox(const Eigen::AlignedBox3d& bounds, double padding) {
  const auto [lower, size] = fitted(bounds, padding);
  return Eigen::AlignedBox3d(lower, lower + size);
}

Eigen::Affine3d fittedLatticeFrame(const Eigen::AlignedBox3d& bounds, double padding) {
  const auto [lower, size] = fitted(bounds, padding);
  return Eigen::Translation3d(lower) * Eigen::Scaling(size);
}

}  // namespace ffdkit::scenes
