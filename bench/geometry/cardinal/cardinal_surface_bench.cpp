// Interpolating a grid of points and tessellating the surface (issue 9 benchmark). Each
// benchmark also reports, as a counter, the interpolation error at the grid points of the
// same input: a correctness check beside the timing.

#include <cmath>

#include <benchmark/benchmark.h>

#include "ffdkit/geometry/cardinal/s_spline_surface.h"
#include "ffdkit/geometry/cardinal/shape_points.h"
#include "ffdkit/geometry/cardinal/surface_tessellation.h"

namespace {

using namespace ffdkit::geometry::cardinal;

PointGrid wavyGrid(int n) {
  PointGrid g(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      g(i, j) = Eigen::Vector3d(i, j, 3.0 * std::sin(0.21 * i) * std::cos(0.17 * j) + 0.01 * i * j);
  return g;
}

template <class Surface>
double gridError(const Surface& s, const PointGrid& g) {
  double worst = 0.0;
  for (int i = 0; i < g.rows; ++i)
    for (int j = 0; j < g.cols; ++j) worst = std::max(worst, (s.evaluate(i, j) - g(i, j)).norm());
  return worst;
}

void BM_SigmaBicubicInterpolate(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const PointGrid g = wavyGrid(n);
  const SigmaKnots k = SigmaKnots::uniform(n - 1);
  for (auto _ : state) {
    SigmaSurfaceResult r = interpolateSigmaSurface(k, k, g);
    benchmark::DoNotOptimize(r.surface.Puv.data.data());
  }
  state.counters["maxGridError"] = gridError(interpolateSigmaSurface(k, k, g).surface, g);
}
BENCHMARK(BM_SigmaBicubicInterpolate)->ArgName("grid:NxN")->Arg(100)->Unit(benchmark::kMillisecond);

void BM_SigmaHeuristicInterpolate(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const PointGrid g = wavyGrid(n);
  const SigmaKnots k = SigmaKnots::uniform(n - 1);
  SigmaSurfaceOptions o;
  o.mode = ShapeMode::Heuristic;
  for (auto _ : state) {
    SigmaSurfaceResult r = interpolateSigmaSurface(k, k, g, o);
    benchmark::DoNotOptimize(r.surface.Puv.data.data());
  }
  state.counters["maxGridError"] = gridError(interpolateSigmaSurface(k, k, g, o).surface, g);
}
BENCHMARK(BM_SigmaHeuristicInterpolate)->ArgName("grid:NxN")->Arg(100)->Unit(benchmark::kMillisecond);

// Interpolation + tessellation with per-vertex normals, samples per span s x s.
void BM_SigmaBicubicInterpolateAndTessellate(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int samples = static_cast<int>(state.range(1));
  const PointGrid g = wavyGrid(n);
  const SigmaKnots k = SigmaKnots::uniform(n - 1);
  Eigen::Index vertices = 0;
  for (auto _ : state) {
    const SigmaSurface s = interpolateSigmaSurface(k, k, g).surface;
    SurfaceTessellation t = tessellate(s, {samples, samples});
    vertices = t.mesh.vertices.rows();
    benchmark::DoNotOptimize(t.normals.data());
  }
  state.counters["vertices"] = static_cast<double>(vertices);
}
BENCHMARK(BM_SigmaBicubicInterpolateAndTessellate)
    ->ArgNames({"grid:NxN", "samplesPerSpan"})
    ->Args({100, 4})
    ->Args({100, 8})
    ->Unit(benchmark::kMillisecond);

void BM_SSplineInterpolateAndTessellate(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int samples = static_cast<int>(state.range(1));
  const PointGrid g = wavyGrid(n);
  Eigen::Index vertices = 0;
  for (auto _ : state) {
    const SSplineSurface s(g);
    SurfaceTessellation t = tessellate(s, {samples, samples});
    vertices = t.mesh.vertices.rows();
    benchmark::DoNotOptimize(t.normals.data());
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["maxGridError"] = gridError(SSplineSurface(g), g);
}
BENCHMARK(BM_SSplineInterpolateAndTessellate)
    ->ArgNames({"grid:NxN", "samplesPerSpan"})
    ->Args({100, 4})
    ->Unit(benchmark::kMillisecond);

}  // namespace
