#include "ffdkit/geometry/cardinal/generators.h"

#include <algorithm>
#include <functional>
#include <string>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

namespace ffdkit::geometry::cardinal {
namespace {

void checkCurveSampling(const CurveSampling& sampling) {
  if (sampling.samplesPerSpan < 1) {
    throw CardinalSplineError("CurveSampling.samplesPerSpan must be >= 1, got " +
                              std::to_string(sampling.samplesPerSpan));
  }
}

void checkPoints(const Eigen::MatrixX3d& points, int minimum, const std::string& where) {
  if (points.rows() < minimum) {
    throw CardinalSplineError(where + ".points: expected >= " + std::to_string(minimum) +
                              " points, got " + std::to_string(points.rows()));
  }
  if (!points.allFinite()) throw CardinalSplineError(where + ".points: must be finite");
}

void checkGrid(const PointGrid& g, int minRows, int minCols, const std::string& where) {
  if (g.rows < minRows || g.cols < minCols ||
      static_cast<int>(g.data.size()) != g.rows * g.cols) {
    throw CardinalSplineError(where + ".points: expected a grid of >= " + std::to_string(minRows) +
                              " x " + std::to_string(minCols) + " points, got " +
                              std::to_string(g.rows) + " x " + std::to_string(g.cols) + " (" +
                              std::to_string(g.data.size()) + " stored)");
  }
  for (const auto& p : g.data) {
    if (!p.allFinite()) throw CardinalSplineError(where + ".points: must be finite");
  }
}

// Cumulative knots from interval widths; a zero width is a duplicate point.
Eigen::VectorXd knotsFromWidths(const Eigen::VectorXd& widths, const std::string& where) {
  Eigen::VectorXd t(widths.size() + 1);
  t[0] = 0.0;
  for (Eigen::Index i = 0; i < widths.size(); ++i) {
    if (!(widths[i] > 0.0)) {
      throw CardinalSplineError(where + ": chord-length knots need distinct consecutive points; "
                                "points " + std::to_string(i) + " and " + std::to_string(i + 1) +
                                " coincide");
    }
    t[i + 1] = t[i] + widths[i];
  }
  return t;
}

// Knots for `count` points along a direction whose k-th chord averages `chord(k)`.
template <class Chord>
SigmaKnots makeKnots(const Eigen::VectorXd& given, KnotSpacing spacing, const Eigen::VectorXd& beta2,
                     bool closed, int count, Chord chord, const std::string& where) {
  SigmaKnotsOptions o;
  o.closed = closed;
  const int intervals = closed ? count : count - 1;
  Eigen::VectorXd t;
  if (given.size() > 0) {
    if (given.size() != intervals + 1) {
      throw CardinalSplineError(where + ": expected " + std::to_string(intervals + 1) +
                                " knots for " + std::to_string(count) + (closed ? " closed" : " open") +
                                " points, got " + std::to_string(given.size()));
    }
    t = given;
  } else if (spacing == KnotSpacing::Uniform) {
    t = Eigen::VectorXd::LinSpaced(intervals + 1, 0.0, intervals);
  } else {
    Eigen::VectorXd widths(intervals);
    for (int k = 0; k < intervals; ++k) widths[k] = chord(k, (k + 1) % count);
    t = knotsFromWidths(widths, where);
  }
  return SigmaKnots(t, beta2, o);
}

Polyline sampleCurve(const std::function<Eigen::Vector3d(double)>& eval, double start, double end,
                     int spans, int perSpan, bool closed) {
  const int count = spans * perSpan + (closed ? 0 : 1);
  Polyline out;
  out.closed = closed;
  out.points.resize(count, 3);
  for (int k = 0; k < count; ++k) {
    out.points.row(k) = eval(start + (end - start) * k / (spans * perSpan)).transpose();
  }
  return out;
}

Eigen::VectorXd sampleParameters(const SigmaKnots& knots, int perSpan) {
  const int spans = knots.intervalCount();
  const int count = spans * perSpan + (knots.closed() ? 0 : 1);
  Eigen::VectorXd x(count);
  for (int k = 0; k < count; ++k) {
    const int span = std::min(k / perSpan, spans - 1);
    x[k] = knots.knot(span) + knots.delta(span) * static_cast<double>(k - span * perSpan) / perSpan;
  }
  return x;
}

}  // namespace

// ---- S-spline ------------------------------------------------------------------------------

void SSplineCurveParams::validate() const {
  checkPoints(points, options.end == SSplineEnd::Closed ? 3 : 2, "SSplineCurveParams");
  SSplineBasis(options.beta2, options.halfWidth, options.degree);  // throws on bad tension/width/degree
}

Polyline generateSSplineCurve(const SSplineCurveParams& params, const CurveSampling& sampling) {
  params.validate();
  checkCurveSampling(sampling);
  const SSplineCurve curve(params.points, params.options);
  const int spans = static_cast<int>(curve.parameterEnd());
  return sampleCurve([&](double x) { return curve.evaluate(x); }, 0.0, curve.parameterEnd(), spans,
                     sampling.samplesPerSpan, curve.closed());
}

CurvatureSamples sSplineCurveCurvature(const SSplineCurveParams& params,
                                       const CurveSampling& sampling) {
  params.validate();
  checkCurveSampling(sampling);
  const SSplineCurve curve(params.points, params.options);
  const int spans = static_cast<int>(curve.parameterEnd());
  const int count = spans * sampling.samplesPerSpan + 1;
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(count, 0.0, curve.parameterEnd());
  return sampleCurvature(
      [&](double y, int k) {
        return k == 0 ? curve.evaluate(y) : curve.evaluate(y, k, Limit::FromRight);
      },
      x);
}

void SSplineSurfaceParams::validate() const {
  checkGrid(points, options.closedU ? 3 : 2, options.closedV ? 3 : 2, "SSplineSurfaceParams");
  SSplineBasis(options.beta2U, options.halfWidthU, options.degreeU);
  SSplineBasis(options.beta2V, options.halfWidthV, options.degreeV);
}

TriangleMesh generateSSplineSurface(const SSplineSurfaceParams& params,
                                    const SurfaceSampling& sampling) {
  return generateSSplineSurfaceWithNormals(params, sampling).mesh;
}

SurfaceTessellation generateSSplineSurfaceWithNormals(const SSplineSurfaceParams& params,
                                                      const SurfaceSampling& sampling) {
  params.validate();
  return tessellate(SSplineSurface(params.points, params.options), sampling);
}

// ---- sigma-spline --------------------------------------------------------------------------

void SigmaSplineCurveParams::validate() const { buildSigmaCurve(*this); }

SigmaCurve buildSigmaCurve(const SigmaSplineCurveParams& params) {
  checkPoints(params.points, params.closed ? 3 : 2, "SigmaSplineCurveParams");
  const auto count = static_cast<int>(params.points.rows());
  const SigmaKnots knots = makeKnots(
      params.knots, params.spacing, params.beta2, params.closed, count,
      [&](int a, int b) { return (params.points.row(b) - params.points.row(a)).norm(); },
      "SigmaSplineCurveParams.knots");
  return interpolateSigmaCurve(knots, params.points, params.shape, params.endSlopes);
}

Polyline generateSigmaSplineCurve(const SigmaSplineCurveParams& params,
                                  const CurveSampling& sampling) {
  checkCurveSampling(sampling);
  const SigmaCurve curve = buildSigmaCurve(params);
  const Eigen::VectorXd x = sampleParameters(curve.knots(), sampling.samplesPerSpan);
  Polyline out;
  out.closed = curve.knots().closed();
  out.points.resize(x.size(), 3);
  for (Eigen::Index k = 0; k < x.size(); ++k) out.points.row(k) = curve.evaluate(x[k]).transpose();
  return out;
}

CurvatureSamples sigmaSplineCurveCurvature(const SigmaSplineCurveParams& params,
                                           const CurveSampling& sampling) {
  checkCurveSampling(sampling);
  const SigmaCurve curve = buildSigmaCurve(params);
  return sampleCurvature([&](double y, int k) { return curve.evaluate(y, k); },
                         sampleParameters(curve.knots(), sampling.samplesPerSpan));
}

void SigmaSplineSurfaceParams::validate() const { buildSigmaSurface(*this); }

SigmaSurface buildSigmaSurface(const SigmaSplineSurfaceParams& params) {
  const PointGrid& g = params.points;
  checkGrid(g, params.closedU ? 3 : 2, params.closedV ? 3 : 2, "SigmaSplineSurfaceParams");
  const SigmaKnots ku = makeKnots(
      params.knotsU, params.spacing, params.beta2U, params.closedU, g.rows,
      [&](int a, int b) {
        double sum = 0.0;
        for (int j = 0; j < g.cols; ++j) sum += (g(b, j) - g(a, j)).norm();
        return sum / g.cols;
      },
      "SigmaSplineSurfaceParams.knotsU");
  const SigmaKnots kv = makeKnots(
      params.knotsV, params.spacing, params.beta2V, params.closedV, g.cols,
      [&](int a, int b) {
        double sum = 0.0;
        for (int i = 0; i < g.rows; ++i) sum += (g(i, b) - g(i, a)).norm();
        return sum / g.rows;
      },
      "SigmaSplineSurfaceParams.knotsV");
  return interpolateSigmaSurface(ku, kv, g, params.shape).surface;
}

TriangleMesh generateSigmaSplineSurface(const SigmaSplineSurfaceParams& params,
                                        const SurfaceSampling& sampling) {
  return generateSigmaSplineSurfaceWithNormals(params, sampling).mesh;
}

SurfaceTessellation generateSigmaSplineSurfaceWithNormals(const SigmaSplineSurfaceParams& params,
                                                          const SurfaceSampling& sampling) {
  return tessellate(buildSigmaSurface(params), sampling);
}

// ---- blend ---------------------------------------------------------------------------------

void SplineBlendParams::validate() const { buildSplineBlend(*this); }

BlendResult buildSplineBlend(const SplineBlendParams& params) {
  return blendSurfaces(buildSigmaSurface(params.first), buildSigmaSurface(params.second),
                       params.blend);
}

TriangleMesh generateSplineBlend(const SplineBlendParams& params, const SurfaceSampling& sampling) {
  return generateSplineBlendWithNormals(params, sampling).mesh;
}

SurfaceTessellation generateSplineBlendWithNormals(const SplineBlendParams& params,
                                                   const SurfaceSampling& sampling) {
  const BlendResult r = buildSplineBlend(params);
  return tessellate(params.part == BlendPart::Composite ? r.composite : r.blend, sampling);
}

}  // namespace ffdkit::geometry::cardinal
