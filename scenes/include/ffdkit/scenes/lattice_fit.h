#pragma once

#include <Eigen/Geometry>

namespace ffdkit::scenes {

/// The thinnest a fitted lattice gets along any axis, as a fraction of the fitted objects'
/// bounding-box diagonal (or in world units when that diagonal is 0, a single point): a flat
/// object (a plane, a planar curve) or a point still gets a lattice with volume, whose frame is
/// invertible and whose embedding is well posed.
inline constexpr double kMinimumLatticeThickness = 1e-3;

/// The box a lattice fitted to `bounds` spans (Kuriyama 1996, sec. 6.4, "attach"; the GUI's Attach, scenes::
/// attachNewLattice and ffdkit-cli deform --fit): `bounds` grown by padding x its diagonal on
/// every side, then each axis widened about its centre to at least kMinimumLatticeThickness x the
/// diagonal. @throws std::invalid_argument for an empty box or a negative / non-finite padding.
Eigen::AlignedBox3d fittedLatticeBox(const Eigen::AlignedBox3d& bounds, double padding);

/// The root lattice frame taking the unit box [0,1]^3 onto fittedLatticeBox(bounds, padding).
Eigen::Affine3d fittedLatticeFrame(const Eigen::AlignedBox3d& bounds, double padding);

}  // namespace ffdkit::scenes
