#pragma once

#include <array>

#include <Eigen/Geometry>

#include "ffdkit/ffd/axis_basis.h"
#include "ffdkit/ffd/outside_policy.h"

namespace ffdkit::ffd {

/// Options for makeBoxLattice(): an oriented box lattice (the default FFD lattice,
/// Kuriyama 1996, sec. 6.3.2).
struct BoxLatticeOptions {
  Eigen::Vector3i counts{4, 4, 4};                  ///< (l, m, n), each >= 2.
  std::array<AxisBasis, 3> bases{AxisBasis::bspline(3), AxisBasis::bspline(3),
                                 AxisBasis::bspline(3)};  ///< per axis; degree is capped at count-1.
  Eigen::Vector3d boxMin{0.0, 0.0, 0.0};            ///< local box corner (lattice-local units).
  Eigen::Vector3d boxMax{1.0, 1.0, 1.0};            ///< opposite corner, boxMax > boxMin per axis.
  Eigen::Affine3d frame = Eigen::Affine3d::Identity();  ///< world = frame * local.
  OutsidePolicy outsidePolicy{};                    ///< Identity by default.
  /// true: a (non-periodic) B-spline degree above count-1 is lowered to count-1, so the default
  /// cubic bases also serve 2- and 3-point axes; false: such a degree throws LatticeError.
  bool capDegreeToCount = true;
};

}  // namespace ffdkit::ffd
