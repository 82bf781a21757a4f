#include "ffdkit/scenes/generator.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ffdkit/geometry/cardinal/generators.h"
#include "ffdkit/geometry/curvenet/example_networks.h"
#include "ffdkit/geometry/g3/g3_curve_generator.h"
#include "ffdkit/geometry/polyhedron/polyhedron_surface_generator.h"
#include "ffdkit/geometry/quaternion/curve_generators.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"
#include "scenes_test_support.h"

namespace ffdkit::scenes {
namespace {
using test_support::kExamples;
using test_support::fileText;

// Sample scene folder -> its one generated object's generator (one sample per generator).
const std::vector<std::pair<std::string, std::string>> kGeneratedSamples = {
    {"qi-interpolate", "qi-interpolate"},
    {"qi-fit", "qi-fit"},
    {"sphere-tangent", "sphere-tangent"},
    {"g3-curve", "g3-curve"},
    {"s-spline-curve", "s-spline-curve"},
    {"sigma-spline-curve", "sigma-spline-curve"},
    {"s-spline-surface", "s-spline-surface"},
    {"sigma-spline-surface", "sigma-spline-surface"},
    {"spline-blend", "spline-blend"},
    {"polyhedron-surface", "polyhedron-surface"},
    {"curve-network-surface", "curve-network-surface"},
};

bool isCurve(const std::string& generator) { return static_cast<bool>(builtinGenerators().get(generator).profile); }

// The generated source of a sample scene's only object.
GeneratedSource sampleSource(const std::string& folder) {
  const Scene scene = readScene(kExamples / folder);
  EXPECT_EQ(scene.objects().size(), 1u);
  return std::get<GeneratedSource>(scene.objects().front().source);
}

// Message of the GeneratorError that generating raises ("" if none).
std::string errorOf(const std::string& generator, const GeneratorParameters& parameters, double density = 1.0) {
  try {
    builtinGenerators().generate(generator, parameters, density);
  } catch (const GeneratorError& e) {
    return e.what();
  }
  return "";
}

double diagonal(const Eigen::MatrixX3d& points) {
  return (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
}

// Distance from p to the polyline's segments.
double distanceToPolyline(const Eigen::Vector3d& p, const MeshData& mesh) {
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index s = 0; s < mesh.segments.rows(); ++s) {
    const Eigen::Vector3d a = mesh.points.row(mesh.segments(s, 0));
    const Eigen::Vector3d b = mesh.points.row(mesh.segments(s, 1));
    const double t = std::clamp((p - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-300), 0.0, 1.0);
    best = std::min(best, (a + t * (b - a) - p).norm());
  }
  return best;
}

double distanceToNearestPoint(const Eigen::Vector3d& p, const Eigen::MatrixX3d& points) {
  return (points.rowwise() - p.transpose()).rowwise().norm().minCoeff();
}

// distanceToNearestPoint for many queries against one point set: the points sorted by their
// component along a unit direction u; a query walks outward from its own component and stops on
// each side where that difference alone reaches the best distance so far (|u.(q - p)| <= |q - p|;
// plus a margin far above the components' rounding), so the minimum is the brute force's, after a
// few points instead of all of them.
class NearestPoints {
 public:
  explicit NearestPoints(const Eigen::MatrixX3d& points)
      : points_(points), margin_(1e-12 * (points.size() ? points.cwiseAbs().maxCoeff() : 0.0)) {
    Eigen::VectorXd along(points.rows());
    for (Eigen::Index i = 0; i < points.rows(); ++i) along[i] = direction().dot(points.row(i).transpose());
    order_.resize(std::size_t(points.rows()));
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = Eigen::Index(i);
    std::sort(order_.begin(), order_.end(), [&](Eigen::Index a, Eigen::Index b) { return along[a] < along[b]; });
    keys_.resize(order_.size());
    for (std::size_t i = 0; i < order_.size(); ++i) keys_[i] = along[order_[i]];
  }
  double distance(const Eigen::Vector3d& p) const {
    const double key = direction().dot(p);
    const auto start = std::size_t(std::lower_bound(keys_.begin(), keys_.end(), key) - keys_.begin());
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = start; i < keys_.size() && keys_[i] - key - margin_ < best; ++i) best = std::min(best, at(i, p));
    for (std::size_t i = start; i > 0 && key - keys_[i - 1] - margin_ < best; --i) best = std::min(best, at(i - 1, p));
    return best;
  }

