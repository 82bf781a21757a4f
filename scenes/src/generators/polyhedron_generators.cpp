// polyhedron-surface: the G1 triangular-patch surface over a polyhedron of Kuriyama 1996, ch. 4
// (docs/geometry-polyhedron.md) as a scene generator.
#include "ffdkit/geometry/polyhedron/builtin_meshes.h"
#include "ffdkit/geometry/polyhedron/polyhedron_surface_generator.h"
#include "generator_support.h"

namespace ffdkit::scenes::generators {
namespace {

namespace ph = geometry::polyhedron;

const std::vector<std::pair<std::string, ph::SplitLegRule>> kSplitRules = {
    {"thesis-face-based", ph::SplitLegRule::ThesisFaceBased},
    {"regular-vertex-based", ph::SplitLegRule::RegularVertexBased},
};
const std::vector<std::pair<std::string, ph::G1Scalars>> kScalars = {
    {"per-edge", ph::G1Scalars::PerEdge},
    {"thesis-constants", ph::G1Scalars::ThesisConstants},
};

/// "sphere" and "torus" take `resolution` [a, b]: segments x rings, around x tube.
std::pair<int, int> parametricResolution(const GeneratorParameters& p) {
  std::vector<int> resolution = integers(p, "resolution", 2, 1'000'000);
  if (resolution.empty()) resolution = {12, 6};
  if (resolution.size() != 2)
    throw GeneratorError("parameter 'resolution': expected 2 whole numbers, got " + std::to_string(resolution.size()));
  return {resolution[0], resolution[1]};
}

ph::PolygonMesh parametricMesh(const GeneratorParameters& p, const std::string& name) {
  const auto [a, b] = parametricResolution(p);
  return name == "sphere" ? ph::sphereMesh(a, b) : ph::torusMesh(a, b);
}

ph::PolygonMesh explicitMesh(const GeneratorParameters& p) {
  ph::PolygonMesh mesh;
  mesh.vertices = points3(p, "vertices", 4);
  if (!p.has("faces")) throw GeneratorError("missing parameter 'faces' (vertex index lists, one per face)");
  const auto faces = raggedRows(p, "faces");
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const std::string where = "parameter 'faces' row " + std::to_string(f);
    std::vector<int> face;
    for (double x : faces[f]) {
      const int index = wholeNumber(x, where, 0, kMaxCount);
      if (index < 0 || index >= mesh.vertices.rows())
        throw GeneratorError(where + ": vertex index " + std::to_string(index) + " out of range 0.." +
                             std::to_string(mesh.vertices.rows() - 1));
      face.push_back(index);
    }
    if (face.size() < 3) throw GeneratorError(where + ": a face needs >= 3 vertices, got " + std::to_string(face.size()));
    mesh.faces.push_back(std::move(face));
  }
  return mesh;
}

ph::PolyhedronSurfaceParams surfaceParams(const GeneratorParameters& p) {
  ph::PolyhedronSurfaceParams params;
  if (p.has("vertices") || p.has("faces")) {
    if (p.has("builtin-mesh")) throw GeneratorError("give either 'builtin-mesh' or 'vertices' + 'faces', not both");
    params.mesh = explicitMesh(p);
  } else {
    params.builtinMesh = p.text("builtin-mesh", params.builtinMesh);
    if (params.builtinMesh == "sphere" || params.builtinMesh == "torus") {
      params.mesh = parametricMesh(p, params.builtinMesh);
    } else {
      const auto names = ph::builtinMeshNames();
      if (std::find(names.begin(), names.end(), params.builtinMesh) == names.end()) {
        std::string list;
        for (const auto& n : names) list += n + ", ";
        throw GeneratorError("parameter 'builtin-mesh': unknown mesh '" + params.builtinMesh + "' (known: " + list +
                             "sphere, torus)");
      }
    }
  }
  const bool explicitPolyhedron = p.has("vertices") || p.has("faces");
  const bool parametric = !explicitPolyhedron && (params.builtinMesh == "sphere" || params.builtinMesh == "torus");
  if (p.has("resolution") && !parametric)
    throw GeneratorError("parameter 'resolution': only with builtin-mesh 'sphere' or 'torus'");

  auto& t = params.tensions;
  t.defaultAlpha = p.number("default-alpha", t.defaultAlpha);
  t.defaultBeta = p.number("default-beta", t.defaultBeta);
  const Eigen::MatrixXd alpha = p.rows("vertex-alpha", 2, false);
  for (Eigen::Index r = 0; r < alpha.rows(); ++r)
    t.vertexAlpha[wholeNumber(alpha(r, 0), "parameter 'vertex-alpha' row " + std::to_string(r), 0, kMaxCount)] = alpha(r, 1);
  const Eigen::MatrixXd beta = p.rows("edge-beta", 3, false);
  for (Eigen::Index r = 0; r < beta.rows(); ++r) {
    const std::string where = "parameter 'edge-beta' row " + std::to_string(r);
    t.edgeBeta[{wholeNumber(beta(r, 0), where, 0, kMaxCount), wholeNumber(beta(r, 1), where, 0, kMaxCount)}] = beta(r, 2);
  }
  params.splitRule = choice(p, "split-rule", params.splitRule, kSplitRules);
  params.g1Scalars = choice(p, "g1-scalars", params.g1Scalars, kScalars);
  return params;
}

int samplesPerPatchSide(const GeneratorParameters& p, double density) {
  return scaledCount(p.integer("samples-per-patch-side", ph::PolyhedronSurfaceSampling{}.samplesPerPatchSide, 1, kMaxSamples),
                     density, 1);
}

/// pointBound: one patch per corner of every face (a face of m sides splits into m triangles),
/// each sampled at (n + 1)(n + 2) / 2 points; a parametric sphere or torus is bounded from its
/// resolution before its polyhedron is built (a x b faces of at most 4 sides).
std::uint64_t patchPointBound(const GeneratorParameters& p, double density) {
  const bool explicitPolyhedron = p.has("vertices") || p.has("faces");
  const std::string builtin = p.text("builtin-mesh", ph::PolyhedronSurfaceParams{}.builtinMesh);
  std::uint64_t patches = 0;
  if (!explicitPolyhedron && (builtin == "sphere" || builtin == "torus")) {
    const auto [a, b] = parametricResolution(p);
    patches = boundProduct(4, boundProduct(std::uint64_t(a), std::uint64_t(b)));
  } else {
    const ph::PolygonMesh mesh = ph::resolvePolyhedron(surfaceParams(p));
    for (const auto& face : mesh.faces) patches += face.size();
  }
  const std::uint64_t n = std::uint64_t(samplesPerPatchSide(p, density));
  return boundProduct(patches, boundProduct(n + 1, n + 2) / 2);
}

}  // namespace

void addPolyhedronGenerators(GeneratorRegistry& registry) {
  registry.add({
      .name = "polyhedron-surface",
      .summary = "G1 surface of triangular patches over a polyhedron's curve network, with tensions (Kuriyama 1996, ch. 4)",
      .parameterNames = {"builtin-mesh", "resolution", "vertices", "faces", "default-alpha", "default-beta",
                         "vertex-alpha", "edge-beta", "split-rule", "g1-scalars", "samples-per-patch-side"},
      .generate =
          [](const GeneratorParameters& p, double density) {
            return triangleMesh(ph::generatePolyhedronSurface(surfaceParams(p), {samplesPerPatchSide(p, density)}));
          },
      .profile = {},
      .pointBound = patchPointBound,
  });
}

}  // namespace ffdkit::scenes::generators
