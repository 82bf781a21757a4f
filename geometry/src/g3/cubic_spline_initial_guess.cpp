#include "ffdkit/geometry/g3/cubic_spline_initial_guess.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <Eigen/LU>

#include "ffdkit/geometry/g3/g3_error.h"
#include "points_validation.h"
#include "span_quadrature.h"

namespace ffdkit::geometry::g3 {
namespace detail {

void validatePoints(const Eigen::Ref<const Eigen::MatrixX2d>& points, const char* where) {
  if (points.rows() < 2) {
    std::ostringstream msg;
    msg << where << ": needs >= 2 points, got " << points.rows();
    throw G3InputError(msg.str());
  }
  if (!points.allFinite()) {
    std::ostringstream msg;
    msg << where << ": points must be finite";
    throw G3InputError(msg.str());
  }
  const double scale = points.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i + 1 < points.rows(); ++i) {
    if ((points.row(i + 1) - points.row(i)).norm() <= 1e-14 * (1.0 + scale)) {
      std::ostringstream msg;
      msg << where << ": consecutive points " << i << " and " << i + 1 << " coincide at ("
          << points(i, 0) << ", " << points(i, 1) << "); a span needs a non-zero chord";
      throw G3InputError(msg.str());
    }
  }
}

}  // namespace detail

namespace {

// Parametric C^2 cubic through the points, chord-length parameter, stored by second
// derivatives M_i at the nodes (one column per coordinate).
struct ParametricCubic {
  Eigen::VectorXd h;       // n parameter steps (chord lengths)
  Eigen::MatrixX2d p;      // n+1 points
  Eigen::MatrixX2d m;      // n+1 second derivatives

  Eigen::Vector2d d1(int i, double u) const {
    const double hi = h[i];
    const Eigen::Vector2d mi = m.row(i).transpose();
    const Eigen::Vector2d mj = m.row(i + 1).transpose();
    const Eigen::Vector2d slope = (p.row(i + 1) - p.row(i)).transpose() / hi;
    return -mi * (hi - u) * (hi - u) / (2.0 * hi) + mj * u * u / (2.0 * hi) + slope - (mj - mi) * hi / 6.0;
  }
  Eigen::Vector2d d2(int i, double u) const {
    return (m.row(i).transpose() * (h[i] - u) + m.row(i + 1).transpose() * u) / h[i];
  }
  double curvature(int i, double u) const {
    const Eigen::Vector2d a = d1(i, u);
    const Eigen::Vector2d b = d2(i, u);
    return (a.x() * b.y() - a.y() * b.x()) / std::pow(a.norm(), 3);
  }
};

ParametricCubic fitNotAKnot(const Eigen::Ref<const Eigen::MatrixX2d>& points) {
  const int n = static_cast<int>(points.rows()) - 1;
  ParametricCubic c;
  c.p = points;
  c.h.resize(n);
  for (int i = 0; i < n; ++i) c.h[i] = (points.row(i + 1) - points.row(i)).norm();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n + 1, n + 1);
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(n + 1, 2);
  const auto& h = c.h;
  for (int i = 1; i < n; ++i) {
    a(i, i - 1) = h[i - 1];
    a(i, i) = 2.0 * (h[i - 1] + h[i]);
    a(i, i + 1) = h[i];
    rhs.row(i) = 6.0 * ((points.row(i + 1) - points.row(i)) / h[i] - (points.row(i) - points.row(i - 1)) / h[i - 1]);
  }
  if (n == 1) {  // the line
    a(0, 0) = 1.0;
    a(1, 1) = 1.0;
  } else if (n == 2) {  // the parabola: both not-a-knot rows coincide, so ask M constant
    a(0, 0) = 1.0;
    a(0, 1) = -1.0;
    a(2, 1) = -1.0;
    a(2, 2) = 1.0;
  } else {  // third derivative continuous at u_1 and u_{n-1}
    a(0, 0) = h[1];
    a(0, 1) = -(h[0] + h[1]);
    a(0, 2) = h[0];
    a(n, n - 2) = h[n - 1];
    a(n, n - 1) = -(h[n - 2] + h[n - 1]);
    a(n, n) = h[n - 2];
  }
  c.m = a.partialPivLu().solve(rhs);
  return c;
}

