// Fuzz target: the scene-file reader (objects, primitives, generators, widgets, attachments,
// animation) and the evaluation of what it read at the ends of the frame range and at its first
// keys. What matters here is every path through the reader and the scene, at over a thousand
// inputs a second, not how a big scene deforms, so one input is kept cheap:
// - the read has a small budget (SceneReadOptions::limits): a primitive, mesh, generator or
//   lattice that a few bytes make big is refused before it is computed;
// - generators are stand-ins: each builtin generator's name, parameter names and point bound,
//   but a small curve or surface instead of its solve or fit (a sphere-tangent or curve-network
//   solve takes up to a second under ASan and coverage). fuzz_generator runs the real ones.
// Mesh paths resolve against a folder that does not exist, under the default confinement rule,
// so no file outside the input is read.
#include <algorithm>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/generator.h"
#include "ffdkit/scenes/scene_file.h"

namespace {

// The keys evaluated per input: a scene with thousands of keys costs no more than one with eight.
constexpr std::size_t kKeysEvaluated = 8;

// A polyline of `n` points (a curve generator's stand-in) or a strip of 2 x `n` points (a surface's).
ffdkit::meshio::MeshData standIn(bool curve, int n) {
  ffdkit::meshio::MeshData mesh;
  const int rows = curve ? 1 : 2;
  mesh.points.resize(rows * n, 3);
  for (int r = 0; r < rows; ++r)
    for (int i = 0; i < n; ++i) mesh.points.row(r * n + i) << 0.1 * i, 0.05 * i * i, 0.3 * r;
  if (curve) {
    mesh.segments.resize(n - 1, 2);
    for (int i = 0; i + 1 < n; ++i) mesh.segments.row(i) << i, i + 1;
  } else {
    mesh.triangles.resize(2 * (n - 1), 3);
    for (int i = 0; i + 1 < n; ++i) {
      mesh.triangles.row(2 * i) << i, i + 1, n + i;
      mesh.triangles.row(2 * i + 1) << i + 1, n + i + 1, n + i;
    }
  }
  return mesh;
}

const ffdkit::scenes::GeneratorRegistry& standInGenerators() {
  static const ffdkit::scenes::GeneratorRegistry registry = [] {
    ffdkit::scenes::GeneratorRegistry result;
    const auto& builtin = ffdkit::scenes::builtinGenerators();
    for (const std::string& name : builtin.names()) {
      ffdkit::scenes::Generator generator = builtin.get(name);
      const bool curve = bool(generator.profile);
      // The reader has charged the real pointBound already (a curve network's builds the network:
      // a tenth of the target's time in perf); the stand-in does not compute it again.
      generator.generate = [curve](const ffdkit::scenes::GeneratorParameters&, double) { return standIn(curve, 8); };
      result.add(std::move(generator));
    }
    return result;
  }();
  return registry;
}

ffdkit::scenes::SceneReadOptions smallRead() {
  ffdkit::scenes::SceneReadOptions options;
  options.baseDirectory = "/nonexistent-ffdkit-fuzz-folder";
  options.generators = &standInGenerators();
  // A scene's points (primitives, generated samples, lattice control points together) and bytes:
  // small, so that an input that asks for a big sphere or lattice is refused at once instead of
  // being built and animated under ASan. Most sample scenes read within these; the larger ones
  // (a 48-step sphere or torus, the spline surfaces) still exercise every path up to the refusal,
  // and fuzz_generator runs the generators with their real sizes.
  options.limits.maxPoints = 1'500;
  options.limits.maxMemoryBytes = 256u << 10;
  return options;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ffdkit::scenes::SceneReadOptions options = smallRead();
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    ffdkit::scenes::Scene scene = ffdkit::scenes::readScene(in, "fuzz", options);
    ffdkit::scenes::applyAnimationFrame(scene, scene.animation().firstFrame);
    const std::vector<double> keys = ffdkit::scenes::keyTimes(scene);
    for (std::size_t k = 0; k < std::min(keys.size(), kKeysEvaluated); ++k) ffdkit::scenes::applyAnimation(scene, keys[k]);
    ffdkit::scenes::applyAnimationFrame(scene, scene.animation().lastFrame);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
