#pragma once

#include <optional>

#include <Eigen/Core>
#include <Eigen/SparseLU>

#include "ffdkit/geometry/cardinal/point_grid.h"
#include "ffdkit/geometry/cardinal/sigma_curve.h"
#include "ffdkit/geometry/cardinal/sigma_knots.h"
#include "ffdkit/geometry/cardinal/sigma_surface.h"

namespace ffdkit::geometry::cardinal {

/// How the shape (auxiliary) control points Phat of a sigma-spline are chosen by default.
enum class ShapeMode {
  Midpoint,   ///< Phat_i = (P_i + P_{i+1}) / 2 (Fig. 3-13, sec. 3.3.4); open ends by point reflection
  Heuristic,  ///< eq. (3.26), similarity invariant, local (sec. 3.3.4, Kuriyama 1996, sec. 3.3.4)
  Cubic,      ///< the unique shape points making every interval cubic (eq. 3.28/3.33, Kuriyama 1996, sec. 3.3.5)
};

/// End derivatives for the cubic mode, with respect to the LOCAL parameter of the end
/// interval (Q'(t_0) = startSlope / Delta_0). Unset: chord rule P_1 - P_0 and P_n - P_{n-1}
/// (Kuriyama 1996, sec. 3.2.2). Ignored for closed curves.
struct EndSlopes {
  std::optional<Eigen::Vector3d> start;  ///< start slope; unset: the chord rule
  std::optional<Eigen::Vector3d> end;  ///< end slope; unset: the chord rule
};

/// Precomputed factorisation of the cubic-mode system (3.28) + (3.33) (or cyclic (3.28)) for
/// one knot vector; solve() then costs O(n) per right-hand side column.
class CubicShapeSolver {
 public:
  /// @throws CardinalSplineError if the system is singular.
  explicit CubicShapeSolver(const SigmaKnots& knots);

  /// Shape values for data Y (pointCount x k, any k columns) and local end slopes
  /// (1 x k each; ignored when closed). Returns shapeCount x k.
  /// @throws CardinalSplineError on size mismatch, or if the residual max|A x - b| exceeds
  /// 1e-9 (1 + max|b| + max|x|) (never a silently wrong result).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& values, const Eigen::MatrixXd& startSlope,
                        const Eigen::MatrixXd& endSlope) const;

  /// The knots the solver was factored for.
  const SigmaKnots& knots() const { return knots_; }

 private:
  SigmaKnots knots_;
  Eigen::SparseMatrix<double> matrix_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_;
};

/// Shape points for curve data (knots.pointCount() x 3) in the given mode.
/// Returns knots.shapeCount() x 3 (row r <-> Phat_{r + shapeFirst()}).
/// @throws CardinalSplineError on size mismatch.
Eigen::MatrixX3d sigmaShapePoints(const SigmaKnots& knots, const Eigen::MatrixX3d& points,
                                  ShapeMode mode, const EndSlopes& slopes = {});

/// Convenience: the sigma-spline curve interpolating `points` with default shape points.
SigmaCurve interpolateSigmaCurve(const SigmaKnots& knots, const Eigen::MatrixX3d& points,
                                 ShapeMode mode = ShapeMode::Cubic, const EndSlopes& slopes = {});

/// End data of the bicubic mode; everything is in local parameters of the end intervals.
/// Unset fields take the defaults of Kuriyama 1996, sec. 3.3.5: chord rule for the cross-boundary
/// derivatives, 0 for the corner twists.
struct SurfaceEndData {
  std::optional<Eigen::MatrixX3d> uStart;  ///< dQ/du at u = t_0 for every v-knot j (#Pcols x 3)
  std::optional<Eigen::MatrixX3d> uEnd;    ///< dQ/du at u = t_m
  std::optional<Eigen::MatrixX3d> vStart;  ///< dQ/dv at v = t_0 for every u-knot i (#Prows x 3)
  std::optional<Eigen::MatrixX3d> vEnd;    ///< dQ/dv at v = t_n
  /// Corner twists d2Q/dudv at (u0,v0), (u0,vn), (um,v0), (um,vn); unset = 0.
  std::optional<std::array<Eigen::Vector3d, 4>> twists;
};

/// How the shape points of a sigma-spline surface are chosen.
struct SigmaSurfaceOptions {
  ShapeMode mode = ShapeMode::Cubic;  ///< how the shape points are chosen
  SurfaceEndData ends;  ///< Cubic mode only
  /// Cubic mode: use the thesis's literal zero for the twist-like end data of the Pv rows
  /// (sec. 3.3.5) instead of the consistent rule (Kuriyama 1996, sec. 3.3.5). For fidelity tests
  /// only: the result is then not bicubic.
  bool thesisZeroCrossDefaults = false;
  /// Cubic mode: also compute Puv by the v-route and report the difference.
  bool crossCheckRoutes = false;
};

/// A sigma-spline surface with its shape points.
struct SigmaSurfaceResult {
  SigmaSurface surface;  ///< the surface
  /// max |Puv(u-route) - Puv(v-route)| when crossCheckRoutes (else 0).
  double routeDiscrepancy = 0.0;
};

/// Interpolating sigma-spline surface through the grid P (knotsU.pointCount() x
/// knotsV.pointCount()) with default shape grids: Pu along u per knot row, Pv along v per knot
/// column, Puv by the heuristic average (Heuristic/Midpoint, sec. 3.3.4) or by the bicubic
/// rule with consistent cross-end data (Cubic, Kuriyama 1996, sec. 3.3.5).
/// @throws CardinalSplineError on size mismatch.
SigmaSurfaceResult interpolateSigmaSurface(const SigmaKnots& knotsU, const SigmaKnots& knotsV,
                                           const PointGrid& points,
                                           const SigmaSurfaceOptions& options = {});

}  // namespace ffdkit::geometry::cardinal
