#include "ffdkit/geometry/cardinal/s_spline_curve.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

#include "floor_mod.h"

namespace ffdkit::geometry::cardinal {
using detail::floorMod;

SSplineCurve::SSplineCurve(const Eigen::MatrixX3d& points, const SSplineCurveOptions& options)
    : points_(points), options_(options), basis_(options.beta2, options.halfWidth, options.degree, options.clipped) {
  const auto count = static_cast<int>(points.rows());
  if (options.end == SSplineEnd::Closed) {
    if (count < 3) {
      throw CardinalSplineError("SSplineCurve: a closed curve needs >= 3 distinct points, got " +
                                std::to_string(count));
    }
    span_ = count;
  } else {
    if (count < 2) {
      throw CardinalSplineError("SSplineCurve: an open curve needs >= 2 points, got " +
                                std::to_string(count));
    }
    span_ = count - 1;
  }
  if (!points.allFinite()) throw CardinalSplineError("SSplineCurve: points must be finite");
  startTangent_ = options.startTangent;
  endTangent_ = options.endTangent;
  if (options.scaleTangent) {
    const double lambda = basis_.tangentFactor();
    startTangent_ /= lambda;
    endTangent_ /= lambda;
  }
}

Eigen::Vector3d SSplineCurve::extendedPoint(int i) const {
  const int s = span_;
  switch (options_.end) {
    case SSplineEnd::Closed:
      return points_.row(floorMod(i, s)).transpose();
    case SSplineEnd::Open:
      return points_.row(std::clamp(i, 0, s)).transpose();
    case SSplineEnd::Tangent:
      // sec. 3.2.4: mirror the data and shift by the tangent; applied recursively so that
      // any index (also beyond 2s) is defined.
      if (i < 0) return extendedPoint(-i) - startTangent_;
      if (i > s) return extendedPoint(2 * s - i) + endTangent_;
      return points_.row(i).transpose();
  }
  return Eigen::Vector3d::Zero();
}

Eigen::Vector3d SSplineCurve::evaluate(double x, int deriv, Limit side) const {
  if (closed()) {
    x -= span_ * std::floor(x / span_);
    if (x >= span_) x = 0.0;
  }
  const int w = static_cast<int>(std::ceil(basis_.supportRadius()));
  const int lo = static_cast<int>(std::floor(x)) - w;
  const int hi = static_cast<int>(std::ceil(x)) + w;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = lo; k <= hi; ++k) {
    const double b = basis_.evaluate(x - k, deriv, side);
    if (b != 0.0) sum += b * extendedPoint(k);
  }
  return sum;
}

}  // namespace ffdkit::geometry::cardinal
