#include "ffdkit/geometry/cardinal/s_spline_basis.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

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
  // Segment polynomials of sec. 3.2.3 in the order b1, b0, b_{-1}, b_{-2} (Kuriyama 1996,
  // sec. 3.2.3).
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
  // sec. 3.2.3: the decaying root of the characteristic equation and its normalisation.
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

namespace {

void checkOddDegree(int degree, const char* where) {
  if (degree < 3 || degree > 9 || degree % 2 == 0) {
    throw CardinalSplineError(std::string(where) + ": degree must be odd in 3..9, got " +
                              std::to_string(degree));
  }
}

double factorial(int n) {
  double f = 1.0;
  for (int k = 2; k <= n; ++k) f *= k;
  return f;
}

double binomial(int n, int k) { return factorial(n) / (factorial(k) * factorial(n - k)); }

// Value at xi of V_1 xi^{m-1} + ... + V_m and its derivative (Horner).
std::pair<double, double> characteristic(const Eigen::VectorXd& v, double xi) {
  double p = 0.0, dp = 0.0;
  for (Eigen::Index j = 0; j < v.size(); ++j) {
    dp = dp * xi + p;
    p = p * xi + v[j];
  }
  return {p, dp};
}

}  // namespace

double centredBSpline(double x, int degree, int deriv) {
  checkOddDegree(degree, "centredBSpline");
  if (deriv < 0 || deriv > std::min(3, degree - 1)) {
    throw CardinalSplineError("centredBSpline: deriv must be in 0.." +
                              std::to_string(std::min(3, degree - 1)) + ", got " +
                              std::to_string(deriv));
  }
  const double half = 0.5 * (degree + 1);
  if (std::abs(x) >= half) return 0.0;
  // N_0^m(y), y = x + half, by eq. (3.5) on the left half; M is even, so its r-th derivative
  // picks up (-1)^r when reflected.
  double y = x + half;
  double sign = 1.0;
  if (x > 0.0) {
    y = half - x;
    if (deriv % 2 == 1) sign = -1.0;
  }
  const int power = degree - deriv;
  double sum = 0.0;
  for (int p = 0; p <= degree + 1 && p < y; ++p) {
    const double term = binomial(degree + 1, p) * std::pow(y - p, power);
    sum += (p % 2 == 0) ? term : -term;
  }
  return sign * sum / factorial(power);
}

Eigen::VectorXd sSplineCoefficientsOddDegree(int degree, int halfWidth) {
  checkOddDegree(degree, "sSplineCoefficientsOddDegree");
  if (halfWidth < 1) {
    throw CardinalSplineError("sSplineCoefficientsOddDegree: halfWidth must be >= 1, got " +
                              std::to_string(halfWidth));
  }
  const int m = degree;
  const int k = (m + 1) / 2;
  const double half = 0.5 * (m + 1);
  // eq. (3.6): V_j = N_0^m(j), j = 1..m.
  Eigen::VectorXd v(m);
  for (int j = 1; j <= m; ++j) v[j - 1] = centredBSpline(j - half, m);
  // eq. (3.9): roots of the palindromic degree m-1 polynomial via its companion matrix,
  // keeping the k-1 real ones in (-1, 0), polished by Newton.
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(m - 1, m - 1);
  for (int j = 0; j < m - 1; ++j) companion(0, j) = -v[j + 1] / v[0];
  for (int j = 1; j < m - 1; ++j) companion(j, j - 1) = 1.0;
  const Eigen::VectorXcd eig = Eigen::EigenSolver<Eigen::MatrixXd>(companion, false).eigenvalues();
  std::vector<double> roots;
  for (Eigen::Index r = 0; r < eig.size(); ++r) {
    if (std::abs(eig[r].imag()) > 1e-8 || !(eig[r].real() > -1.0 && eig[r].real() < 0.0)) continue;
    double xi = eig[r].real();
    for (int it = 0; it < 20; ++it) {
      const auto [p, dp] = characteristic(v, xi);
      if (dp == 0.0) break;
      const double step = p / dp;
      xi -= step;
      if (std::abs(step) < 1e-17) break;
    }
    roots.push_back(xi);
  }
  if (static_cast<int>(roots.size()) != k - 1) {
    throw CardinalSplineError("sSplineCoefficientsOddDegree: expected " + std::to_string(k - 1) +
                              " roots in (-1, 0) for degree " + std::to_string(m) + ", found " +
                              std::to_string(roots.size()));
  }
  std::sort(roots.begin(), roots.end());
  // eq. (3.7) for j = 0..k-2: sum_{|i|<=k-1} V_{k+i} c_{j-i} = delta_{j0}, c_l = sum_p kappa_p xi_p^|l|.
  Eigen::MatrixXd a(k - 1, k - 1);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(k - 1);
  rhs[0] = 1.0;
  for (int j = 0; j <= k - 2; ++j) {
    for (int p = 0; p < k - 1; ++p) {
      double sum = 0.0;
      for (int i = -(k - 1); i <= k - 1; ++i) {
        sum += v[k + i - 1] * std::pow(roots[static_cast<std::size_t>(p)], std::abs(j - i));
      }
      a(j, p) = sum;
    }
  }
  const Eigen::VectorXd kappa = a.fullPivLu().solve(rhs);
  Eigen::VectorXd c = Eigen::VectorXd::Zero(halfWidth + 1);
  for (int i = 0; i <= halfWidth; ++i) {
    for (int p = 0; p < k - 1; ++p) c[i] += kappa[p] * std::pow(roots[static_cast<std::size_t>(p)], i);
  }
  return c;
}

