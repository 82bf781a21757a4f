#include "ffdkit/geometry/g3/quadratic_curvature_spline.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ffdkit/geometry/g3/bohm_conversion.h"
#include "ffdkit/geometry/g3/g3_error.h"
#include "span_quadrature.h"

namespace ffdkit::geometry::g3 {
namespace {

void validate(const Eigen::Ref<const Eigen::VectorXd>& spanLengths,
              const Eigen::Ref<const Eigen::VectorXd>& deBoor) {
  const Eigen::Index n = spanLengths.size();
  if (n < 1) throw G3InputError("QuadraticCurvatureSpline needs >= 1 span, got 0 span lengths");
  if (deBoor.size() != n + 3) {
    std::ostringstream msg;
    msg << "QuadraticCurvatureSpline with " << n << " spans needs n+3 = " << n + 3
        << " de Boor ordinates d_{-1}..d_{n+1}, got " << deBoor.size();
    throw G3InputError(msg.str());
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(spanLengths[i] > 0.0) || !std::isfinite(spanLengths[i])) {
      std::ostringstream msg;
      msg << "span length Delta s_" << i << " must be finite and > 0, got " << spanLengths[i];
      throw G3InputError(msg.str());
    }
  }
  for (Eigen::Index j = 0; j < deBoor.size(); ++j) {
    if (!std::isfinite(deBoor[j])) {
      std::ostringstream msg;
      msg << "de Boor ordinate d_" << j - 1 << " must be finite, got " << deBoor[j];
      throw G3InputError(msg.str());
    }
  }
}

}  // namespace

QuadraticCurvatureSpline QuadraticCurvatureSpline::fromStartPoint(
    const Eigen::Vector2d& start, const Eigen::Ref<const Eigen::VectorXd>& spanLengths,
    const Eigen::Ref<const Eigen::VectorXd>& deBoor) {
  validate(spanLengths, deBoor);
  if (!start.allFinite()) throw G3InputError("start point must be finite");
  QuadraticCurvatureSpline c;
  c.spanLengths_ = spanLengths;
  c.deBoor_ = deBoor;
  const Eigen::Index n = spanLengths.size();
  c.spanStarts_.resize(n + 1, 2);
  c.spanStarts_.row(0) = start.transpose();
  c.finish();
  for (int i = 0; i < n; ++i) {
    c.spanStarts_.row(i + 1) = c.spanStarts_.row(i) + c.spanDisplacement(i).transpose();
  }
  return c;
}

QuadraticCurvatureSpline QuadraticCurvatureSpline::fromSpanStarts(
    const Eigen::Ref<const Eigen::MatrixX2d>& spanStarts, const Eigen::Ref<const Eigen::VectorXd>& spanLengths,
    const Eigen::Ref<const Eigen::VectorXd>& deBoor) {
  validate(spanLengths, deBoor);
  if (spanStarts.rows() != spanLengths.size() + 1) {
    std::ostringstream msg;
    msg << "fromSpanStarts needs n+1 = " << spanLengths.size() + 1 << " span start points, got "
        << spanStarts.rows();
    throw G3InputError(msg.str());
  }
  if (!spanStarts.allFinite()) throw G3InputError("span start points must be finite");
  QuadraticCurvatureSpline c;
  c.spanLengths_ = spanLengths;
  c.deBoor_ = deBoor;
  c.spanStarts_ = spanStarts;
  c.finish();
  return c;
}

void QuadraticCurvatureSpline::finish() {
  bezier_ = bezierOrdinatesFromDeBoor(spanLengths_, deBoor_);
  const Eigen::Index n = spanLengths_.size();
  knots_.resize(n + 1);
  knots_[0] = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) knots_[i + 1] = knots_[i] + spanLengths_[i];
}

double QuadraticCurvatureSpline::spanLength(int span) const {
  if (span < 0 || span >= spanCount()) {
    std::ostringstream msg;
    msg << "span index must be in 0.." << spanCount() - 1 << ", got " << span;
    throw G3InputError(msg.str());
  }
  return spanLengths_[span];
}

Eigen::Vector3d QuadraticCurvatureSpline::curvatureQuadratic(int span) const {
  const double ds = spanLength(span);
  const Eigen::Vector4d b = bezier_.segment<4>(3 * span);
  const double a1 = 3.0 * (b[1] - b[0]);
  const double a2 = 3.0 * (b[2] - 2.0 * b[1] + b[0]);
  const double a3 = b[3] - 3.0 * b[2] + 3.0 * b[1] - b[0];
  return {a1 / ds, 2.0 * a2 / (ds * ds), 3.0 * a3 / (ds * ds * ds)};
}

int QuadraticCurvatureSpline::spanAt(double s) const {
  const int n = spanCount();
  const auto begin = knots_.data() + 1;
  const auto end = knots_.data() + n;  // interior knots s_1..s_{n-1}
  return static_cast<int>(std::upper_bound(begin, end, s) - begin);
}

