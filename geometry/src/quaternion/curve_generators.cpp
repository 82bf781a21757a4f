#include "ffdkit/geometry/quaternion/curve_generators.h"

#include <cmath>
#include <random>
#include <sstream>

#include "ffdkit/geometry/quaternion/quaternion_error.h"

namespace ffdkit::geometry::quaternion {

namespace {
void requireSampling(const char* generator, const CurveSampling& sampling) {
  if (sampling.samples < 2) {
    std::ostringstream msg;
    msg << generator << ": expected sampling.samples >= 2, got " << sampling.samples;
    throw QuaternionCurveError(msg.str());
  }
}

void requirePoints(const char* generator, const Eigen::MatrixX3d& points, int minimum) {
  if (points.rows() < minimum || !points.allFinite()) {
    std::ostringstream msg;
    msg << generator << ": expected at least " << minimum << " finite points, got " << points.rows()
        << (points.allFinite() ? "" : " (with NaN or infinity)");
    throw QuaternionCurveError(msg.str());
  }
}

// Re-throws a solver's input error with the generator's name in front.
template <class F>
auto named(const char* generator, F&& f) {
  try {
    return f();
  } catch (const QuaternionCurveError& e) {
    const std::string what = e.what();
    if (what.rfind(generator, 0) == 0) throw;
    throw QuaternionCurveError(std::string(generator) + ": " + what);
  }
}
}  // namespace

void QiInterpolateParams::validate() const {
  requirePoints("qi-interpolate", points, options.endRule == EndTangentRule::Circle3 ? 3 : 2);
}

void QiFitParams::validate() const {
  requirePoints("qi-fit", points, 2);
  named("qi-fit", [&] { return chordLengthParameters(points, breaks); });
}

void SphereTangentParams::validate() const {
  if (segment.degree != 2 && segment.degree != 3) {
    std::ostringstream msg;
    msg << "sphere-tangent: expected segment.degree 2 or 3, got " << segment.degree;
    throw QuaternionCurveError(msg.str());
  }
  if (!segment.startPoint.allFinite() || !segment.endPoint.allFinite() || !(segment.startTangent.norm() > 0.0) ||
      !(segment.endTangent.norm() > 0.0)) {
    throw QuaternionCurveError("sphere-tangent: expected finite end points and non-zero end tangents");
  }
}

std::shared_ptr<const ArcLengthCurve> solveQiInterpolate(const QiInterpolateParams& params) {
  params.validate();
  InterpolationResult r = named("qi-interpolate", [&] { return interpolateQi(params.points, params.options); });
  if (!r.converged) {
    throw QuaternionCurveError("qi-interpolate: Newton did not converge (" + r.message + ")");
  }
  return std::make_shared<QiSpline>(std::move(r.curve));
}

std::shared_ptr<const ArcLengthCurve> solveQiFit(const QiFitParams& params) {
  params.validate();
  FitResult r = named("qi-fit", [&] { return fitQiChain(params.points, params.breaks, params.options); });
  if (!r.converged) {
    throw QuaternionCurveError("qi-fit: Levenberg-Marquardt stopped without converging (" + r.message + ")");
  }
  return std::make_shared<QiChain>(std::move(r.curve));
}

std::shared_ptr<const ArcLengthCurve> solveSphereTangent(const SphereTangentParams& params) {
  params.validate();
  SphereTangentFitResult r = named("sphere-tangent", [&] { return fitSphereTangentSegment(params.segment, params.options); });
  if (!r.converged || !r.curve) {
    throw QuaternionCurveError("sphere-tangent: no curve meets the end conditions (" + r.message + ")");
  }
  return std::make_shared<TangentIntegralCurve>(std::move(*r.curve));
}

Polyline generateQiInterpolate(const QiInterpolateParams& params, const CurveSampling& sampling) {
  requireSampling("qi-interpolate", sampling);
  return toPolyline(*solveQiInterpolate(params), sampling.samples);
}

Polyline generateQiFit(const QiFitParams& params, const CurveSampling& sampling) {
  requireSampling("qi-fit", sampling);
  return toPolyline(*solveQiFit(params), sampling.samples);
}

Polyline generateSphereTangent(const SphereTangentParams& params, const CurveSampling& sampling) {
  requireSampling("sphere-tangent", sampling);
  return toPolyline(*solveSphereTangent(params), sampling.samples);
}

CurveProfile profileQiInterpolate(const QiInterpolateParams& params, const CurveSampling& sampling) {
  requireSampling("qi-interpolate", sampling);
  return sampleProfile(*solveQiInterpolate(params), sampling.samples);
}

CurveProfile profileQiFit(const QiFitParams& params, const CurveSampling& sampling) {
  requireSampling("qi-fit", sampling);
  return sampleProfile(*solveQiFit(params), sampling.samples);
}

CurveProfile profileSphereTangent(const SphereTangentParams& params, const CurveSampling& sampling) {
  requireSampling("sphere-tangent", sampling);
  return sampleProfile(*solveSphereTangent(params), sampling.samples);
}

QiInterpolateParams exampleQiInterpolateParams() {
  QiInterpolateParams p;
  p.points.resize(7, 3);
  p.points << 0, 3, 0, 1, 2.8, 0.3, 1.8, 2.2, 0.9, 2.2, 1.3, 1.2, 2.0, 0.4, 1.0, 2.6, -0.3, 0.5, 3.6, -0.4, 0.2;
  p.options.endRule = EndTangentRule::Circle3;
  return p;
}

QiFitParams exampleQiFitParams() {
  // D-SINE-N, a synthetic stand-in for the data of Sakiyama et al. 2001, sec. 3.7: one period of 35
  // (x, sin x), uniform noise 0.5% of the length.
  QiFitParams p;
  p.points = Eigen::MatrixX3d::Zero(31, 3);
  std::mt19937 gen(12345);
  for (int i = 0; i <= 30; ++i) {
    const double x = 2.0 * M_PI * i / 30.0;
    p.points.row(i) << 35.0 * x, 35.0 * std::sin(x), 0.0;
    for (int c = 0; c < 2; ++c) {
      p.points(i, c) += 1.33706923 * (2.0 * (static_cast<double>(gen()) / 4294967296.0) - 1.0);
    }
  }
  p.breaks = {0, 6, 15, 24, 30};
  return p;
}

SphereTangentParams exampleSphereTangentParams() {
  SphereTangentParams p;
  p.segment.startPoint = Eigen::Vector3d::Zero();
  p.segment.startTangent = Eigen::Vector3d::UnitX();
  p.segment.endPoint = Eigen::Vector3d(1.0, 1.0, 1.0);
  p.segment.endTangent = Eigen::Vector3d::UnitZ();
  p.segment.degree = 2;
  return p;
}

}  // namespace ffdkit::geometry::quaternion