 private:
  static Eigen::Vector3d direction() { return Eigen::Vector3d(1.0, 0.7548776662, 0.5698402910).normalized(); }
  double at(std::size_t i, const Eigen::Vector3d& p) const { return (points_.row(order_[i]) - p.transpose()).norm(); }
  const Eigen::MatrixX3d& points_;
  double margin_;
  std::vector<Eigen::Index> order_;
  std::vector<double> keys_;
};

GeneratorParameters fig2dSetUp() {
  GeneratorParameters p;
  p.set("points", std::vector<std::vector<double>>{
                      {0.6, 10.5}, {4, 11.2}, {7.2, 7.9}, {10.6, 5.7}, {13.9, 8.9}, {16.3, 14}, {19.8, 17.4}, {23.3, 16.6}});
  p.set("curvatures", std::vector<std::vector<double>>{{0, 0}, {-1, 0}});
  p.set("total-length", 31.724017364);
  return p;
}

TEST(BuiltinGenerators, RegistersEveryGeneratorOfTheGeometryTopics) {
  std::vector<std::string> expected;
  for (const auto& [folder, generator] : kGeneratedSamples) expected.push_back(generator);
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(builtinGenerators().names(), expected);
  for (const auto& name : expected) {
    const Generator& g = builtinGenerators().get(name);
    EXPECT_FALSE(g.summary.empty()) << name;
    EXPECT_FALSE(g.parameterNames.empty()) << name;
  }
}

TEST(BuiltinGenerators, EverySampleParameterSetGeneratesAValidMesh) {
  for (const auto& [folder, generator] : kGeneratedSamples) {
    SCOPED_TRACE(folder);
    const GeneratedSource source = sampleSource(folder);
    ASSERT_EQ(source.generator, generator);
    const MeshData mesh = builtinGenerators().generate(generator, source.parameters, source.density);
    EXPECT_TRUE(mesh.points.allFinite());
    if (isCurve(generator)) {
      EXPECT_GE(mesh.points.rows(), 32);
      EXPECT_EQ(mesh.triangles.rows(), 0);
      EXPECT_FALSE(mesh.hasNormals);
      const bool closed = mesh.segments.rows() == mesh.points.rows();
      EXPECT_EQ(mesh.segments.rows(), mesh.points.rows() - (closed ? 0 : 1));
      for (Eigen::Index s = 0; s < mesh.segments.rows(); ++s)
        EXPECT_EQ(mesh.segments(s, 1), (mesh.segments(s, 0) + 1) % mesh.points.rows());
    } else {
      EXPECT_GE(mesh.triangles.rows(), 64);
      EXPECT_EQ(mesh.segments.rows(), 0);
      EXPECT_TRUE(mesh.hasNormals);
    }
  }
}

TEST(BuiltinGenerators, DefaultsOfTheTopicStructsApplyWhenParametersAreAbsent) {
  const MeshData segment = builtinGenerators().generate("sphere-tangent", {});
  EXPECT_EQ(segment.points.rows(), geometry::quaternion::CurveSampling{}.samples);
  EXPECT_LT((segment.points.row(segment.points.rows() - 1) - Eigen::RowVector3d(1, 1, 0)).norm(), 1e-6);
  const MeshData cube = builtinGenerators().generate("polyhedron-surface", {});
  const auto expected = geometry::polyhedron::generatePolyhedronSurface({});
  EXPECT_EQ(cube.points, expected.vertices);
  EXPECT_EQ(cube.triangles, expected.triangles);
  EXPECT_TRUE(cube.hasNormals);
}

TEST(BuiltinGenerators, MeshesEqualTheTopicsOwnGeneratorsWithDensityScalingTheSampling) {
  for (double density : {1.0, 2.0}) {
    SCOPED_TRACE(density);
    namespace q = geometry::quaternion;
    GeneratorParameters qi;
    qi.set("points", std::vector<std::vector<double>>{{0, 3, 0}, {1, 2.8, 0.3}, {1.8, 2.2, 0.9}, {2.2, 1.3, 1.2},
                                                      {2.0, 0.4, 1.0}, {2.6, -0.3, 0.5}, {3.6, -0.4, 0.2}});
    const MeshData curve = builtinGenerators().generate("qi-interpolate", qi, density);
    EXPECT_EQ(curve.points, q::generateQiInterpolate(q::exampleQiInterpolateParams(), {int(256 * density)}).points);

    const GeneratedSource g3 = sampleSource("g3-curve");
    geometry::g3::G3CurveParams g3Params;
    g3Params.points = {{0.6, 10.5}, {4, 11.2}, {7.2, 7.9}, {10.6, 5.7}, {13.9, 8.9}, {16.3, 14}, {19.8, 17.4}, {23.3, 16.6}};
    g3Params.conditions = {geometry::g3::Condition::tangentAngle(0, 0.546728),
                           geometry::g3::Condition::curvature(0, -0.10923218),
                           geometry::g3::Condition::curvature(geometry::g3::kLast, -0.16584946)};
    const MeshData g3Curve = builtinGenerators().generate("g3-curve", g3.parameters, density);
    const auto g3Expected = geometry::g3::generateG3Curve(g3Params, {int(32 * density)});
    ASSERT_EQ(g3Curve.points.rows(), g3Expected.points.rows());
    EXPECT_LT((g3Curve.points - g3Expected.points).cwiseAbs().maxCoeff(), 1e-9);

    namespace c = geometry::cardinal;
    c::SigmaSplineCurveParams sigma;
    sigma.points.resize(6, 3);
    sigma.points << 0, 0, 0, 1, 1, 0, 2, 0, 0, 3, 1, 0, 4, 0, 0, 6, 2, 0;
    const MeshData sigmaCurve = builtinGenerators().generate("sigma-spline-curve", sampleSource("sigma-spline-curve").parameters, density);
    EXPECT_EQ(sigmaCurve.points, c::generateSigmaSplineCurve(sigma, {int(32 * density)}).points);

    GeneratorParameters box;
    box.set("builtin-mesh", std::string("tetrahedron"));
    const MeshData tetrahedron = builtinGenerators().generate("polyhedron-surface", box, density);
    geometry::polyhedron::PolyhedronSurfaceParams tetraParams;
    tetraParams.builtinMesh = "tetrahedron";
    EXPECT_EQ(tetrahedron.points, geometry::polyhedron::generatePolyhedronSurface(tetraParams, {int(8 * density)}).vertices);
  }
}

TEST(BuiltinGenerators, DoubleDensityGivesMorePointsOnTheSameCurveOrSurface) {
  for (const auto& [folder, generator] : kGeneratedSamples) {
    SCOPED_TRACE(folder);
    const GeneratedSource source = sampleSource(folder);
    const MeshData coarse = builtinGenerators().generate(generator, source.parameters, 1.0);
    const MeshData fine = builtinGenerators().generate(generator, source.parameters, 2.0);
    EXPECT_GT(fine.points.rows(), coarse.points.rows());
    const double size = diagonal(coarse.points);
    EXPECT_LT(std::abs(diagonal(fine.points) - size), 1e-2 * size);
    double worst = 0.0;
    const NearestPoints finePoints(fine.points);
    for (Eigen::Index i = 0; i < coarse.points.rows(); ++i) {
      const Eigen::Vector3d p = coarse.points.row(i);
      // curves: every coarse sample lies on the fine polyline; surfaces: the fine sampling
      // refines the coarse one (2 sub-intervals per coarse one), so it holds every coarse vertex
      worst = std::max(worst, isCurve(generator) ? distanceToPolyline(p, fine) : finePoints.distance(p));
    }
    // curves: chord error of the fine polyline only (arc-length samples need not nest)
    EXPECT_LT(worst, (isCurve(generator) ? 1e-4 : 1e-9) * size);
    if (isCurve(generator)) {
      EXPECT_LT((coarse.points.row(0) - fine.points.row(0)).norm(), 1e-9 * size);
    }
  }
}

TEST(BuiltinGenerators, InterpolatingGeneratorsPassThroughTheirDataPoints) {
  for (const char* folder : {"qi-interpolate", "g3-curve", "s-spline-curve", "sigma-spline-curve"}) {
    SCOPED_TRACE(folder);
    const GeneratedSource source = sampleSource(folder);
    const MeshData curve = builtinGenerators().generate(source.generator, source.parameters);
    const auto& rows = std::get<std::vector<std::vector<double>>>(source.parameters.values().at("points"));
    for (const auto& row : rows) {
      const Eigen::Vector3d p(row[0], row[1], row.size() == 3 ? row[2] : 0.0);
      EXPECT_LT(distanceToPolyline(p, curve), 1e-4 * diagonal(curve.points));
    }
  }
  const GeneratedSource sheet = sampleSource("s-spline-surface");
  const MeshData surface = builtinGenerators().generate(sheet.generator, sheet.parameters);
  for (const auto& row : std::get<std::vector<std::vector<double>>>(sheet.parameters.values().at("points")))
    EXPECT_LT(distanceToNearestPoint(Eigen::Vector3d(row[0], row[1], row[2]), surface.points), 1e-9);
}

TEST(BuiltinGenerators, RefusesUnknownParameterNamesNamingThem) {
  GeneratorParameters p = sampleSource("qi-interpolate").parameters;
  p.set("sampels", 100.0);
  const std::string message = errorOf("qi-interpolate", p);
  EXPECT_NE(message.find("qi-interpolate"), std::string::npos) << message;
  EXPECT_NE(message.find("unknown parameter 'sampels'"), std::string::npos) << message;
  EXPECT_NE(message.find("samples"), std::string::npos) << "the known names are listed: " << message;
}

TEST(BuiltinGenerators, RefusesWrongTypesAndValuesNamingTheParameter) {
  struct Case {
    std::string generator;
    std::string name;
    ParameterValue value;
    std::string expected;  // a piece of the message
  };
  const std::vector<Case> cases = {
      {"qi-interpolate", "points", std::string("abc"), "parameter 'points': expected a list of rows"},
      {"qi-interpolate", "end-rule", std::string("circle4"), "parameter 'end-rule': unknown value 'circle4' (known: circle3"},
      {"qi-interpolate", "samples", 10.5, "parameter 'samples': expected an integer in [2, 100000000], got 10.5"},
      {"qi-interpolate", "samples", 1.0, "parameter 'samples': expected an integer in [2, 100000000], got 1.0"},
      {"qi-interpolate", "start-tangent", std::vector<double>{1, 0, 0}, "used only with end-rule 'user'"},
      {"qi-fit", "start-tangent", std::vector<double>{1, 0, 0}, "parameter 'start-tangent' goes with start-tangent-mode 'given'"},
      {"qi-fit", "start-tangent-mode", std::string("given"), "parameter 'start-tangent' goes with start-tangent-mode 'given'"},
      {"s-spline-curve", "end-tangent", std::vector<double>{1, 0, 0}, "used only with end 'tangent'"},
      {"sphere-tangent", "end-point", std::vector<double>{1, 2}, "parameter 'end-point': expected 3 numbers, got 2"},
      {"sphere-tangent", "degree", 4.0, "parameter 'degree': expected an integer in [2, 3], got 4.0"},
      {"g3-curve", "points", std::vector<std::vector<double>>{{0, 0, 0}, {1, 0, 0}}, "parameter 'points' row 0: expected 2 numbers"},
      {"g3-curve", "curvatures", std::vector<std::vector<double>>{{0.5, 1}}, "parameter 'curvatures' row 0: expected an integer in [-1, 100000000], got 0.5"},
      {"s-spline-surface", "columns", 7.0, "parameter 'points': 81 points do not fill rows of 'columns' = 7"},
      {"sigma-spline-surface", "closed-u", 1.0, "parameter 'closed-u': expected true or false"},
      {"spline-blend", "part", std::string("all"), "parameter 'part': unknown value 'all'"},
      {"polyhedron-surface", "builtin-mesh", std::string("dodecahedron"), "parameter 'builtin-mesh': unknown mesh 'dodecahedron'"},
      {"polyhedron-surface", "split-rule", true, "parameter 'split-rule': expected a string"},
      {"curve-network-surface", "network", std::string("spiderweb"), "parameter 'network': unknown network 'spiderweb'"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.generator + " " + c.name);
    const auto sample = std::find_if(kGeneratedSamples.begin(), kGeneratedSamples.end(),
                                     [&](const auto& s) { return s.second == c.generator; });
    GeneratorParameters p = sampleSource(sample->first).parameters;
    p.set(c.name, c.value);
    const std::string message = errorOf(c.generator, p);
    EXPECT_NE(message.find("generator '" + c.generator + "'"), std::string::npos) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
  }
}

TEST(BuiltinGenerators, RefusesParametersTheChosenOptionsWouldIgnore) {
  GeneratorParameters sigma = sampleSource("sigma-spline-curve").parameters;
  sigma.set("start-slope", std::vector<double>{1, 1, 0});
  EXPECT_EQ(errorOf("sigma-spline-curve", sigma), "");
  sigma.set("shape", std::string("midpoint"));
  EXPECT_NE(errorOf("sigma-spline-curve", sigma).find("'start-slope' and 'end-slope' are used only by open curves"),
            std::string::npos);
  GeneratorParameters cube;
  cube.set("resolution", std::vector<double>{8, 4});
  EXPECT_NE(errorOf("polyhedron-surface", cube).find("parameter 'resolution': only with builtin-mesh 'sphere' or 'torus'"),
            std::string::npos);
  cube.set("builtin-mesh", std::string("torus"));
  EXPECT_EQ(errorOf("polyhedron-surface", cube), "");
  GeneratorParameters quadratic;
  quadratic.set("second-control", std::vector<double>{0, 1, 0});
  EXPECT_NE(errorOf("sphere-tangent", quadratic).find("parameter 'second-control': only with degree 3"), std::string::npos);
}

TEST(BuiltinGenerators, RequiredParametersAreNamedWhenMissing) {
  EXPECT_NE(errorOf("qi-interpolate", {}).find("missing parameter 'points'"), std::string::npos);
  EXPECT_NE(errorOf("g3-curve", {}).find("missing parameter 'points'"), std::string::npos);
  GeneratorParameters grid;
  grid.set("points", std::vector<std::vector<double>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
  EXPECT_NE(errorOf("s-spline-surface", grid).find("missing parameter 'columns'"), std::string::npos);
  EXPECT_NE(errorOf("curve-network-surface", {}).find("missing parameter 'network'"), std::string::npos);
  GeneratorParameters faces;
  faces.set("vertices", std::vector<std::vector<double>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  EXPECT_NE(errorOf("polyhedron-surface", faces).find("missing parameter 'faces'"), std::string::npos);
}

TEST(BuiltinGenerators, ACurveNetworkCanBeGivenAsCurvesAndFaired) {
  // The height-grid network given curve by curve equals the named one.
  const auto named = geometry::curvenet::exampleNetwork("height-grid");
  std::vector<std::vector<double>> points;
  std::vector<double> sizes;
  for (const auto& curve : named.curves) {
    ASSERT_FALSE(curve.closed);
    sizes.push_back(static_cast<double>(curve.points.rows()));
    for (Eigen::Index r = 0; r < curve.points.rows(); ++r)
      points.push_back({curve.points(r, 0), curve.points(r, 1), curve.points(r, 2)});
  }
  GeneratorParameters byName, byCurves;
  byName.set("network", std::string("height-grid"));
  byCurves.set("points", points);
  byCurves.set("curve-sizes", sizes);
  const MeshData a = builtinGenerators().generate("curve-network-surface", byName);
  const MeshData b = builtinGenerators().generate("curve-network-surface", byCurves);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.triangles, b.triangles);
  byName.set("fairing", true);
  const MeshData faired = builtinGenerators().generate("curve-network-surface", byName);
  EXPECT_EQ(faired.triangles, a.triangles);
  EXPECT_TRUE(faired.points.allFinite());
  EXPECT_GT((faired.points - a.points).cwiseAbs().maxCoeff(), 1e-9) << "the flag reaches the topic";
  sizes.back() += 1;
  byCurves.set("curve-sizes", sizes);
  EXPECT_NE(errorOf("curve-network-surface", byCurves).find("parameter 'curve-sizes': the sizes add up to more than"),
            std::string::npos);
}

TEST(BuiltinGenerators, AnExplicitPolyhedronIsAccepted) {
  GeneratorParameters p;
  p.set("vertices", std::vector<std::vector<double>>{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}});
  p.set("faces", std::vector<std::vector<double>>{{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}});
  const MeshData mesh = builtinGenerators().generate("polyhedron-surface", p);
  EXPECT_GT(mesh.triangles.rows(), 4 * 64 - 1);
  p.set("faces", std::vector<std::vector<double>>{{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 9}});
  EXPECT_NE(errorOf("polyhedron-surface", p).find("parameter 'faces' row 3: vertex index 9 out of range"), std::string::npos);
}

TEST(BuiltinGenerators, AFailingSolveIsAnErrorNotAWrongMesh) {
  // Kuroda et al. 1997, Fig. 2(d): no curve with zero end curvatures is that short (docs/geometry-g3.md).
  const std::string g3 = errorOf("g3-curve", fig2dSetUp());
  EXPECT_NE(g3.find("generator 'g3-curve'"), std::string::npos) << g3;
  EXPECT_NE(g3.find("g3:"), std::string::npos) << "the solver's own message is kept: " << g3;
  EXPECT_THROW(builtinGenerators().profile("g3-curve", fig2dSetUp()), GeneratorError);
  // Two faces on four vertices: every vertex has valence 2, which the topic refuses.
  GeneratorParameters flat;
  flat.set("vertices", std::vector<std::vector<double>>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  flat.set("faces", std::vector<std::vector<double>>{{0, 1, 2, 3}, {3, 2, 1, 0}});
  const std::string polyhedron = errorOf("polyhedron-surface", flat);
  EXPECT_NE(polyhedron.find("generator 'polyhedron-surface'"), std::string::npos) << polyhedron;
  EXPECT_NE(polyhedron.find("valence 2"), std::string::npos) << polyhedron;
  // Sphere-tangent report, sec. 5: end conditions the quadratic tangent path cannot meet (docs/geometry-quaternion.md).
  GeneratorParameters unreachable;
  unreachable.set("end-point", std::vector<double>{1, 0.5, 0.5});
  unreachable.set("end-tangent", std::vector<double>{0, -1, 0});
  const std::string sphere = errorOf("sphere-tangent", unreachable);
  EXPECT_NE(sphere.find("generator 'sphere-tangent'"), std::string::npos) << sphere;
  EXPECT_NE(sphere.find("no curve meets the end conditions"), std::string::npos) << sphere;
}

TEST(BuiltinGenerators, AFailingGeneratorMakesTheSceneFileErrorNameObjectAndParameter) {
  const auto messageOf = [](const std::string& generatorObject) -> std::string {
    std::istringstream in(R"({"format": "ffdkit-scene", "version": 1, "objects": [{"name": "bad", "generator": )" +
                          generatorObject + "}]}");
    try {
      readScene(in, "scene.json");
    } catch (const SceneFileError& e) {
      return e.what();
    }
    return "";
  };
  const std::string infeasible = messageOf(
      R"({"name": "g3-curve", "parameters": {"points": [[0.6, 10.5], [4, 11.2], [7.2, 7.9], [10.6, 5.7], [13.9, 8.9],
          [16.3, 14], [19.8, 17.4], [23.3, 16.6]], "curvatures": [[0, 0], [-1, 0]], "total-length": 31.724017364}})");
  EXPECT_NE(infeasible.find("object 'bad'"), std::string::npos) << infeasible;
  EXPECT_NE(infeasible.find("generator 'g3-curve'"), std::string::npos) << infeasible;
  EXPECT_NE(infeasible.find("did not converge"), std::string::npos) << infeasible;
  const std::string typo = messageOf(R"({"name": "polyhedron-surface", "parameters": {"builtin_mesh": "cube"}})");
  EXPECT_NE(typo.find("object 'bad'"), std::string::npos) << typo;
  EXPECT_NE(typo.find("unknown parameter 'builtin_mesh'"), std::string::npos) << typo;
}

