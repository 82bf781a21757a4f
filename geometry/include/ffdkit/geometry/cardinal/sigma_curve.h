#pragma once

#include <array>

#include <Eigen/Core>

#include "ffdkit/geometry/cardinal/sigma_knots.h"

namespace ffdkit::geometry::cardinal {

/// Quartic Bezier control points of one interval, b_0..b_4.
using QuarticBezier = std::array<Eigen::Vector3d, 5>;

/// The quartic Bezier form of interval i of a sigma-spline from its five local coefficients:
/// b0 = P_i, b2 = Phat_i, b4 = P_{i+1},
/// b1 = C_{i,1} P_i + Chat_{i,1} Phat_i + Chat_{i-1,4} Phat_{i-1},
/// b3 = C_{i+1,0} P_{i+1} + Chat_{i,3} Phat_i + Chat_{i+1,0} Phat_{i+1}.
/// @see Kuriyama 1996, sec. 3.3.2, eqs. (3.17)-(3.24) (in per-interval Bezier form).
QuarticBezier sigmaIntervalBezier(const SigmaKnots& knots, int i, const Eigen::Vector3d& p0,
                                  const Eigen::Vector3d& p1, const Eigen::Vector3d& shapePrev,
                                  const Eigen::Vector3d& shape, const Eigen::Vector3d& shapeNext);

/// d^deriv/ds^deriv of a quartic Bezier at local s in [0, 1] (deriv 0..4).
Eigen::Vector3d evaluateQuarticBezier(const QuarticBezier& b, double s, int deriv = 0);

/// Splits a quartic Bezier and returns the piece on local [a, c], reparametrised to [0, 1].
QuarticBezier quarticBezierPiece(const QuarticBezier& b, double a, double c);

/// sigma-spline curve Q(x) = sum_i P_i sigma_i(x) + sum_i Phat_i sigmahat_i(x) (eq. 3.24):
/// exact G2 (C1 plus Q''(t+) = Q''(t-) + beta2_i Q'(t-)), Q(t_i) = P_i for any shape points.
/// Shape points: row r holds Phat_{r + knots.shapeFirst()}.
class SigmaCurve {
 public:
  /// points: knots.pointCount() x 3; shapePoints: knots.shapeCount() x 3.
  /// @throws CardinalSplineError on size mismatch.
  SigmaCurve(SigmaKnots knots, Eigen::MatrixX3d points, Eigen::MatrixX3d shapePoints);

  /// The knots and tensions.
  const SigmaKnots& knots() const { return knots_; }
  /// The interpolation points, knots.pointCount() x 3.
  const Eigen::MatrixX3d& points() const { return points_; }
  /// The shape points, knots.shapeCount() x 3.
  const Eigen::MatrixX3d& shapePoints() const { return shape_; }

  Eigen::Vector3d point(int i) const;  ///< P_i (closed: modulo n)
  Eigen::Vector3d shape(int i) const;  ///< Phat_i, i in shapeFirst().. (closed: modulo n)

  /// Bezier control points of interval i in 0..n-1.
  QuarticBezier bezier(int interval) const;

  /// Q^(deriv)(x) with respect to the global parameter x, deriv 0..4; right-continuous at
  /// knots (the last knot of an open curve belongs to the last interval).
  Eigen::Vector3d evaluate(double x, int deriv = 0) const;

 private:
  SigmaKnots knots_;
  Eigen::MatrixX3d points_;
  Eigen::MatrixX3d shape_;
};

}  // namespace ffdkit::geometry::cardinal