double QuadraticCurvatureSpline::localT(double s, int& span) const {
  const double len = length();
  const double slack = 1e-12 * len;
  if (!(s >= -slack && s <= len + slack)) {
    std::ostringstream msg;
    msg << "arc length s must be in [0, " << len << "], got " << s;
    throw G3InputError(msg.str());
  }
  s = std::clamp(s, 0.0, len);
  span = spanAt(s);
  return std::clamp((s - knots_[span]) / spanLengths_[span], 0.0, 1.0);
}

double QuadraticCurvatureSpline::tangentAngle(double s) const {
  int span = 0;
  const double t = localT(s, span);
  return detail::cubicBezier(bezier_.segment<4>(3 * span), t);
}

double QuadraticCurvatureSpline::curvature(double s) const {
  int span = 0;
  const double t = localT(s, span);
  const double sigma = t * spanLengths_[span];
  const Eigen::Vector3d c = curvatureQuadratic(span);
  return c[0] + sigma * (c[1] + sigma * c[2]);
}

double QuadraticCurvatureSpline::curvatureDerivative(double s) const {
  int span = 0;
  const double t = localT(s, span);
  const double sigma = t * spanLengths_[span];
  const Eigen::Vector3d c = curvatureQuadratic(span);
  return c[1] + 2.0 * sigma * c[2];
}

double QuadraticCurvatureSpline::curvatureSecondDerivative(double s) const {
  int span = 0;
  localT(s, span);
  return 2.0 * curvatureQuadratic(span)[2];
}

Eigen::Vector2d QuadraticCurvatureSpline::position(double s) const {
  int span = 0;
  const double t = localT(s, span);
  const Eigen::Vector4d b = bezier_.segment<4>(3 * span);
  const int panels = detail::panelCount(detail::controlPolygonTurning(b) * t, detail::kMaxTurnPerPanel);
  const Eigen::Vector2d start = spanStarts_.row(span).transpose();
  return start + spanLengths_[span] *
                     detail::integrateTangent(detail::defaultRule(), [&](double u) { return detail::cubicBezier(b, u); },
                                              0.0, t, panels);
}

Eigen::Vector2d QuadraticCurvatureSpline::spanDisplacement(int span, int panelMultiplier) const {
  const double ds = spanLength(span);
  if (panelMultiplier < 1) throw G3InputError("panelMultiplier must be >= 1");
  const Eigen::Vector4d b = bezier_.segment<4>(3 * span);
  const int panels = panelMultiplier * detail::panelCount(detail::controlPolygonTurning(b), detail::kMaxTurnPerPanel);
  return ds * detail::integrateTangent(detail::defaultRule(), [&](double u) { return detail::cubicBezier(b, u); },
                                       0.0, 1.0, panels);
}

CurveSamples QuadraticCurvatureSpline::sample(int perSpan) const {
  if (perSpan < 1) {
    std::ostringstream msg;
    msg << "sample needs >= 1 sample per span, got " << perSpan;
    throw G3InputError(msg.str());
  }
  const int n = spanCount();
  const int count = n * perSpan + 1;
  CurveSamples out;
  out.arcLength.resize(count);
  out.points.resize(count, 2);
  out.tangentAngle.resize(count);
  out.curvature.resize(count);
  out.curvatureDerivative.resize(count);
  const auto& rule = detail::defaultRule();
  int k = 0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector4d b = bezier_.segment<4>(3 * i);
    const double ds = spanLengths_[i];
    const Eigen::Vector3d c = curvatureQuadratic(i);
    const int panels = detail::panelCount(detail::controlPolygonTurning(b) / perSpan, detail::kMaxTurnPerPanel);
    Eigen::Vector2d p = spanStarts_.row(i).transpose();
    for (int j = 0; j < perSpan; ++j, ++k) {
      const double t = static_cast<double>(j) / perSpan;
      const double sigma = t * ds;
      if (j > 0) {
        const double t0 = static_cast<double>(j - 1) / perSpan;
        p += ds * detail::integrateTangent(rule, [&](double u) { return detail::cubicBezier(b, u); }, t0, t, panels);
      }
      out.arcLength[k] = knots_[i] + sigma;
      out.points.row(k) = p.transpose();
      out.tangentAngle[k] = detail::cubicBezier(b, t);
      out.curvature[k] = c[0] + sigma * (c[1] + sigma * c[2]);
      out.curvatureDerivative[k] = c[1] + 2.0 * sigma * c[2];
    }
  }
  const Eigen::Vector3d c = curvatureQuadratic(n - 1);
  const double ds = spanLengths_[n - 1];
  out.arcLength[k] = length();
  out.points.row(k) = spanStarts_.row(n);
  out.tangentAngle[k] = bezier_[3 * n];
  out.curvature[k] = c[0] + ds * (c[1] + ds * c[2]);
  out.curvatureDerivative[k] = c[1] + 2.0 * ds * c[2];
  return out;
}

}  // namespace ffdkit::geometry::g3
