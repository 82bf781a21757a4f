#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/g3/g3_curve_solver.h"
#include "ffdkit/geometry/g3/quadratic_curvature_spline.h"

namespace ffdkit::geometry::g3 {

/// The comparison curve of the paper (sec. 2, Figs. 2(b), 4(a)): a G2 interpolating clothoid
/// spline whose curvature is continuous and piecewise linear in arc length, i.e. psi(s) is a
/// C^1 clamped quadratic B-spline with de Boor ordinates e_{-1}..e_n (n+2 of them) and Bezier
/// ordinates b_{2i+1} = e_i, b_{2i} = (Delta s_i e_{i-1} + Delta s_{i-1} e_i) / (Delta s_{i-1} + Delta s_i)
/// (Kuroda et al. 1997, sec. 2, last item). Its dkappa/ds jumps at the knots: it is not G3.
class ClothoidSpline {
 public:
  /// spanStarts (n+1) x 2 (p_0..p_n), spanLengths n (> 0), deBoor n+2 (e_{-1}..e_n).
  /// @throws G3InputError on wrong sizes or non-positive / non-finite values.
  static ClothoidSpline fromSpanStarts(const Eigen::Ref<const Eigen::MatrixX2d>& spanStarts,
                                       const Eigen::Ref<const Eigen::VectorXd>& spanLengths,
                                       const Eigen::Ref<const Eigen::VectorXd>& deBoor);

  /// Number of spans n.
  int spanCount() const { return static_cast<int>(spanLengths_.size()); }
  /// Total arc length.
  double length() const { return knots_[knots_.size() - 1]; }
  /// Arc length of each span, Delta s_0..Delta s_{n-1}.
  const Eigen::VectorXd& spanLengths() const { return spanLengths_; }
  const Eigen::VectorXd& knots() const { return knots_; }            ///< s_0..s_n
  const Eigen::VectorXd& deBoor() const { return deBoor_; }          ///< e_{-1}..e_n
  const Eigen::VectorXd& bezierOrdinates() const { return bezier_; } ///< b_0..b_{2n}
  /// Start point of each span, p_0..p_n, (n+1) x 2.
  const Eigen::MatrixX2d& spanStarts() const { return spanStarts_; }

  /// Evaluations at s in [0, length()]; dkappa/ds is the span's constant sharpness (the span on
  /// the right at an interior knot). @throws G3InputError outside the curve.
  double tangentAngle(double s) const;
  /// Curvature at arc length s.
  double curvature(double s) const;
  /// dkappa/ds at arc length s.
  double curvatureDerivative(double s) const;
  /// Position at arc length s.
  Eigen::Vector2d position(double s) const;
  /// Sharpness (dkappa/ds) of span i.
  double sharpness(int span) const;
  /// Delta s_i * integral of (cos, sin) psi_i, with panelMultiplier times the default panels.
  Eigen::Vector2d spanDisplacement(int span, int panelMultiplier = 1) const;
  /// n*perSpan+1 samples, as QuadraticCurvatureSpline::sample.
  CurveSamples sample(int perSpan) const;

 private:
  ClothoidSpline() = default;
  int locate(double s, double& t) const;

  Eigen::VectorXd spanLengths_, deBoor_, bezier_, knots_;
  Eigen::MatrixX2d spanStarts_;
};

/// A solved clothoid spline and how the solve went.
struct ClothoidSplineResult {
  G3SolveStatus status = G3SolveStatus::MaxIterations;  ///< how the solve ended
  bool converged = false;  ///< status == Converged
  int iterations = 0;  ///< Newton iterations taken
  double residualNorm = 0.0;       ///< ||f||_2 unscaled
  double scaledResidualInf = 0.0;  ///< as G3SolveResult
  std::vector<double> residualHistory;  ///< residual norm before the first and after each iteration
  std::string message;  ///< why it failed, empty on success
  Eigen::VectorXd unknowns;        ///< (Delta s_0..Delta s_{n-1}, e_{-1}..e_n), last iterate
  std::optional<ClothoidSpline> curve;  ///< set only when converged
};

/// Solves the clothoid spline through points ((n+1) x 2) with end curvatures kappa_0 =
/// 2 (e_0 - e_{-1}) / Delta s_0 and kappa_n = 2 (e_n - e_{n-1}) / Delta s_{n-1}: 2n+2 unknowns,
/// 2n interpolation rows + 2 conditions, square. Damped Newton with the analytic Jacobian
/// (options.maxIterations, tolerance, lineSearchFloor, quadratureNodes, maxTurnPerPanel are
/// used; Levenberg-Marquardt, continuation and paper mode are not). The initial guess comes
/// from initialGuessFromCubicSpline.
/// @throws G3InputError for invalid points or non-finite curvatures.
/// @see Kuroda et al. 1997, sec. 2 (the clothoid spline the paper compares with).
ClothoidSplineResult solveClothoidSpline(const Eigen::Ref<const Eigen::MatrixX2d>& points, double startCurvature,
                                         double endCurvature, const G3SolverOptions& options = {});

}  // namespace ffdkit::geometry::g3
