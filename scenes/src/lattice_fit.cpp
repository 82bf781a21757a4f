#include "ffdkit/scenes/lattice_fit.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ffdkit::scenes {

Eigen::AlignedBox3d fittedLatticeBox(const Eigen::AlignedBox3d& bounds, double padding) {
  if (bounds.isEmpty()) throw std::invalid_argument("lattice fit: no points to fit");
  if (!(padding >= 0.0) || !std::isfinite(padding))
    throw std::invalid_argument("lattice fit: padding must be finite and >= 0, got " + std::to_string(padding));
  const double diagonal = bounds.diagonal().norm();
  const double minimum = kMinimumLatticeThickness * (diagonal > 0.0 ? diagonal : 1.0);
  const Eigen::Vector3d size =
      (bounds.sizes().array() + 2.0 * padding * diagonal).max(minimum).matrix();
  const Eigen::Vector3d centre = bounds.center();
  return Eigen::AlignedBox3d(centre - 0.5 * size, centre + 0.5 * size);
}

Eigen::Affine3d fittedLatticeFrame(const Eigen::AlignedBox3d& bounds, double padding) {
  const Eigen::AlignedBox3d box = fittedLatticeBox(bounds, padding);
  return Eigen::Translation3d(box.min()) * Eigen::Scaling(box.sizes());
}

}  // namespace ffdkit::scenes
