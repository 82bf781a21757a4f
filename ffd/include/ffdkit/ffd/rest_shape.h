#pragma once

namespace ffdkit::ffd {

/// Analytic description of a cylindrical rest lattice (EFFD, Coquillart 1990; Kuriyama 1996,
/// Fig. 6-11), in lattice-local coordinates: the lattice axis is local z, radius in [innerRadius,
/// outerRadius] maps linearly to the radial parameter u, the angle atan2(y, x) / 2pi to the
/// periodic parameter v, z in [zMin, zMax] to w. Only used as the initial guess of Newton
/// embedding.
struct CylinderRestShape {
  double innerRadius = 0.0;  ///< radius of the innermost ring of control points (>= 0).
  double outerRadius = 1.0;  ///< radius of the outermost ring.
  double zMin = 0.0;  ///< lower end of the height range (local z).
  double zMax = 1.0;  ///< upper end of the height range.
};

}  // namespace ffdkit::ffd
