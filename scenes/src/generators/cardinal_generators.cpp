// s-spline-curve, sigma-spline-curve, s-spline-surface, sigma-spline-surface, spline-blend:
// the cardinal splines of Kuriyama 1996, ch. 3 (docs/geometry-cardinal.md) as scene generators.
#include "ffdkit/geometry/cardinal/generators.h"
#include "generator_support.h"

namespace ffdkit::scenes::generators {
namespace {

namespace c = geometry::cardinal;

const std::vector<std::pair<std::string, c::SSplineEnd>> kEnds = {
    {"open", c::SSplineEnd::Open},
    {"closed", c::SSplineEnd::Closed},
    {"tangent", c::SSplineEnd::Tangent},
};
const std::vector<std::pair<std::string, c::KnotSpacing>> kSpacings = {
    {"uniform", c::KnotSpacing::Uniform},
    {"chord-length", c::KnotSpacing::ChordLength},
};
const std::vector<std::pair<std::string, c::ShapeMode>> kShapes = {
    {"cubic", c::ShapeMode::Cubic},
    {"heuristic", c::ShapeMode::Heuristic},
    {"midpoint", c::ShapeMode::Midpoint},
};
const std::vector<std::pair<std::string, c::BlendPart>> kParts = {
    {"composite", c::BlendPart::Composite},
    {"blend-only", c::BlendPart::BlendOnly},
};

c::CurveSampling curveSampling(const GeneratorParameters& p, double density) {
  return {scaledCount(p.integer("samples-per-span", c::CurveSampling{}.samplesPerSpan, 1, kMaxSamples), density, 1)};
}

c::SurfaceSampling surfaceSampling(const GeneratorParameters& p, double density) {
  const c::SurfaceSampling base;
  return {scaledCount(p.integer("samples-per-span-u", base.samplesPerSpanU, 1, kMaxSamples), density, 1),
          scaledCount(p.integer("samples-per-span-v", base.samplesPerSpanV, 1, kMaxSamples), density, 1)};
}

CurvatureProfile toProfile(const c::CurvatureSamples& s) {
  return {s.arcLength, s.curvature, s.torsion, s.points, s.normals};
}

/// A grid given as `<prefix>points` (rows of 3, row-major: i along u outer, j along v inner)
/// and `<prefix>columns` (points per row).
c::PointGrid grid(const GeneratorParameters& p, const std::string& prefix) {
  const Eigen::MatrixX3d points = points3(p, prefix + "points", 4);
  const std::string columnsName = prefix + "columns";
  if (!p.has(columnsName)) throw GeneratorError("missing parameter '" + columnsName + "' (points per grid row)");
  const int columns = p.integer(columnsName, 0, 2, kMaxCount);
  if (points.rows() % columns != 0)
    throw GeneratorError("parameter '" + prefix + "points': " + std::to_string(points.rows()) +
                         " points do not fill rows of '" + columnsName + "' = " + std::to_string(columns));
  c::PointGrid result(static_cast<int>(points.rows()) / columns, columns);
  for (Eigen::Index r = 0; r < points.rows(); ++r) result.data[std::size_t(r)] = points.row(r).transpose();
  return result;
}

c::SSplineCurveParams sSplineCurve(const GeneratorParameters& p) {
  c::SSplineCurveParams params;
  params.points = points3(p, "points", 2);
  auto& o = params.options;
  o.beta2 = p.number("beta2", o.beta2);
  o.halfWidth = p.integer("half-width", o.halfWidth, 1, kMaxHalfWidth);
  o.end = choice(p, "end", o.end, kEnds);
  o.startTangent = vector3(p, "start-tangent", o.startTangent);
  o.endTangent = vector3(p, "end-tangent", o.endTangent);
  o.degree = p.integer("degree", o.degree, 1, kMaxDegree);
  o.clipped = p.flag("clipped", o.clipped);
  if (o.end != c::SSplineEnd::Tangent && (p.has("start-tangent") || p.has("end-tangent")))
    throw GeneratorError("parameters 'start-tangent' and 'end-tangent' are used only with end 'tangent'");
  params.validate();
  return params;
}

c::SigmaSplineCurveParams sigmaSplineCurve(const GeneratorParameters& p) {
  c::SigmaSplineCurveParams params;
  params.points = points3(p, "points", 2);
  params.knots = vectorX(p, "knots");
  params.spacing = choice(p, "spacing", params.spacing, kSpacings);
  params.beta2 = vectorX(p, "beta2");
  params.closed = p.flag("closed", params.closed);
  params.shape = choice(p, "shape", params.shape, kShapes);
  params.endSlopes.start = optionalVector3(p, "start-slope");
  params.endSlopes.end = optionalVector3(p, "end-slope");
  if ((params.closed || params.shape != c::ShapeMode::Cubic) && (p.has("start-slope") || p.has("end-slope")))
    throw GeneratorError("parameters 'start-slope' and 'end-slope' are used only by open curves with shape 'cubic'");
  params.validate();
  return params;
}

c::SSplineSurfaceParams sSplineSurface(const GeneratorParameters& p) {
  c::SSplineSurfaceParams params;
  params.points = grid(p, "");
  auto& o = params.options;
  o.beta2U = p.number("beta2-u", o.beta2U);
  o.beta2V = p.number("beta2-v", o.beta2V);
  o.halfWidthU = p.integer("half-width-u", o.halfWidthU, 1, kMaxHalfWidth);
  o.halfWidthV = p.integer("half-width-v", o.halfWidthV, 1, kMaxHalfWidth);
  o.degreeU = p.integer("degree-u", o.degreeU, 1, kMaxDegree);
  o.degreeV = p.integer("degree-v", o.degreeV, 1, kMaxDegree);
  o.closedU = p.flag("closed-u", o.closedU);
  o.closedV = p.flag("closed-v", o.closedV);
  params.validate();
  return params;
}

const std::vector<std::string> kSigmaSurfaceNames = {"points", "columns", "knots-u", "knots-v", "spacing", "beta2-u",
                                                     "beta2-v", "closed-u",  "closed-v", "shape"};

/// A sigma-spline surface from parameters named `<prefix><name>` for the names above.
c::SigmaSplineSurfaceParams sigmaSplineSurface(const GeneratorParameters& p, const std::string& prefix) {
  c::SigmaSplineSurfaceParams params;
  params.points = grid(p, prefix);
  params.knotsU = vectorX(p, prefix + "knots-u");
  params.knotsV = vectorX(p, prefix + "knots-v");
  params.spacing = choice(p, prefix + "spacing", params.spacing, kSpacings);
  params.beta2U = vectorX(p, prefix + "beta2-u");
  params.beta2V = vectorX(p, prefix + "beta2-v");
  params.closedU = p.flag(prefix + "closed-u", params.closedU);
  params.closedV = p.flag(prefix + "closed-v", params.closedV);
  params.shape.mode = choice(p, prefix + "shape", params.shape.mode, kShapes);
  params.validate();
  return params;
}

c::SplineBlendParams splineBlend(const GeneratorParameters& p) {
  c::SplineBlendParams params;
  params.first = sigmaSplineSurface(p, "first-");
  params.second = sigmaSplineSurface(p, "second-");
  if (p.has("gap-before")) params.blend.gapBefore = p.number("gap-before", 0.0);
  if (p.has("gap-after")) params.blend.gapAfter = p.number("gap-after", 0.0);
  if (auto beta = fixedNumbers(p, "junction-beta2", 3)) params.blend.junctionBeta2 = {(*beta)(0), (*beta)(1), (*beta)(2)};
  params.part = choice(p, "part", params.part, kParts);
  params.validate();
  return params;
}

// ---- point bounds (Generator::pointBound): a direction of n data points has at most n spans
// (n - 1 open, n closed), sampled at samples-per-span each.

std::uint64_t curveBound(const GeneratorParameters& p, double density) {
  return samplesAlong(std::uint64_t(p.rows("points", 3).rows()), curveSampling(p, density).samplesPerSpan);
}

// Rows (along u) and columns (along v) of the grid `<prefix>points`, without building it.
std::pair<std::uint64_t, std::uint64_t> gridShape(const GeneratorParameters& p, const std::string& prefix) {
  const c::PointGrid g = grid(p, prefix);
  return {std::uint64_t(g.rows), std::uint64_t(g.cols)};
}

std::uint64_t surfaceBound(const GeneratorParameters& p, double density) {
  const c::SurfaceSampling s = surfaceSampling(p, density);
  const auto [rows, columns] = gridShape(p, "");
  return boundProduct(samplesAlong(rows, s.samplesPerSpanU), samplesAlong(columns, s.samplesPerSpanV));
}

// The composite joins the two grids' columns with two blend spans between them.
std::uint64_t blendBound(const GeneratorParameters& p, double density) {
  const c::SurfaceSampling s = surfaceSampling(p, density);
  const auto [rows1, columns1] = gridShape(p, "first-");
  const auto [rows2, columns2] = gridShape(p, "second-");
  return boundProduct(samplesAlong(std::max(rows1, rows2), s.samplesPerSpanU), samplesAlong(columns1 + columns2 + 2, s.samplesPerSpanV));
}

std::vector<std::string> withPrefix(const std::string& prefix, const std::vector<std::string>& names) {
  std::vector<std::string> result;
  for (const auto& name : names) result.push_back(prefix + name);
  return result;
}

std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace

void addCardinalGenerators(GeneratorRegistry& registry) {
  registry.add({
      .name = "s-spline-curve",
      .summary = "interpolating S-spline curve with tension (Kuriyama 1996, eq. (3.9))",
      .parameterNames = {"points", "beta2", "half-width", "end", "start-tangent", "end-tangent", "degree", "clipped",
                         "samples-per-span"},
      .generate = [](const GeneratorParameters& p,
                     double density) { return polylineMesh(c::generateSSplineCurve(sSplineCurve(p), curveSampling(p, density))); },
      .profile = [](const GeneratorParameters& p,
                    double density) { return toProfile(c::sSplineCurveCurvature(sSplineCurve(p), curveSampling(p, density))); },
      .pointBound = curveBound,
  });
  registry.add({
      .name = "sigma-spline-curve",
      .summary = "interpolating sigma-spline curve on arbitrary knots with per-knot tension (Kuriyama 1996, ch. 3)",
      .parameterNames = {"points", "knots", "spacing", "beta2", "closed", "shape", "start-slope", "end-slope",
                         "samples-per-span"},
      .generate = [](const GeneratorParameters& p,
                     double density) { return polylineMesh(c::generateSigmaSplineCurve(sigmaSplineCurve(p), curveSampling(p, density))); },
      .profile = [](const GeneratorParameters& p,
                    double density) { return toProfile(c::sigmaSplineCurveCurvature(sigmaSplineCurve(p), curveSampling(p, density))); },
      .pointBound = curveBound,
  });
  registry.add({
      .name = "s-spline-surface",
      .summary = "tensor-product S-spline surface interpolating a point grid (Kuriyama 1996, eq. (3.11))",
      .parameterNames = {"points", "columns", "beta2-u", "beta2-v", "half-width-u", "half-width-v", "degree-u", "degree-v",
                         "closed-u", "closed-v", "samples-per-span-u", "samples-per-span-v"},
      .generate = [](const GeneratorParameters& p,
                     double density) { return triangleMesh(c::generateSSplineSurface(sSplineSurface(p), surfaceSampling(p, density))); },
      .profile = {},
      .pointBound = surfaceBound,
  });
  registry.add({
      .name = "sigma-spline-surface",
      .summary = "tensor-product sigma-spline surface interpolating a point grid (Kuriyama 1996, ch. 3)",
      .parameterNames = concat(kSigmaSurfaceNames, {"samples-per-span-u", "samples-per-span-v"}),
      .generate =
          [](const GeneratorParameters& p, double density) {
            return triangleMesh(c::generateSigmaSplineSurface(sigmaSplineSurface(p, ""), surfaceSampling(p, density)));
          },
      .profile = {},
      .pointBound = surfaceBound,
  });
  registry.add({
      .name = "spline-blend",
      .summary = "two sigma-spline surfaces joined by a C2 blend across v (Kuriyama 1996, Fig. 3-18)",
      .parameterNames = concat(concat(withPrefix("first-", kSigmaSurfaceNames), withPrefix("second-", kSigmaSurfaceNames)),
                               {"gap-before", "gap-after", "junction-beta2", "part", "samples-per-span-u",
                                "samples-per-span-v"}),
      .generate = [](const GeneratorParameters& p,
                     double density) { return triangleMesh(c::generateSplineBlend(splineBlend(p), surfaceSampling(p, density))); },
      .profile = {},
      .pointBound = blendBound,
  });
}

}  // namespace ffdkit::scenes::generators