double unwrapNear(double reference, double angle) {
  return angle + 2.0 * std::numbers::pi * std::round((reference - angle) / (2.0 * std::numbers::pi));
}

}  // namespace

CubicSplineInitialGuess initialGuessFromCubicSpline(const Eigen::Ref<const Eigen::MatrixX2d>& points) {
  detail::validatePoints(points, "initialGuessFromCubicSpline");
  const int n = static_cast<int>(points.rows()) - 1;
  const ParametricCubic cubic = fitNotAKnot(points);
  const auto& rule = detail::defaultRule();
  constexpr int kTable = 64;  // arc-length table entries per span (>= 32 for unwrapping)

  // Table of (s, u, psi) at kTable+1 parameters per span; psi unwrapped along the curve.
  const int rows = n * kTable + 1;
  Eigen::VectorXd tableS(rows), tableAngle(rows);
  Eigen::VectorXi tableSpan(rows);
  Eigen::VectorXd tableU(rows);
  CubicSplineInitialGuess guess;
  guess.spanLengths.resize(n);
  guess.curvatureAtPoints.resize(n + 1);
  guess.tangentAtPoints.resize(n + 1);
  double s = 0.0;
  double angle = 0.0;
  int r = 0;
  for (int i = 0; i < n; ++i) {
    const double hi = cubic.h[i];
    double spanLength = 0.0;
    for (int k = 0; k <= kTable; ++k) {
      const double u = hi * k / kTable;
      if (k > 0) {
        spanLength += integrateGaussLegendre(rule, hi * (k - 1) / kTable, u, [&](double w) { return cubic.d1(i, w).norm(); });
      }
      if (k == kTable && i + 1 < n) break;  // the next span's first entry is this point
      const Eigen::Vector2d t = cubic.d1(i, u);
      const double raw = std::atan2(t.y(), t.x());
      angle = (r == 0) ? raw : unwrapNear(angle, raw);
      tableS[r] = s + spanLength;
      tableU[r] = u;
      tableSpan[r] = i;
      tableAngle[r] = angle;
      ++r;
    }
    guess.spanLengths[i] = spanLength;
    guess.curvatureAtPoints[i] = cubic.curvature(i, 0.0);
    guess.tangentAtPoints[i] = tableAngle[i * kTable];
    s += spanLength;
  }
  guess.curvatureAtPoints[n] = cubic.curvature(n - 1, cubic.h[n - 1]);
  guess.tangentAtPoints[n] = tableAngle[rows - 1];
  guess.length = s;

  // Span lengths came from the table's 64 panels of 16 nodes, finer than 16 x 16.
  Eigen::VectorXd knots(n + 1);
  knots[0] = 0.0;
  for (int i = 0; i < n; ++i) knots[i + 1] = knots[i] + guess.spanLengths[i];
  auto knot = [&](int j) { return knots[std::clamp(j, 0, n)]; };
  guess.deBoor.resize(n + 3);
  int row = 0;
  for (int j = -1; j <= n + 1; ++j) {
    const double xi = (knot(j - 1) + knot(j) + knot(j + 1)) / 3.0;
    while (row + 1 < rows - 1 && tableS[row + 1] <= xi) ++row;
    const int next = std::min(row + 1, rows - 1);
    const double gap = tableS[next] - tableS[row];
    const double w = gap > 0.0 ? std::clamp((xi - tableS[row]) / gap, 0.0, 1.0) : 0.0;
    // Interpolate the parameter inside the table cell, then evaluate the exact tangent there.
    const int span = tableSpan[row];
    const double uNext = tableSpan[next] == span ? tableU[next] : cubic.h[span];
    const double u = tableU[row] + w * (uNext - tableU[row]);
    const Eigen::Vector2d t = cubic.d1(span, u);
    guess.deBoor[j + 1] = unwrapNear(tableAngle[row], std::atan2(t.y(), t.x()));
  }
  guess.unknowns.resize(2 * n + 3);
  guess.unknowns << guess.spanLengths, guess.deBoor;
  return guess;
}

}  // namespace ffdkit::geometry::g3
