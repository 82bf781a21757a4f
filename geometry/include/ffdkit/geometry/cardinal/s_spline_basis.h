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
/// @see Kuriyama 1996, sec. 3.2.3 (segment polynomials) (centred assembly).
/// @throws CardinalSplineError if beta2 < 0 or deriv not in 0..3.
double beta2SplineBasis(double x, double beta2, int deriv = 0, Limit side = Limit::Value);

/// Centred uniform B-spline M_m(x) of odd degree m in 3..9 (knots at the integers, support
/// [-(m+1)/2, (m+1)/2]) and its derivatives of order deriv in 0..min(3, m-1), from the
/// truncated-power form of eq. (3.5), evaluated on the half nearer its left end (symmetry) to
/// limit cancellation.
/// @throws CardinalSplineError on an even or out-of-range degree or derivative order.
double centredBSpline(double x, int degree, int deriv = 0);

/// Coefficients c_0..c_w of the S-spline of odd degree m (beta2 = 0): c_i = sum_p kappa_p
/// xi_p^i over the k-1 roots xi_p in (-1, 0) of V_1 xi^{m-1} + ... + V_m = 0 (eq. 3.9, corrected
/// exponent; V_j = N_0^m(j), eq. 3.6), kappa from the k-1 equations (3.7), m = 2k-1.
/// degree 3 agrees with the closed form of sSplineCoefficients(0, w).
/// @see Kuriyama 1996, sec. 3.2.2, eq. (3.4)-(3.9).
/// @throws CardinalSplineError on an even or out-of-range degree, or halfWidth < 1.
Eigen::VectorXd sSplineCoefficientsOddDegree(int degree, int halfWidth);

/// Coefficients c_0..c_w of the beta2 S-spline: c_i = sqrt((b+12)/(b+4)) xi0^i with
/// xi0 = (-(b+8) + sqrt((b+12)(b+4))) / 4. beta2 = 0 gives sqrt(3)(-2+sqrt(3))^i.
/// @see Kuriyama 1996, secs. 3.2.2, 3.2.3, Table 3-1 (sec. 3.2.3).
/// @throws CardinalSplineError if beta2 < 0 or halfWidth < 1.
Eigen::VectorXd sSplineCoefficients(double beta2, int halfWidth);

/// The truncated local cardinal basis S_0(x) = sum_{|i|<=w} c_|i| B(x - i; beta2) for |x| < w,
/// 0 otherwise (open support interval: exact interpolation, Kuriyama 1996, sec. 3.2.2). S_k(x) =
/// S_0(x-k). For odd degree m = 2k-1 > 3 the sum runs to |i| <= w + k - 2, since M_m does not
/// vanish at its inner knots; this keeps S_0(j) = delta_0j exactly for all integers (an extension:
/// the thesis only writes the cubic case out).
/// @see Kuriyama 1996, eq. (3.3), (3.10).
class SSplineBasis {
 public:
  /// degree 3 uses the beta2-spline B(x; beta2); odd degrees 5..9 use the B-spline M_m and
  /// need beta2 = 0 (the thesis's beta2 extension is cubic only).
  /// @throws CardinalSplineError if beta2 < 0, halfWidth < 1, or the degree is unsupported.
  /// clipped = false gives an unclipped variant of the S-spline of Kuriyama 1996, sec. 3.2 (not in
  /// the thesis): no cut at |x| = w, so the curve is an ordinary uniform spline (exactly C2 /
  /// G2-beta) that interpolates only approximately (the truncation is what the thesis accepts in
  /// sec. 3.2.2).
  explicit SSplineBasis(double beta2 = 0.0, int halfWidth = 4, int degree = 3,
                        bool clipped = true);

  /// Tension beta2.
  double beta2() const { return beta2_; }
  /// B-spline degree (odd).
  int degree() const { return degree_; }
  /// True for the thesis's clipped basis.
  bool clipped() const { return clipped_; }
  /// S_0 vanishes for |x| >= supportRadius(): w when clipped, else w + k - 1 + (m+1)/2.
  double supportRadius() const;
  /// Truncation half-width w.
  int halfWidth() const { return halfWidth_; }
  /// c_0..c_w (degree 3) or c_0..c_{w+k-2} (degree m = 2k-1 > 3, see evaluate).
  const Eigen::VectorXd& coefficients() const { return c_; }

  /// S_0^(deriv)(x), x in knot-index units. With Limit::Value and deriv = 0 the open-support
  /// rule applies (0 at |x| >= w); otherwise the requested one-sided limit (Value is taken
  /// as FromRight for deriv >= 1).
  double evaluate(double x, int deriv = 0, Limit side = Limit::Value) const;

  /// lambda_w of the tangent end condition: Q'(0+) = lambda_w * dP0 + S_0'(-w+) * P_w
  /// (Kuriyama 1996, secs. 3.2.4, 3.2.2 item 6): lambda_w = -sum_{j=1}^{w-1} S_0'(j), since the
  /// mirrored data terms cancel in pairs (S_0' is odd) and only the truncation-edge term P_w is
  /// left.
  /// Unclipped: the sum runs over the whole support and there is no edge term.
  double tangentFactor() const;

 private:
  double beta2_;
  int halfWidth_;
  int degree_;
  bool clipped_;
  Eigen::VectorXd c_;
};

}  // namespace ffdkit::geometry::cardinal
