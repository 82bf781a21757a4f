#pragma once

#include <Eigen/Core>

namespace ffdkit::geometry::g3 {

/// Dense samples of a planar curve against arc length, for polylines, curvature plots and
/// curvature combs. All vectors have the same length N; points is N x 2.
struct CurveSamples {
  Eigen::VectorXd arcLength;            ///< s, ascending from 0 to the curve length
  Eigen::MatrixX2d points;              ///< r(s), one point per row
  Eigen::VectorXd tangentAngle;         ///< psi(s) in rad, unwrapped (never reduced mod 2 pi)
  Eigen::VectorXd curvature;            ///< kappa(s) = dpsi/ds, > 0 turning left
  Eigen::VectorXd curvatureDerivative;  ///< dkappa/ds
};

/// A planar curve parametrized by arc length whose tangent angle psi(s) is a clamped cubic
/// B-spline with a knot at each data point, so its curvature is C^1 piecewise quadratic in s
/// (a G3 curve). Positions integrate r' = (cos psi, sin psi) by composite Gauss-Legendre from
/// the start of the span that holds s, so errors do not accumulate along the curve.
/// @see Kuroda et al. 1997, secs. 2, 3, eq. (1)-(2); Kuroda et al. 1997 and 5.
class QuadraticCurvatureSpline {
 public:
  /// A curve starting at `start`, span starts found by chaining the span integrals.
  ///   spanLengths  n >= 1 values, each > 0 and finite
  ///   deBoor       n+3 values d_{-1}..d_{n+1} (rad), finite
  /// @throws G3InputError on wrong sizes, non-positive or non-finite values.
  static QuadraticCurvatureSpline fromStartPoint(const Eigen::Vector2d& start,
                                                 const Eigen::Ref<const Eigen::VectorXd>& spanLengths,
                                                 const Eigen::Ref<const Eigen::VectorXd>& deBoor);

  /// A curve whose spans start at the given points (n+1 rows, p_0..p_n; p_n is the end
  /// point), as the solver returns it: integrating span i from p_i keeps knot positions exact
  /// up to the solve residual.
  /// @throws G3InputError as fromStartPoint, or when spanStarts has not n+1 rows.
  static QuadraticCurvatureSpline fromSpanStarts(const Eigen::Ref<const Eigen::MatrixX2d>& spanStarts,
                                                 const Eigen::Ref<const Eigen::VectorXd>& spanLengths,
                                                 const Eigen::Ref<const Eigen::VectorXd>& deBoor);

  /// Number of spans n.
  int spanCount() const { return static_cast<int>(spanLengths_.size()); }
  /// Total arc length.
  double length() const { return knots_[knots_.size() - 1]; }
  /// Arc length of span `span`, Delta s_i.
  double spanLength(int span) const;
  /// Arc length of each span, Delta s_0..Delta s_{n-1}.
  const Eigen::VectorXd& spanLengths() const { return spanLengths_; }
  /// s_0 = 0 .. s_n = length(): the arc lengths of the data points (n+1 values).
  const Eigen::VectorXd& knots() const { return knots_; }
  /// d_{-1}..d_{n+1} (n+3 values). In the standard clamped convention the knot vector is
  /// {0,0,0,0,s_1..s_{n-1},L,L,L,L} (n+7 entries); both describe the same spline (sec. 6).
  const Eigen::VectorXd& deBoor() const { return deBoor_; }
  /// b_0..b_{3n} (3n+1 values); span i uses b_{3i}..b_{3i+3}.
  const Eigen::VectorXd& bezierOrdinates() const { return bezier_; }
  /// p_0..p_n, (n+1) x 2.
  const Eigen::MatrixX2d& spanStarts() const { return spanStarts_; }

  /// kappa on span i as c0 + c1*sigma + c2*sigma^2 with sigma = s - s_i in [0, Delta s_i].
  Eigen::Vector3d curvatureQuadratic(int span) const;
  /// The span holding s: span i for s_i <= s < s_{i+1} (the right one at an interior knot), the
  /// last span for s >= s_{n-1}. s is not range-checked here.
  int spanAt(double s) const;

  /// Evaluations at arc length s in [0, length()] (a tolerance of 1e-12 L is clamped).
  /// @throws G3InputError when s is outside the curve.
  double tangentAngle(double s) const;
  /// Curvature at arc length s.
  double curvature(double s) const;
  /// dkappa/ds at arc length s.
  double curvatureDerivative(double s) const;
  /// d^2 kappa / ds^2 = 6 a_3 / Delta s_i^3, constant per span (jumps at knots).
  double curvatureSecondDerivative(double s) const;
  /// Position at arc length s.
  Eigen::Vector2d position(double s) const;

  /// Delta s_i * integral_0^1 (cos psi_i, sin psi_i) dt: the chord the span produces, with
  /// panelMultiplier times the default panel count (for the interpolation property test).
  Eigen::Vector2d spanDisplacement(int span, int panelMultiplier = 1) const;

  /// perSpan >= 1 equal arc-length steps per span, cumulative integration, O(N).
  /// Returns n*perSpan+1 samples.
  /// @throws G3InputError if perSpan < 1.
  CurveSamples sample(int perSpan) const;

 private:
  QuadraticCurvatureSpline() = default;
  void finish();
  double localT(double s, int& span) const;

  Eigen::VectorXd spanLengths_;
  Eigen::VectorXd deBoor_;
  Eigen::VectorXd bezier_;
  Eigen::VectorXd knots_;
  Eigen::MatrixX2d spanStarts_;
};

}  // namespace ffdkit::geometry::g3
