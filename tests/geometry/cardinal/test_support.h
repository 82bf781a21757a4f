#pragma once

// Shared helpers for the cardinal tests: basis functions read off curves with unit data, and
// an independent clamped cubic spline (Hermite form, Kuriyama 1996, sec. 2.3.2) as an oracle.

#include <Eigen/Dense>

#include "ffdkit/geometry/cardinal/sigma_curve.h"
#include "ffdkit/geometry/cardinal/sigma_knots.h"

namespace ffdkit::geometry::cardinal::test {

/// sigma_k(x) (cardinal) or sigmahat_k(x) (auxiliary) as the x-coordinate of a curve with
/// unit data in slot k.
inline double sigmaBasis(const SigmaKnots& knots, int k, double x, bool auxiliary,
                         int deriv = 0) {
  Eigen::MatrixX3d p = Eigen::MatrixX3d::Zero(knots.pointCount(), 3);
  Eigen::MatrixX3d s = Eigen::MatrixX3d::Zero(knots.shapeCount(), 3);
  if (auxiliary) {
    s(k - knots.shapeFirst(), 0) = 1.0;
  } else {
    p(k, 0) = 1.0;
  }
  return SigmaCurve(knots, p, s).evaluate(x, deriv).x();
}

/// Clamped C2 cubic spline through P at knots t with end derivatives d0, dn (global
/// parameter), evaluated at x. Hermite form with the tridiagonal system of eq. (2.3),
/// solved densely: an oracle independent of the sigma-spline code.
inline Eigen::Vector3d clampedCubicSpline(const Eigen::VectorXd& t, const Eigen::MatrixX3d& P,
                                          const Eigen::Vector3d& d0, const Eigen::Vector3d& dn,
                                          double x) {
  const int n = static_cast<int>(t.size()) - 1;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 1, n + 1);
  Eigen::MatrixX3d b = Eigen::MatrixX3d::Zero(n + 1, 3);
  A(0, 0) = 1.0;
  b.row(0) = d0.transpose();
  A(n, n) = 1.0;
  b.row(n) = dn.transpose();
  for (int i = 1; i < n; ++i) {
    const double dm = t[i] - t[i - 1], d = t[i + 1] - t[i];
    A(i, i - 1) = d;
    A(i, i) = 2.0 * (dm + d);
    A(i, i + 1) = dm;
    b.row(i) = 3.0 * (d * (P.row(i) - P.row(i - 1)) / dm + dm * (P.row(i + 1) - P.row(i)) / d);
  }
  const Eigen::MatrixX3d D = A.partialPivLu().solve(Eigen::MatrixXd(b));
  int i = 0;
  while (i < n - 1 && x >= t[i + 1]) ++i;
  const double d = t[i + 1] - t[i];
  const double s = (x - t[i]) / d;
  const double h0 = 1 - 3 * s * s + 2 * s * s * s, h1 = s - 2 * s * s + s * s * s;
  const double h2 = -s * s + s * s * s, h3 = 3 * s * s - 2 * s * s * s;
  return (h0 * P.row(i) + h1 * d * D.row(i) + h2 * d * D.row(i + 1) + h3 * P.row(i + 1))
      .transpose();
}

}  // namespace ffdkit::geometry::cardinal::test
