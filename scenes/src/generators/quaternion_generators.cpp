// qi-interpolate, qi-fit, sphere-tangent: the quaternion curves of Miura 1998, Sakiyama et al. 2001 and the sphere-tangent report
// (docs/geometry-quaternion.md) as scene generators.
#include "ffdkit/geometry/quaternion/curve_generators.h"
#include "generator_support.h"

namespace ffdkit::scenes::generators {
namespace {

namespace q = geometry::quaternion;

const std::vector<std::pair<std::string, q::EndTangentRule>> kEndRules = {
    {"circle3", q::EndTangentRule::Circle3},
    {"natural-spline", q::EndTangentRule::NaturalSpline},
    {"user", q::EndTangentRule::User},
};
const std::vector<std::pair<std::string, q::StopMode>> kStopModes = {
    {"strict", q::StopMode::Strict},
    {"paper", q::StopMode::Paper},
};
const std::vector<std::pair<std::string, q::FitDimension>> kDimensions = {
    {"auto", q::FitDimension::Auto},
    {"planar", q::FitDimension::Planar},
    {"spatial", q::FitDimension::Spatial},
};
const std::vector<std::pair<std::string, q::StartTangentMode>> kStartModes = {
    {"from-initial-curve", q::StartTangentMode::FromInitialCurve},
    {"given", q::StartTangentMode::Given},
    {"free", q::StartTangentMode::Free},
};
const std::vector<std::pair<std::string, q::FitInitialCurve>> kInitialCurves = {
    {"least-squares-cubic", q::FitInitialCurve::LeastSquaresCubic},
    {"interpolating-cubic", q::FitInitialCurve::InterpolatingCubic},
};
const std::vector<std::pair<std::string, q::ProductForm>> kForms = {
    {"global", q::ProductForm::Global},
    {"local", q::ProductForm::Local},
};

q::CurveSampling quaternionSampling(const GeneratorParameters& p, double density) {
  return {scaledCount(p.integer("samples", q::CurveSampling{}.samples, 2, kMaxSamples), density, 2)};
}

// pointBound: the curve is sampled at exactly `samples` points (scaled by density).
std::uint64_t samplesBound(const GeneratorParameters& p, double density) { return std::uint64_t(quaternionSampling(p, density).samples); }

CurvatureProfile toProfile(const q::CurveProfile& profile) {
  return {profile.arcLength, profile.curvature, profile.torsion, profile.points, profile.normals};
}

q::QiInterpolateParams interpolateParams(const GeneratorParameters& p) {
  q::QiInterpolateParams params;
  params.points = points3(p, "points", 2);
  auto& o = params.options;
  o.endRule = choice(p, "end-rule", o.endRule, kEndRules);
  o.startTangent = vector3(p, "start-tangent", o.startTangent);
  o.endTangent = vector3(p, "end-tangent", o.endTangent);
  if (o.endRule == q::EndTangentRule::User && (!p.has("start-tangent") || !p.has("end-tangent")))
    throw GeneratorError("parameters 'start-tangent' and 'end-tangent' are required with end-rule 'user'");
  if (o.endRule != q::EndTangentRule::User && (p.has("start-tangent") || p.has("end-tangent")))
    throw GeneratorError("parameters 'start-tangent' and 'end-tangent' are used only with end-rule 'user'");
  o.stopMode = choice(p, "stop-mode", o.stopMode, kStopModes);
  o.maxIterations = p.integer("max-iterations", o.maxIterations, 1, kMaxIterations);
  return params;
}

q::QiFitParams fitParams(const GeneratorParameters& p) {
  q::QiFitParams params;
  params.points = points3(p, "points", 2);
  params.breaks = integers(p, "breaks", 0, kMaxCount);
  if (params.breaks.empty()) params.breaks = {0, static_cast<int>(params.points.rows()) - 1};
  auto& o = params.options;
  o.degree = p.integer("degree", o.degree, 1, kMaxDegree);
  o.dimension = choice(p, "dimension", o.dimension, kDimensions);
  o.form = choice(p, "form", o.form, kForms);
  o.startTangent = choice(p, "start-tangent-mode", o.startTangent, kStartModes);
  o.givenStartTangent = vector3(p, "start-tangent", o.givenStartTangent);
  if ((o.startTangent == q::StartTangentMode::Given) != p.has("start-tangent"))
    throw GeneratorError("parameter 'start-tangent' goes with start-tangent-mode 'given' (and is required by it)");
  o.initialCurve = choice(p, "initial-curve", o.initialCurve, kInitialCurves);
  o.maxIterations = p.integer("max-iterations", o.maxIterations, 1, kMaxIterations);
  return params;
}

q::SphereTangentParams sphereTangentParams(const GeneratorParameters& p) {
  q::SphereTangentParams params;
  auto& s = params.segment;
  s.startPoint = vector3(p, "start-point", s.startPoint);
  s.startTangent = vector3(p, "start-tangent", s.startTangent);
  s.endPoint = vector3(p, "end-point", s.endPoint);
  s.endTangent = vector3(p, "end-tangent", s.endTangent);
  s.degree = p.integer("degree", s.degree, 2, 3);
  if (auto v = optionalVector3(p, "second-control")) {
    if (s.degree != 3) throw GeneratorError("parameter 'second-control': only with degree 3");
    s.fixedSecondControl = *v;
  }
  params.options.multiStarts = p.integer("multi-starts", params.options.multiStarts, 1, 7);
  return params;
}

}  // namespace

void addQuaternionGenerators(GeneratorRegistry& registry) {
  registry.add({
      .name = "qi-interpolate",
      .summary = "G2 curve through points by quadratic quaternion-integral segments (Miura 1998)",
      .parameterNames = {"points", "end-rule", "start-tangent", "end-tangent", "stop-mode", "max-iterations", "samples"},
      .generate = [](const GeneratorParameters& p,
                     double density) { return polylineMesh(q::generateQiInterpolate(interpolateParams(p), quaternionSampling(p, density))); },
      .profile = [](const GeneratorParameters& p,
                    double density) { return toProfile(q::profileQiInterpolate(interpolateParams(p), quaternionSampling(p, density))); },
      .pointBound = samplesBound,
  });
  registry.add({
      .name = "qi-fit",
      .summary = "G1 chain of quaternion-integral segments fitted to (noisy) points (Sakiyama et al. 2001)",
      .parameterNames = {"points", "breaks", "degree", "dimension", "form", "start-tangent-mode", "start-tangent",
                         "initial-curve", "max-iterations", "samples"},
      .generate = [](const GeneratorParameters& p,
                     double density) { return polylineMesh(q::generateQiFit(fitParams(p), quaternionSampling(p, density))); },
      .profile = [](const GeneratorParameters& p,
                    double density) { return toProfile(q::profileQiFit(fitParams(p), quaternionSampling(p, density))); },
      .pointBound = samplesBound,
  });
  registry.add({
      .name = "sphere-tangent",
      .summary = "one tangent-integral segment between given end points and tangents (sphere-tangent report)",
      .parameterNames = {"start-point", "start-tangent", "end-point", "end-tangent", "degree", "second-control",
                         "multi-starts", "samples"},
      .generate = [](const GeneratorParameters& p,
                     double density) { return polylineMesh(q::generateSphereTangent(sphereTangentParams(p), quaternionSampling(p, density))); },
      .profile = [](const GeneratorParameters& p,
                    double density) { return toProfile(q::profileSphereTangent(sphereTangentParams(p), quaternionSampling(p, density))); },
      .pointBound = samplesBound,
  });
}

}  // namespace ffdkit::scenes::generators
