// curve-network-surface: the surface interpolating a network of curves of Kuriyama 1996, ch. 5
// (docs/geometry-curvenet.md) as a scene generator.
#include "ffdkit/geometry/curvenet/curve_network_surface.h"
#include "ffdkit/geometry/curvenet/example_networks.h"
#include "generator_support.h"

namespace ffdkit::scenes::generators {
namespace {

namespace cn = geometry::curvenet;

/// The network: a named example network, or curves given as `points` split by `curve-sizes`
/// (closed curves listed by index in `closed-curves`).
cn::CurveNetworkDescription network(const GeneratorParameters& p) {
  const bool explicitCurves = p.has("points") || p.has("curve-sizes") || p.has("closed-curves");
  if (p.has("network")) {
    if (explicitCurves) throw GeneratorError("give either 'network' or 'points' + 'curve-sizes', not both");
    const std::string name = p.text("network", "");
    const auto names = cn::exampleNetworkNames();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      throw GeneratorError("parameter 'network': unknown network '" + name + "' (known: " + list + ")");
    }
    return cn::exampleNetwork(name);
  }
  if (!explicitCurves) throw GeneratorError("missing parameter 'network' (an example network) or 'points' + 'curve-sizes'");
  const Eigen::MatrixX3d points = p.rows("points", 3);
  if (!p.has("curve-sizes")) throw GeneratorError("missing parameter 'curve-sizes' (points per curve)");
  const std::vector<int> sizes = integers(p, "curve-sizes", 0, kMaxCount);
  cn::CurveNetworkDescription result;
  Eigen::Index start = 0;
  for (std::size_t c = 0; c < sizes.size(); ++c) {
    if (sizes[c] < 2)
      throw GeneratorError("parameter 'curve-sizes' entry " + std::to_string(c) + ": a curve needs >= 2 points, got " +
                           std::to_string(sizes[c]));
    if (start + sizes[c] > points.rows())
      throw GeneratorError("parameter 'curve-sizes': the sizes add up to more than the " + std::to_string(points.rows()) +
                           " points");
    cn::CurveDescription curve;
    curve.name = "curve " + std::to_string(c);
    curve.points = points.middleRows(start, sizes[c]);
    result.curves.push_back(std::move(curve));
    start += sizes[c];
  }
  if (start != points.rows())
    throw GeneratorError("parameter 'curve-sizes': the sizes add up to " + std::to_string(start) + ", but 'points' has " +
                         std::to_string(points.rows()) + " points");
  const std::vector<int> closed = integers(p, "closed-curves", 0, kMaxCount);
  for (std::size_t i = 0; i < closed.size(); ++i) {
    if (closed[i] < 0 || closed[i] >= static_cast<int>(result.curves.size()))
      throw GeneratorError("parameter 'closed-curves' entry " + std::to_string(i) + ": no curve " + std::to_string(closed[i]));
    result.curves[std::size_t(closed[i])].closed = true;
  }
  return result;
}

cn::CurveNetworkSurfaceParams surfaceParams(const GeneratorParameters& p) {
  cn::CurveNetworkSurfaceParams params;
  params.network = network(p);
  auto& o = params.networkOptions;
  o.intersectionTolerance = p.number("intersection-tolerance", o.intersectionTolerance);
  o.minimumCrossingAngleDegrees = p.number("minimum-crossing-angle", o.minimumCrossingAngleDegrees);
  o.straightAngleDegrees = p.number("straight-angle", o.straightAngleDegrees);
  o.orientationHint = vector3(p, "orientation-hint", o.orientationHint);
  o.fillOpenRegions = p.flag("fill-open-regions", o.fillOpenRegions);
  params.patch.blendingExponent = p.integer("blending-exponent", params.patch.blendingExponent, 1, kMaxDegree);
  params.fairing = p.flag("fairing", params.fairing);
  params.validate();
  return params;
}

int pitch(const GeneratorParameters& p, double density) { return scaledCount(p.integer("pitch", 8, 1, kMaxSamples), density, 1); }

/// pointBound: the network is built (cheap beside its tessellation); a face of N sides is an
/// N-gon lattice of 1 + N P (P + 1) / 2 points at pitch P, plus at most N P points where a
/// T-junction splits a side at its neighbour's samples.
std::uint64_t networkPointBound(const GeneratorParameters& p, double density) {
  const cn::CurveNetworkSurfaceParams params = surfaceParams(p);
  const std::uint64_t P = std::uint64_t(pitch(p, density));
  const cn::CurveNetwork network = cn::buildCurveNetwork(params.network, params.networkOptions);
  std::uint64_t total = 0;
  for (const cn::Face& face : network.faces) {
    const std::uint64_t N = face.sides.size();
    const std::uint64_t points = 1 + boundProduct(N, boundProduct(P, P + 1) / 2) + boundProduct(N, P);
    total = points > std::numeric_limits<std::uint64_t>::max() - total ? std::numeric_limits<std::uint64_t>::max() : total + points;
  }
  return total;
}

}  // namespace

void addCurvenetGenerators(GeneratorRegistry& registry) {
  registry.add({
      .name = "curve-network-surface",
      .summary = "surface interpolating a network of curves by multi-sided sweep patches (Kuriyama 1996, ch. 5)",
      .parameterNames = {"network", "points", "curve-sizes", "closed-curves", "intersection-tolerance",
                         "minimum-crossing-angle", "straight-angle", "orientation-hint", "fill-open-regions",
                         "blending-exponent", "fairing", "pitch"},
      .generate =
          [](const GeneratorParameters& p, double density) {
            return triangleMesh(cn::generateCurveNetworkSurface(surfaceParams(p), pitch(p, density)));
          },
      .profile = {},
      .pointBound = networkPointBound,
  });
}

}  // namespace ffdkit::scenes::generators
