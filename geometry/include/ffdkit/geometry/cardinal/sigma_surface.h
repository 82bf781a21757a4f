#pragma once

#include <array>

#include <Eigen/Core>

#include "ffdkit/geometry/cardinal/point_grid.h"
#include "ffdkit/geometry/cardinal/sigma_knots.h"

namespace ffdkit::geometry::cardinal {

/// 5 x 5 quartic Bezier patch b[k][l], k along u, l along v.
using QuarticPatch = std::array<std::array<Eigen::Vector3d, 5>, 5>;

/// Tensor-product sigma-spline surface (eq. 3.25):
/// Q = sum P_ij s_i s_j + sum Pu_ij sh_i s_j + sum Pv_ij s_i sh_j + sum Puv_ij sh_i sh_j,
/// with s = sigma (cardinal) and sh = sigmahat (auxiliary) bases along u (knotsU) and v (knotsV).
/// Grid sizes: P  knotsU.pointCount() x knotsV.pointCount(),
///             Pu knotsU.shapeCount() x knotsV.pointCount(),
///             Pv knotsU.pointCount() x knotsV.shapeCount(),
///             Puv knotsU.shapeCount() x knotsV.shapeCount();
/// shape rows/columns are offset by shapeFirst() (grid index r <-> shape index r + shapeFirst()).
/// Q(t^u_i, t^v_j) = P_ij for any shape grids. @see Kuriyama 1996, sec. 3.3.3.
struct SigmaSurface {
  SigmaKnots knotsU;  ///< knots and tensions along u
  SigmaKnots knotsV;  ///< knots and tensions along v
  ///@{
  /// The interpolation grid P and the shape grids Pu, Pv, Puv (sizes above).
  PointGrid P, Pu, Pv, Puv;
  ///@}

  /// @throws CardinalSplineError if the grid sizes do not match the knots.
  void validate() const;

  /// Patch over u-interval i and v-interval j (computed in two curve steps, Kuriyama 1996,
  /// sec. 3.3.3).
  QuarticPatch patch(int i, int j) const;

  /// d^du/du d^dv/dv Q(u, v) in global parameters (du, dv in 0..4). Closed directions
  /// wrap, open directions clamp to the knot range.
  Eigen::Vector3d evaluate(double u, double v, int du = 0, int dv = 0) const;
};

/// d^du/ds^du d^dv/dt^dv of a quartic patch at local (s, t) in [0, 1]^2.
Eigen::Vector3d evaluateQuarticPatch(const QuarticPatch& b, double s, double t, int du = 0,
                                     int dv = 0);

}  // namespace ffdkit::geometry::cardinal
