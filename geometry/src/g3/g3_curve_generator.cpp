#include "ffdkit/geometry/g3/g3_curve_generator.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ffdkit/geometry/g3/clothoid_approximation.h"
#include "ffdkit/geometry/g3/g3_error.h"
#include "points_validation.h"

namespace ffdkit::geometry::g3 {
namespace {

Eigen::MatrixX2d pointMatrix(const std::vector<Eigen::Vector2d>& points) {
  Eigen::MatrixX2d m(static_cast<Eigen::Index>(points.size()), 2);
  for (size_t i = 0; i < points.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return m;
}

}  // namespace

void G3CurveParams::validate() const {
  detail::validatePoints(pointMatrix(points), "g3-curve points");
  if (clothoidLevels < 0 || clothoidLevels > 8) {
    std::ostringstream msg;
    msg << "g3-curve clothoidLevels must be in 0..8, got " << clothoidLevels;
    throw G3InputError(msg.str());
  }
  if (!std::isfinite(z)) throw G3InputError("g3-curve z must be finite");
}

QuadraticCurvatureSpline buildG3Curve(const G3CurveParams& params) {
  params.validate();
  const G3SolveResult r = solveG3Curve(pointMatrix(params.points), params.conditions, params.solver);
  if (!r.converged) {
    std::ostringstream msg;
    msg << "g3-curve: the solve did not converge (" << toString(r.status) << "): " << r.message
        << "; check that the conditions are compatible with the points";
    throw G3SolveError(msg.str());
  }
  return *r.curve;
}

CurveSamples sampleG3Curve(const G3CurveParams& params, const G3CurveSampling& sampling) {
  if (sampling.samplesPerSpan < 1) {
    std::ostringstream msg;
    msg << "g3-curve sampling needs samplesPerSpan >= 1, got " << sampling.samplesPerSpan;
    throw G3InputError(msg.str());
  }
  const QuadraticCurvatureSpline curve = buildG3Curve(params);
  if (params.clothoidLevels == 0) return curve.sample(sampling.samplesPerSpan);

  ClothoidApproximationOptions options;
  options.subdivisionLevels = params.clothoidLevels;
  options.measureErrors = false;
  const ClothoidApproximation approx = approximateByClothoids(curve, options);
  if (!approx.converged) throw G3SolveError("g3-curve: a bi-clothoid fit did not converge");
  const int perArc = std::max(2, sampling.samplesPerSpan >> params.clothoidLevels);
  const Eigen::MatrixX2d points = sampleClothoidArcs(approx.arcs, perArc);
  const Eigen::Index count = points.rows();
  CurveSamples out;
  out.points = points;
  out.arcLength.resize(count);
  out.tangentAngle.resize(count);
  out.curvature.resize(count);
  out.curvatureDerivative.resize(count);
  double s0 = 0.0;
  Eigen::Index k = 0;
  for (const ClothoidArc& arc : approx.arcs) {
    for (int j = 0; j < perArc; ++j, ++k) {
      const double sigma = arc.length * j / perArc;
      out.arcLength[k] = s0 + sigma;
      out.tangentAngle[k] = arc.angle(sigma);
      out.curvature[k] = arc.curvature(sigma);
      out.curvatureDerivative[k] = arc.sharpness;
    }
    s0 += arc.length;
  }
  const ClothoidArc& last = approx.arcs.back();
  out.arcLength[k] = s0;
  out.tangentAngle[k] = last.endAngle();
  out.curvature[k] = last.endCurvature();
  out.curvatureDerivative[k] = last.sharpness;
  return out;
}

geometry::Polyline generateG3Curve(const G3CurveParams& params, const G3CurveSampling& sampling) {
  const CurveSamples samples = sampleG3Curve(params, sampling);
  geometry::Polyline line;
  line.closed = false;
  line.points.resize(samples.points.rows(), 3);
  line.points.leftCols<2>() = samples.points;
  line.points.col(2).setConstant(params.z);
  return line;
}

}  // namespace ffdkit::geometry::g3
