#include "ffdkit/geometry/cardinal/sigma_curve.h"

#include <cmath>
#include <string>
#include <utility>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

#include "floor_mod.h"

namespace ffdkit::geometry::cardinal {
using detail::floorMod;

QuarticBezier sigmaIntervalBezier(const SigmaKnots& knots, int i, const Eigen::Vector3d& p0,
                                  const Eigen::Vector3d& p1, const Eigen::Vector3d& shapePrev,
                                  const Eigen::Vector3d& shape, const Eigen::Vector3d& shapeNext) {
  QuarticBezier b;
  b[0] = p0;
  b[1] = knots.C1(i) * p0 + knots.Chat1(i) * shape + knots.Chat4(i - 1) * shapePrev;
  b[2] = shape;
  b[3] = knots.C0(i + 1) * p1 + knots.Chat3(i) * shape + knots.Chat0(i + 1) * shapeNext;
  b[4] = p1;
  return b;
}

Eigen::Vector3d evaluateQuarticBezier(const QuarticBezier& b, double s, int deriv) {
  if (deriv < 0 || deriv > 4) {
    throw CardinalSplineError("evaluateQuarticBezier: deriv must be in 0..4, got " +
                              std::to_string(deriv));
  }
  // Forward differences give the derivative's Bezier points; scale by 4!/(4-deriv)!.
  std::array<Eigen::Vector3d, 5> c = b;
  int degree = 4;
  double scale = 1.0;
  for (int d = 0; d < deriv; ++d) {
    for (int k = 0; k < degree; ++k) c[k] = c[k + 1] - c[k];
    scale *= degree;
    --degree;
  }
  for (int r = 1; r <= degree; ++r) {
    for (int k = 0; k + r <= degree; ++k) c[k] = (1.0 - s) * c[k] + s * c[k + 1];
  }
  return scale * c[0];
}

namespace {

// All de Casteljau levels of b at parameter a: level[r][k], r = 0..4.
std::array<QuarticBezier, 5> deCasteljauLevels(const QuarticBezier& b, double a) {
  std::array<QuarticBezier, 5> level;
  level[0] = b;
  for (int r = 1; r <= 4; ++r) {
    for (int k = 0; k + r <= 4; ++k) {
      level[r][k] = (1.0 - a) * level[r - 1][k] + a * level[r - 1][k + 1];
    }
  }
  return level;
}

}  // namespace

QuarticBezier quarticBezierPiece(const QuarticBezier& b, double a, double c) {
  // Right part of the split at a, then the left part of that at (c - a) / (1 - a).
  QuarticBezier right = b;
  if (a > 0.0) {
    const auto level = deCasteljauLevels(b, a);
    for (int k = 0; k <= 4; ++k) right[k] = level[4 - k][k];
  }
  if (c >= 1.0) return right;
  const auto level = deCasteljauLevels(right, (c - a) / (1.0 - a));
  QuarticBezier left;
  for (int k = 0; k <= 4; ++k) left[k] = level[k][0];
  return left;
}

SigmaCurve::SigmaCurve(SigmaKnots knots, Eigen::MatrixX3d points, Eigen::MatrixX3d shapePoints)
    : knots_(std::move(knots)), points_(std::move(points)), shape_(std::move(shapePoints)) {
  if (points_.rows() != knots_.pointCount()) {
    throw CardinalSplineError("SigmaCurve: expected " + std::to_string(knots_.pointCount()) +
                              " interpolation points for " + std::to_string(knots_.last() + 1) +
                              (knots_.closed() ? " closed" : " open") + " knots, got " +
                              std::to_string(points_.rows()));
  }
  if (shape_.rows() != knots_.shapeCount()) {
    throw CardinalSplineError("SigmaCurve: expected " + std::to_string(knots_.shapeCount()) +
                              " shape points, got " + std::to_string(shape_.rows()));
  }
}

Eigen::Vector3d SigmaCurve::point(int i) const {
  const int r = knots_.closed() ? floorMod(i, knots_.last()) : i;
  return points_.row(r).transpose();
}

Eigen::Vector3d SigmaCurve::shape(int i) const {
  const int r = knots_.closed() ? floorMod(i, knots_.last()) : i - knots_.shapeFirst();
  return shape_.row(r).transpose();
}

QuarticBezier SigmaCurve::bezier(int interval) const {
  if (interval < 0 || interval >= knots_.intervalCount()) {
    throw CardinalSplineError("SigmaCurve::bezier: interval must be in 0.." +
                              std::to_string(knots_.intervalCount() - 1) + ", got " +
                              std::to_string(interval));
  }
  const int i = interval;
  return sigmaIntervalBezier(knots_, i, point(i), point(i + 1), shape(i - 1), shape(i),
                             shape(i + 1));
}

Eigen::Vector3d SigmaCurve::evaluate(double x, int deriv) const {
  double s = 0.0;
  const int i = knots_.locate(x, s);
  const double d = knots_.delta(i);
  return evaluateQuarticBezier(bezier(i), s, deriv) / std::pow(d, deriv);
}

}  // namespace ffdkit::geometry::cardinal