SSplineBasis::SSplineBasis(double beta2, int halfWidth, int degree, bool clipped)
    : beta2_(beta2), halfWidth_(halfWidth), degree_(degree), clipped_(clipped) {
  checkOddDegree(degree, "SSplineBasis");
  if (degree != 3 && beta2 != 0.0) {
    throw CardinalSplineError("SSplineBasis: beta2 must be 0 for degree " +
                              std::to_string(degree) + " (the beta2 extension is cubic), got " +
                              std::to_string(beta2));
  }
  // Degree m = 2k-1 > 3: M_m is nonzero at the knots +-1..+-(k-1), so the translates up to
  // |i| = w + k - 2 are kept for S_0 to stay exactly cardinal at every knot |j| < w (for the
  // cubic this is the thesis's |i| <= w of eq. 3.3).
  c_ = degree == 3 ? sSplineCoefficients(beta2, halfWidth)
                   : sSplineCoefficientsOddDegree(degree, halfWidth + (degree + 1) / 2 - 2);
}

double SSplineBasis::supportRadius() const {
  if (clipped_) return halfWidth_;
  return static_cast<double>(c_.size() - 1) + 0.5 * (degree_ + 1);
}

double SSplineBasis::evaluate(double x, int deriv, Limit side) const {
  if (deriv < 0 || deriv > 3) {
    throw CardinalSplineError("SSplineBasis::evaluate: deriv must be in 0..3, got " +
                              std::to_string(deriv));
  }
  const double w = supportRadius();
  Limit effective = side;
  if (deriv > 0 && side == Limit::Value) effective = Limit::FromRight;
  // Open support |x| < w (Kuriyama 1996, sec. 3.2.2); one-sided limits look just inside/outside the
  // cut.
  if (effective == Limit::Value) {
    if (std::abs(x) >= w) return 0.0;
  } else if (effective == Limit::FromRight) {
    if (x < -w || x >= w) return 0.0;
  } else {
    if (x <= -w || x > w) return 0.0;
  }
  const Limit basisSide = effective == Limit::FromLeft ? Limit::FromLeft : Limit::FromRight;
  // Only the translates with |x - i| < (m+1)/2 contribute.
  const int reach = (degree_ + 1) / 2;
  const int last = static_cast<int>(c_.size()) - 1;
  const int lo = std::max(-last, static_cast<int>(std::floor(x)) - reach);
  const int hi = std::min(last, static_cast<int>(std::ceil(x)) + reach);
  double sum = 0.0;
  for (int i = lo; i <= hi; ++i) {
    const double b = degree_ == 3 ? beta2SplineBasis(x - i, beta2_, deriv, basisSide)
                                  : centredBSpline(x - i, degree_, deriv);
    sum += c_[std::abs(i)] * b;
  }
  return sum;
}

double SSplineBasis::tangentFactor() const {
  double lambda = 0.0;
  // Clipped: the pair at j = w is cut (its right-hand term is the edge residue P_w).
  const int last = clipped_ ? halfWidth_ - 1 : static_cast<int>(std::ceil(supportRadius()));
  for (int j = 1; j <= last; ++j) lambda -= evaluate(static_cast<double>(j), 1);
  return lambda;
}

}  // namespace ffdkit::geometry::cardinal
