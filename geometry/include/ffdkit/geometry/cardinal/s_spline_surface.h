#pragma once

#include <Eigen/Core>

#include "ffdkit/geometry/cardinal/point_grid.h"
#include "ffdkit/geometry/cardinal/s_spline_basis.h"

namespace ffdkit::geometry::cardinal {

/// Options of an S-spline surface.
struct SSplineSurfaceOptions {
  double beta2U = 0.0;   ///< tension along u (rows)
  double beta2V = 0.0;   ///< tension along v (columns)
  int halfWidthU = 4;    ///< truncation half-width along u
  int halfWidthV = 4;    ///< truncation half-width along v
  int degreeU = 3;       ///< odd B-spline degree along u (5..9 need beta2U = 0)
  int degreeV = 3;       ///< odd B-spline degree along v
  bool closedU = false;  ///< u periodic: the grid rows are distinct, row s := row 0
  bool closedV = false;  ///< v periodic
};

/// Tensor-product S-spline surface Q(u,v) = sum_j [sum_i P_ij S_i(u)] S_j(v) (eq. 3.11):
/// Q(i, j) = P_ij exactly. Open ends repeat the boundary rows/columns (sec. 3.2.4).
/// The extended grid is built once; evaluation costs (2w)^2 basis products.
class SSplineSurface {
 public:
  /// grid: >= 2 x 2 (>= 3 along a closed direction).
  /// @throws CardinalSplineError on too small grids or invalid options.
  SSplineSurface(const PointGrid& grid, const SSplineSurfaceOptions& options = {});

  double uEnd() const { return uSpan_; }  ///< u range [0, uEnd]
  double vEnd() const { return vSpan_; }  ///< v range [0, vEnd]
  /// The options the surface was built with.
  const SSplineSurfaceOptions& options() const { return options_; }

  /// d^du/du d^dv/dv Q(u, v), du, dv in 0..3, in knot-index units. Derivatives are
  /// right-hand limits at knots and truncation edges. Closed directions wrap.
  Eigen::Vector3d evaluate(double u, double v, int du = 0, int dv = 0) const;

  /// Q, Q_u and Q_v on the tensor grid us x vs (same conventions as evaluate), each
  /// #us*#vs x 3 with row iu * #vs + iv. Shares the basis values along each axis, so it costs
  /// O(#us * #vs * 2w) instead of O(#us * #vs * (2w)^2) for repeated evaluate() calls.
  struct GridSamples {
    ///@{
    /// Q, Q_u and Q_v at the grid's samples.
    Eigen::MatrixX3d points, du, dv;
    ///@}
  };
  /// Q, Q_u and Q_v on the tensor grid us x vs (see GridSamples).
  GridSamples sampleGrid(const Eigen::VectorXd& us, const Eigen::VectorXd& vs) const;

 private:
  SSplineSurfaceOptions options_;
  SSplineBasis basisU_, basisV_;
  int uSpan_ = 0, vSpan_ = 0;
  PointGrid extended_;  // indices shifted by (wU, wV): extended_(i + wU, j + wV) = P_ij
};

}  // namespace ffdkit::geometry::cardinal