TEST(BuiltinGenerators, CurvesHaveCurvatureProfilesAndSurfacesDoNot) {
  for (const auto& [folder, generator] : kGeneratedSamples) {
    SCOPED_TRACE(folder);
    const GeneratedSource source = sampleSource(folder);
    if (!isCurve(generator)) {
      EXPECT_THROW(builtinGenerators().profile(generator, source.parameters), GeneratorError);
      continue;
    }
    const CurvatureProfile profile = builtinGenerators().profile(generator, source.parameters, source.density);
    const Eigen::Index n = profile.arcLength.size();
    ASSERT_GE(n, 32);
    EXPECT_EQ(profile.curvature.size(), n);
    EXPECT_EQ(profile.points.rows(), n);
    EXPECT_EQ(profile.normals.rows(), n);
    EXPECT_TRUE(profile.curvature.allFinite());
    EXPECT_DOUBLE_EQ(profile.arcLength(0), 0.0);
    for (Eigen::Index i = 1; i < n; ++i) EXPECT_GE(profile.arcLength(i), profile.arcLength(i - 1));
    if (generator == "g3-curve") {
      EXPECT_EQ(profile.torsion.size(), 0) << "planar: no torsion";
    } else {
      EXPECT_EQ(profile.torsion.size(), n);
    }
    // the profile samples the curve that is generated
    const MeshData mesh = builtinGenerators().generate(generator, source.parameters, source.density);
    double worst = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) worst = std::max(worst, distanceToPolyline(profile.points.row(i).transpose(), mesh));
    EXPECT_LT(worst, 1e-6 * diagonal(mesh.points));
  }
  for (double density : {0.0, -1.0, 100.0, std::numeric_limits<double>::quiet_NaN()})
    EXPECT_THROW(builtinGenerators().profile("sphere-tangent", {}, density), GeneratorError) << density;
  // the G3 curve of Fig. 2(c) starts with the curvature it was given
  const CurvatureProfile g3 = builtinGenerators().profile("g3-curve", sampleSource("g3-curve").parameters);
  EXPECT_NEAR(g3.curvature(0), -0.10923218, 1e-7);
  EXPECT_NEAR(g3.curvature(g3.curvature.size() - 1), -0.16584946, 1e-7);
  EXPECT_NEAR(g3.arcLength(g3.arcLength.size() - 1), 31.944481581, 1e-6);
}

