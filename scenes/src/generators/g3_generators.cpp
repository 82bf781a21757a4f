// g3-curve: the G3 curve of Kuroda et al. 1997 (quadratic curvature, optional clothoid approximation;
// docs/geometry-g3.md) as a scene generator.
#include <cmath>

#include "ffdkit/geometry/g3/g3_curve_generator.h"
#include "generator_support.h"

namespace ffdkit::scenes::generators {
namespace {

namespace g3 = geometry::g3;

/// A point index of a condition row: -1 means the last point (kLast).
int conditionIndex(double x, const std::string& where) {
  const int index = wholeNumber(x, where, -1, kMaxCount);
  return index == -1 ? g3::kLast : index;
}

/// Rows [index, value] of one condition kind.
void addIndexed(const GeneratorParameters& p, const std::string& name, std::vector<g3::Condition>& conditions,
                g3::Condition (*make)(int, double)) {
  const Eigen::MatrixXd rows = p.rows(name, 2, false);
  for (Eigen::Index r = 0; r < rows.rows(); ++r)
    conditions.push_back(make(conditionIndex(rows(r, 0), "parameter '" + name + "' row " + std::to_string(r)), rows(r, 1)));
}

g3::G3CurveParams curveParams(const GeneratorParameters& p) {
  g3::G3CurveParams params;
  const Eigen::MatrixXd points = p.rows("points", 2);
  if (points.rows() < 2)
    throw GeneratorError("parameter 'points': expected at least 2 points, got " + std::to_string(points.rows()));
  params.points.clear();
  for (Eigen::Index r = 0; r < points.rows(); ++r) params.points.emplace_back(points(r, 0), points(r, 1));

  std::vector<g3::Condition> conditions;
  addIndexed(p, "tangent-angles", conditions, &g3::Condition::tangentAngle);
  addIndexed(p, "curvatures", conditions, &g3::Condition::curvature);
  addIndexed(p, "radii-of-curvature", conditions, &g3::Condition::radiusOfCurvature);
  const std::vector<int> clothoids = integers(p, "clothoid-spans", -1, kMaxCount);
  for (std::size_t i = 0; i < clothoids.size(); ++i)
    conditions.push_back(g3::Condition::clothoidSpan(conditionIndex(clothoids[i], "parameter 'clothoid-spans' entry " + std::to_string(i))));
  const std::vector<int> arcs = integers(p, "circular-arc-spans", -1, kMaxCount);
  for (std::size_t i = 0; i < arcs.size(); ++i)
    conditions.push_back(g3::Condition::circularArcSpan(conditionIndex(arcs[i], "parameter 'circular-arc-spans' entry " + std::to_string(i))));
  if (p.has("total-length")) conditions.push_back(g3::Condition::totalLength(p.number("total-length", 0.0)));
  const Eigen::MatrixXd lengths = p.rows("span-lengths", 3, false);
  for (Eigen::Index r = 0; r < lengths.rows(); ++r) {
    const std::string where = "parameter 'span-lengths' row " + std::to_string(r);
    conditions.push_back(g3::Condition::partialLength(conditionIndex(lengths(r, 0), where), conditionIndex(lengths(r, 1), where),
                                                      lengths(r, 2)));
  }
  // The struct's default (natural ends) applies when no other condition is given.
  if (p.flag("natural-ends", conditions.empty())) conditions.insert(conditions.begin(), g3::Condition::naturalEnds());
  params.conditions = std::move(conditions);

  params.clothoidLevels = p.integer("clothoid-levels", params.clothoidLevels, 0, 8);
  params.z = p.number("z", params.z);
  params.solver.allowOverdetermined = p.flag("allow-overdetermined", params.solver.allowOverdetermined);
  params.solver.maxIterations = p.integer("max-iterations", params.solver.maxIterations, 1, kMaxIterations);
  return params;
}

g3::G3CurveSampling g3Sampling(const GeneratorParameters& p, double density) {
  return {scaledCount(p.integer("samples-per-span", g3::G3CurveSampling{}.samplesPerSpan, 1, kMaxSamples), density, 2)};
}

/// pointBound: at most one span per point, samples-per-span each; the clothoid output has 2^k
/// arcs per span of max(2, samples-per-span / 2^k) samples each.
std::uint64_t g3PointBound(const GeneratorParameters& p, double density) {
  const std::uint64_t spans = std::uint64_t(p.rows("points", 2).rows());
  const int perSpan = g3Sampling(p, density).samplesPerSpan;
  const int levels = p.integer("clothoid-levels", g3::G3CurveParams{}.clothoidLevels, 0, 8);
  if (levels == 0) return samplesAlong(spans, perSpan);
  return samplesAlong(boundProduct(spans, std::uint64_t(1) << levels), std::max(2, perSpan >> levels));
}

/// Planar profile: signed curvature, no torsion, normal (-sin psi, cos psi) in the plane z.
CurvatureProfile profile(const GeneratorParameters& p, double density) {
  const g3::G3CurveParams params = curveParams(p);
  const g3::CurveSamples samples = g3::sampleG3Curve(params, g3Sampling(p, density));
  const Eigen::Index n = samples.arcLength.size();
  CurvatureProfile result;
  result.arcLength = samples.arcLength;
  result.curvature = samples.curvature;
  result.points.resize(n, 3);
  result.normals.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    result.points.row(i) << samples.points(i, 0), samples.points(i, 1), params.z;
    result.normals.row(i) << -std::sin(samples.tangentAngle(i)), std::cos(samples.tangentAngle(i)), 0.0;
  }
  return result;
}

}  // namespace

void addG3Generators(GeneratorRegistry& registry) {
  registry.add({
      .name = "g3-curve",
      .summary = "planar G3 curve with piecewise quadratic curvature through points, or its clothoid approximation (Kuroda et al. 1997)",
      .parameterNames = {"points", "natural-ends", "tangent-angles", "curvatures", "radii-of-curvature", "clothoid-spans",
                         "circular-arc-spans", "total-length", "span-lengths", "clothoid-levels", "z",
                         "allow-overdetermined", "max-iterations", "samples-per-span"},
      .generate = [](const GeneratorParameters& p,
                     double density) { return polylineMesh(g3::generateG3Curve(curveParams(p), g3Sampling(p, density))); },
      .profile = profile,
      .pointBound = g3PointBound,
  });
}

}  // namespace ffdkit::scenes::generators
