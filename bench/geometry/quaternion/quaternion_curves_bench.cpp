#include <benchmark/benchmark.h>

#include "ffdkit/geometry/quaternion/qi_interpolation.h"

namespace q = ffdkit::geometry::quaternion;

namespace {
Eigen::MatrixX3d sevenPoints() {
  Eigen::MatrixX3d p(7, 3);
  p << 0, 3, 0, 1, 2.8, 0.3, 1.8, 2.2, 0.9, 2.2, 1.3, 1.2, 2.0, 0.4, 1.0, 2.6, -0.3, 0.5, 3.6, -0.4, 0.2;
  return p;
}
}  // namespace

// Seed 000 Ex. 3 size: 7 points, 6 segments, Circle3 rule, strict stop.
static void BM_QiInterpolate_points_7(benchmark::State& state) {
  const Eigen::MatrixX3d p = sevenPoints();
  q::InterpolationOptions o;
  o.endRule = q::EndTangentRule::Circle3;
  const q::InterpolationResult check = q::interpolateQi(p, o);
  if (!check.converged) state.SkipWithError("7-point interpolation did not converge");
  for (auto _ : state) {
    benchmark::DoNotOptimize(q::interpolateQi(p, o));
  }
}
BENCHMARK(BM_QiInterpolate_points_7)->Unit(benchmark::kMillisecond);
