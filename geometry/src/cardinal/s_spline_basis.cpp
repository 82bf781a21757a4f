#include "ffdkit/geometry/cardinal/s_spline_basis.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

namespace ffdkit::geometry::cardinal {
namespace {

void checkBeta2(double beta2, const char* where) {
  if (!(beta2 >= 0.0) || !std::isfinite(beta2)) {
    throw CardinalSplineError(std::string(where) + ": beta2 must be finite and >= 0, got " +
                              std::to_string(beta2));
  }
}

// d^deriv/dx^deriv of c0 + c1 x + c2 x^2 + c3 x^3.
double cubicDerivative(const double c[4], double x, int deriv) {
  switch (deriv) {
    case 0: return c[0] + x * (c[1] + x * (c[2] + x * c[3]));
    case 1: return c[1] + x * (2.0 * c[2] + 3.0 * x * c[3]);
    case 2: return 2.0 * c[2] + 6.0 * x * c[3];
    case 3: return 6.0 * c[3];
    default: return 0.0;
  }
}

}  // namespace

double beta2SplineBasis(double x, double beta2, int deriv, Limit side) {
  checkBeta2(beta2, "beta2SplineBasis");
  if (deriv < 0 || deriv > 3) {
    throw CardinalSplineError("beta2SplineBasis: deriv must be in 0..3, got " +
                              std::to_string(deriv));
  }
  // Segment k covers [k-2, k-1]; at a knot the side decides which polynomial is used. The
  // basis is C1, so values and first derivatives agree either way.
  const double y = x + 2.0;
  const int seg = (side == Limit::FromLeft) ? static_cast<int>(std::ceil(y)) - 1
                                            : static_cast<int>(std::floor(y));
  if (seg < 0 || seg > 3) return 0.0;
  const double v = beta2 + 12.0;
  const double local = y - seg;
  // Segment polynomials of l.944 in the order b1, b0, b_{-1}, b_{-2} (spec §2.3).
  const double coeffs[4][4] = {
      {0.0, 0.0, 0.0, 2.0},
      {2.0, 6.0, 3.0 * beta2 + 6.0, -(2.0 * beta2 + 6.0)},
      {beta2 + 8.0, 0.0, -(3.0 * beta2 + 12.0), 2.0 * beta2 + 6.0},
      {2.0, -6.0, 6.0, -2.0},
  };
  return cubicDerivative(coeffs[seg], local, deriv) / v;
}

Eigen::VectorXd sSplineCoefficients(double beta2, int halfWidth) {
  checkBeta2(beta2, "sSplineCoefficients");
  if (halfWidth < 1) {
    throw CardinalSplineError("sSplineCoefficients: halfWidth must be >= 1, got " +
                              std::to_string(halfWidth));
  }
  // l.955-965: the decaying root of the characteristic equation and its normalisation.
  const double xi0 = (-(beta2 + 8.0) + std::sqrt((beta2 + 12.0) * (beta2 + 4.0))) / 4.0;
  const double kappa = std::sqrt((beta2 + 12.0) / (beta2 + 4.0));
  Eigen::VectorXd c(halfWidth + 1);
  double power = 1.0;
  for (int i = 0; i <= halfWidth; ++i) {
    c[i] = kappa * power;
    power *= xi0;
  }
  return c;
}

SSplineBasis::SSplineBasis(double beta2, int halfWidth)
    : beta2_(beta2), halfWidth_(halfWidth), c_(sSplineCoefficients(beta2, halfWidth)) {}

double SSplineBasis::evaluate(double x, int deriv, Limit side) const {
  if (deriv < 0 || deriv > 3) {
    throw CardinalSplineError("SSplineBasis::evaluate: deriv must be in 0..3, got " +
                              std::to_string(deriv));
  }
  const double w = halfWidth_;
  Limit effective = side;
  if (deriv > 0 && side == Limit::Value) effective = Limit::FromRight;
  // Open support |x| < w (spec §7 item 4); one-sided limits look just inside/outside the cut.
  if (effective == Limit::Value) {
    if (std::abs(x) >= w) return 0.0;
  } else if (effective == Limit::FromRight) {
    if (x < -w || x >= w) return 0.0;
  } else {
    if (x <= -w || x > w) return 0.0;
  }
  const Limit basisSide = effective == Limit::FromLeft ? Limit::FromLeft : Limit::FromRight;
  // Only the four translates with |x - i| < 2 contribute.
  const int lo = std::max(-halfWidth_, static_cast<int>(std::floor(x)) - 2);
  const int hi = std::min(halfWidth_, static_cast<int>(std::ceil(x)) + 2);
  double sum = 0.0;
  for (int i = lo; i <= hi; ++i) {
    sum += c_[std::abs(i)] * beta2SplineBasis(x - i, beta2_, deriv, basisSide);
  }
  return sum;
}

double SSplineBasis::tangentFactor() const {
  double lambda = 0.0;
  for (int j = 1; j < halfWidth_; ++j) lambda -= evaluate(static_cast<double>(j), 1);
  return lambda;
}

}  // namespace ffdkit::geometry::cardinal
