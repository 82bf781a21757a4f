#include <benchmark/benchmark.h>

#include "ffdkit/geometry/curvenet/curve_network_surface.h"
#include "ffdkit/geometry/curvenet/example_networks.h"

namespace {
using namespace ffdkit::geometry::curvenet;

// 25 + 25 curves on the prototype height field: 576 quads.
void BM_BuildAndTessellate(benchmark::State& state) {
  CurveNetworkSurfaceParams params;
  params.network = heightGridNetwork(static_cast<int>(state.range(0)) / 2);
  const int pitch = static_cast<int>(state.range(1));
  for (auto _ : state) {
    const NetworkMesh mesh = generateCurveNetworkSurfaceWithNormals(params, pitch);
    benchmark::DoNotOptimize(mesh.mesh.vertices.data());
  }
}
BENCHMARK(BM_BuildAndTessellate)->ArgNames({"curves", "pitch"})->Args({50, 4})->Args({50, 8})->Unit(benchmark::kMillisecond);

void BM_BuildNetwork(benchmark::State& state) {
  const CurveNetworkDescription d = heightGridNetwork(static_cast<int>(state.range(0)) / 2);
  for (auto _ : state) {
    const CurveNetwork net = buildCurveNetwork(d);
    benchmark::DoNotOptimize(net.faces.data());
  }
}
BENCHMARK(BM_BuildNetwork)->ArgNames({"curves"})->Arg(50)->Unit(benchmark::kMillisecond);

}  // namespace
