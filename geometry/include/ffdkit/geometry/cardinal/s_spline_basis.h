#pragma once

#include <Eigen/Core>

namespace ffdkit::geometry::cardinal {

/// Which one-sided limit to take where a function jumps (S-spline truncation edges, knots
/// of a derivative that is only piecewise continuous).
enum class Limit {
  Value,      ///< the function's own value (open-support rule for the S-spline)
  FromLeft,   ///< x -> x0^-
  FromRight,  ///< x -> x0^+
};

/// Centred uniform beta2-spline basis B(x; beta2) (beta1 = 1), support [-2, 2], and its
/// derivatives up to order 3 in x. beta2 = 0 gives the uniform cubic B-spline M_3.
/// C1 everywhere; at integer knots B''(k+) = B''(k-) + beta2 B'(k-) (eq. 3.10).
/// deriv >= 1 at a knot uses the side given by `side` (Value means FromRight).
/// @see seed 001 l.944 (segment polynomials), spec §2.3 (centred assembly).
/// @throws CardinalSplineError if beta2 < 0 or deriv not in 0..3.
double beta2SplineBasis(double x, double beta2, int deriv = 0, Limit side = Limit::Value);

/// Coefficients c_0..c_w of the beta2 S-spline: c_i = sqrt((b+12)/(b+4)) xi0^i with
/// xi0 = (-(b+8) + sqrt((b+12)(b+4))) / 4. beta2 = 0 gives sqrt(3)(-2+sqrt(3))^i.
/// @see seed 001 l.918, l.955-965, Table 3-1 (l.946-953).
/// @throws CardinalSplineError if beta2 < 0 or halfWidth < 1.
Eigen::VectorXd sSplineCoefficients(double beta2, int halfWidth);

/// The truncated local cardinal basis S_0(x) = sum_{|i|<=w} c_|i| B(x - i; beta2) for |x| < w,
/// 0 otherwise (open support interval: exact interpolation, spec §7 item 4). S_k(x) = S_0(x-k).
/// @see seed 001 eq. (3.3), (3.10).
class SSplineBasis {
 public:
  /// @throws CardinalSplineError if beta2 < 0 or halfWidth < 1.
  explicit SSplineBasis(double beta2 = 0.0, int halfWidth = 4);

  double beta2() const { return beta2_; }
  int halfWidth() const { return halfWidth_; }
  const Eigen::VectorXd& coefficients() const { return c_; }

  /// S_0^(deriv)(x), x in knot-index units. With Limit::Value and deriv = 0 the open-support
  /// rule applies (0 at |x| >= w); otherwise the requested one-sided limit (Value is taken
  /// as FromRight for deriv >= 1).
  double evaluate(double x, int deriv = 0, Limit side = Limit::Value) const;

  /// lambda_w of the tangent end condition: Q'(0+) = lambda_w * dP0 + S_0'(-w+) * P_w
  /// (spec §2.6, §7 item 6): lambda_w = -sum_{j=1}^{w-1} S_0'(j), since the mirrored data
  /// terms cancel in pairs (S_0' is odd) and only the truncation-edge term P_w is left.
  double tangentFactor() const;

 private:
  double beta2_;
  int halfWidth_;
  Eigen::VectorXd c_;
};

}  // namespace ffdkit::geometry::cardinal