TEST(BuiltinGenerators, ClothoidApproximationFollowsTheG3Curve) {
  // Kuroda et al. 1997, Fig. 5 (docs/geometry-g3.md): length about 74.6084 for both.
  const Scene scene = readScene(kExamples / "g3-clothoids");
  ASSERT_EQ(scene.objects().size(), 2u);
  std::vector<double> lengths;
  for (const auto& object : scene.objects()) {
    const auto& source = std::get<GeneratedSource>(object.source);
    const CurvatureProfile profile = builtinGenerators().profile(source.generator, source.parameters, source.density);
    lengths.push_back(profile.arcLength(profile.arcLength.size() - 1));
  }
  EXPECT_NEAR(lengths[0], 74.6084, 1e-3);
  EXPECT_NEAR(lengths[1], lengths[0], 1e-3 * lengths[0]);
}

TEST(BuiltinGenerators, EveryGeneratorHasAWorkingExampleInItsDocumentation) {
  // docs/generators.md: each generator's section ends with a ```json block holding the
  // "generator" object of a scene object; each must load and generate.
  const std::string doc = fileText(FFDKIT_SOURCE_DIR "/docs/generators.md");
  std::vector<std::string> documented;
  for (std::size_t at = doc.find("```json\n{\"name\": "); at != std::string::npos;
       at = doc.find("```json\n{\"name\": ", at + 1)) {
    const std::size_t begin = at + 8, end = doc.find("```", begin);
    ASSERT_NE(end, std::string::npos);
    const std::string generatorObject = doc.substr(begin, end - begin);
    std::istringstream in(R"({"format": "ffdkit-scene", "version": 1, "objects": [{"name": "example", "generator": )" +
                          generatorObject + "}]}");
    try {
      const Scene scene = readScene(in, "docs/generators.md");
      const auto& source = std::get<GeneratedSource>(scene.objects().at(0).source);
      documented.push_back(source.generator);
      EXPECT_GT(scene.objects()[0].mesh.points.rows(), 16) << source.generator;
    } catch (const std::exception& e) {
      ADD_FAILURE() << generatorObject << ": " << e.what();
    }
  }
  std::sort(documented.begin(), documented.end());
  EXPECT_EQ(documented, builtinGenerators().names());
}

TEST(BuiltinGenerators, EveryGeneratedSampleSceneLoadsDeformsAndRoundTrips) {
  std::vector<std::string> folders = {"g3-clothoids"};  // two objects, one lattice
  for (const auto& [folder, generator] : kGeneratedSamples) folders.push_back(folder);
  for (const auto& folder : folders) {
    SCOPED_TRACE(folder);
    const auto path = kExamples / folder / "scene.json";
    const Scene scene = readScene(path);
    EXPECT_FALSE(scene.description.empty());
    EXPECT_EQ(sceneFileText(scene), fileText(path));
    ASSERT_EQ(scene.attachments().size(), 1u);
    SceneDeformer deformer;
    deformer.update(scene);
    deformer.finishGesture(scene);
    EXPECT_EQ(deformer.lastStats().failedPoints, 0);
    for (const auto& object : scene.objects()) {
      const Eigen::MatrixX3d& points = deformer.points(object.name);
      EXPECT_TRUE(points.allFinite());
      EXPECT_GT((points - object.mesh.points).cwiseAbs().maxCoeff(), 1e-3 * diagonal(object.mesh.points))
          << "the sample should show a deformation";
    }
  }
}

}  // namespace
}  // namespace ffdkit::scenes
