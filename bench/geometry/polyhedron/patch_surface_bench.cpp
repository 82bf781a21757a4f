// Building and tessellating the G1 surface of a 1,000-face polyhedron (issue 10): a 40 x 25
// quad torus (R = 2, r = 0.8), 4,000 rational quartic patches. The same input is checked for
// G1 in tests/geometry/polyhedron/patch_surface_test.cpp (ThousandFaceTorusIsG1).
#include <benchmark/benchmark.h>

#include "ffdkit/geometry/polyhedron/builtin_meshes.h"
#include "ffdkit/geometry/polyhedron/patch_surface.h"
#include "ffdkit/geometry/polyhedron/surface_tessellation.h"

namespace ffdkit::geometry::polyhedron {
namespace {

const PolygonMesh& thousandFaceTorus() {
  static const PolygonMesh mesh = torusMesh(40, 25);
  return mesh;
}

void BM_CurveNetwork(benchmark::State& state) {
  const PolygonMesh& mesh = thousandFaceTorus();
  const MeshTopology topology = validatePolygonMesh(mesh);
  const ResolvedTensions tensions = resolveTensions({}, topology);
  for (auto _ : state) benchmark::DoNotOptimize(solveCurveNetwork(mesh, topology, tensions));
}
BENCHMARK(BM_CurveNetwork)->Name("BM_CurveNetwork/faces:1000")->Unit(benchmark::kMillisecond);

void BM_BuildSurface(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(PatchSurface::build(thousandFaceTorus()));
}
BENCHMARK(BM_BuildSurface)->Name("BM_BuildSurface/faces:1000")->Unit(benchmark::kMillisecond);

void BM_Tessellate(benchmark::State& state) {
  const PatchSurface surface = PatchSurface::build(thousandFaceTorus());
  const int samples = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(tessellate(surface, samples));
}
BENCHMARK(BM_Tessellate)->Name("BM_Tessellate/faces:1000/samples")->Arg(4)->Arg(8)->Unit(benchmark::kMillisecond);

void BM_BuildAndTessellate(benchmark::State& state) {
  const int samples = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(tessellate(PatchSurface::build(thousandFaceTorus()), samples));
}
BENCHMARK(BM_BuildAndTessellate)->Name("BM_BuildAndTessellate/faces:1000/samples")->Arg(8)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ffdkit::geometry::polyhedron
