// glTF export of a 1M-vertex sphere in the default scene's 3x3x3 Bernstein lattice, animated by
// its arrow's variation scaled over [0, 1] (keys at 0, 0.5, 1; 8 frames per second: 9 samples):
//   BM_ExportGltf/content:frame/vertices:1000000   the deformed mesh at t = 1
//   BM_ExportGltf/content:morph/vertices:1000000   3 morph targets
//   BM_ExportGltf/content:skin/vertices:1000000    bind (embedding + weights), 9 sampled deformations
//                                                  each measured with k = 4 and 8 and all weights
// into memory (no disk). Beside the timing, each run checks the .glb header and the error
// bound (finite, and float32-small for frame / morph). Counters: error, MB written.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "ffdkit/exporters/gltf_export.h"
#include "ffdkit/scenes/primitive.h"
#include "ffdkit/scenes/scene_file.h"

namespace {

using namespace ffdkit;

scenes::Scene bigScene(int resolution) {
  scenes::Scene scene = scenes::readScene(std::filesystem::path(FFDKIT_SOURCE_DIR) / "scenes/examples/default");
  scenes::PrimitiveOptions sphere;
  sphere.resolution = resolution;
  const geometry::TriangleMesh mesh = scenes::makePrimitive(sphere);
  scenes::MeshData data = scene.objects().at(0).mesh;
  data.points = mesh.vertices;
  data.triangles = mesh.triangles;
  scene.setObjectMesh(scene.objects().at(0).name, std::move(data), sphere);
  return scene;
}

exporters::AnimationSource scaled(const scenes::Scene& scene) {
  const widgets::WidgetId pull = scene.widgets.find("pull");
  const double value = scene.widgets.variation(pull);
  exporters::AnimationSource source;
  source.keyTimes = {0.0, 0.5, 1.0};
  source.frameRate = 8.0;
  source.setTime = [pull, value](scenes::Scene& s, double t) { s.widgets.setVariation(pull, value * t); };
  return source;
}

void BM_ExportGltf(benchmark::State& state, exporters::GltfContent content) {
  const scenes::Scene scene = bigScene(static_cast<int>(state.range(0)));
  const exporters::AnimationSource animation = scaled(scene);
  exporters::GltfExportOptions options;
  options.content = content;
  options.time = 1.0;
  options.tolerance = 1e9;
  options.raiseJoints = false;
  exporters::GltfExportReport report;
  std::string bytes;
  for (auto _ : state) {
    std::ostringstream out(std::ios::binary);
    report = exporters::exportGltf(scene, animation, out, options);
    bytes = std::move(out).str();
    benchmark::DoNotOptimize(bytes.data());
  }
  if (bytes.size() < 12 || std::memcmp(bytes.data(), "glTF", 4) != 0) throw std::runtime_error("not a .glb");
  if (!std::isfinite(report.maxError)) throw std::runtime_error("non-finite error");
  if (content != exporters::GltfContent::Skin && report.maxError > 1e-6) throw std::runtime_error("float32 error too large");
  state.counters["vertices"] = static_cast<double>(report.vertices);
  state.counters["error"] = report.maxError;
  state.counters["MB"] = static_cast<double>(bytes.size()) / 1e6;
  state.counters["samples"] = static_cast<double>(report.samples.size());
}

// Resolution 1414: 998,302 vertices, 1,996,600 triangles.
BENCHMARK_CAPTURE(BM_ExportGltf, content:frame, exporters::GltfContent::Frame)
    ->Arg(1414)->ArgName("resolution")->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_ExportGltf, content:morph, exporters::GltfContent::Morph)
    ->Arg(1414)->ArgName("resolution")->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_ExportGltf, content:skin, exporters::GltfContent::Skin)
    ->Arg(1414)->ArgName("resolution")->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
