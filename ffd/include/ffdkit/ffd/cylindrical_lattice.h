#pragma once

#include <array>

#include <Eigen/Geometry>

#include "ffdkit/ffd/axis_basis.h"
#include "ffdkit/ffd/lattice.h"
#include "ffdkit/ffd/outside_policy.h"

namespace ffdkit::ffd {

/// Options for makeCylindricalLattice(): an EFFD cylindrical lattice (Coquillart 1990;
/// Kuriyama 1996, sec. 6.3.2, Fig. 6-11). Axes: u = radius, v = angle (periodic), w = height, in
/// the lattice-local frame whose z axis is the cylinder axis.
struct CylindricalLatticeOptions {
  Eigen::Vector3i counts{3, 8, 4};  ///< (radial >= 2, angular >= degree+1, height >= 2).
  std::array<AxisBasis, 3> bases{AxisBasis::bspline(3), AxisBasis::periodic(3),
                                 AxisBasis::bspline(3)};  ///< angular basis must be periodic; the
                                                          ///< radial/height cubic is capped at count-1.
  double innerRadius = 0.0;  ///< >= 0; 0 puts the first ring of points on the axis (degenerate ring).
  double outerRadius = 1.0;  ///< > innerRadius. The control ring radius: the B-spline ring itself
                             ///< lies slightly inside it between control points.
  double zMin = 0.0;         ///< local height range, zMax > zMin.
  double zMax = 1.0;  ///< upper end of the height range.
  Eigen::Affine3d frame = Eigen::Affine3d::Identity();  ///< world = frame * local.
  OutsidePolicy outsidePolicy{};  ///< what happens to points outside the cylinder.
};

/// A cylindrical lattice: rest point (i, j, k) = (r_i cos t_j, r_i sin t_j, z_k) with r_i, z_k
/// at the Greville abscissae of the radial and height axes (linear in u and w) and
/// t_j = 2 pi * (periodic Greville abscissa of j). The rest map is not affine: embedding uses
/// Newton with cylindrical coordinates as the initial guess.
/// @throws LatticeError on bad counts/bases, a non-periodic angular basis, a periodic radial or
///         height basis, innerRadius < 0, outerRadius <= innerRadius, zMax <= zMin.
Lattice makeCylindricalLattice(const CylindricalLatticeOptions& options = {});

}  // namespace ffdkit::ffd
