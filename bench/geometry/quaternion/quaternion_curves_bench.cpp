#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "ffdkit/geometry/quaternion/qi_fitting.h"
#include "ffdkit/geometry/quaternion/qi_interpolation.h"
#include "ffdkit/geometry/quaternion/sphere_tangent_fit.h"

namespace q = ffdkit::geometry::quaternion;

namespace {
Eigen::MatrixX3d sevenPoints() {
  Eigen::MatrixX3d p(7, 3);
  p << 0, 3, 0, 1, 2.8, 0.3, 1.8, 2.2, 0.9, 2.2, 1.3, 1.2, 2.0, 0.4, 1.0, 2.6, -0.3, 0.5, 3.6, -0.4, 0.2;
  return p;
}

// D-SPIRAL-N, a synthetic stand-in for the data of Sakiyama et al. 2001, sec. 3.7 (164 points,
// uniform noise 0.5% of the length, seed 164).
Eigen::MatrixX3d noisySpiral() {
  Eigen::MatrixX3d p(164, 3);
  std::mt19937 gen(164);
  for (int i = 0; i <= 163; ++i) {
    const double t = 3.0 * M_PI * i / 163.0;
    const double r = 50.0 - 3.0 * t;
    p.row(i) << r * std::cos(t), r * std::sin(t), 6.0 * t;
    for (int c = 0; c < 3; ++c) p(i, c) += 1.72066449 * (2.0 * (static_cast<double>(gen()) / 4294967296.0) - 1.0);
  }
  return p;
}
}  // namespace

// Miura 1998, Ex. 3 size: 7 points, 6 segments, Circle3 rule, strict stop.
static void BM_QiInterpolate_points_7(benchmark::State& state) {
  const Eigen::MatrixX3d p = sevenPoints();
  q::InterpolationOptions o;
  o.endRule = q::EndTangentRule::Circle3;
  const q::InterpolationResult check = q::interpolateQi(p, o);
  if (!check.converged) state.SkipWithError("7-point interpolation did not converge");
  for (auto _ : state) {
    benchmark::DoNotOptimize(q::interpolateQi(p, o));
  }
  state.counters["newton_iterations"] = check.iterations;
}
BENCHMARK(BM_QiInterpolate_points_7)->Unit(benchmark::kMillisecond);

// Sakiyama et al. 2001, Ex. (5) size: 164 noisy spiral points, 6 segments, 3D, default (LSQ-cubic)
// preset.
static void BM_QiFit_points_164_segments_6(benchmark::State& state) {
  const Eigen::MatrixX3d p = noisySpiral();
  const std::vector<int> breaks = {0, 27, 54, 82, 109, 136, 163};
  const q::FitResult check = q::fitQiChain(p, breaks);
  if (!check.converged || std::abs(check.rms - 1.6213) > 0.02) state.SkipWithError("spiral fit off its reference");
  for (auto _ : state) {
    benchmark::DoNotOptimize(q::fitQiChain(p, breaks));
  }
  state.counters["lm_iterations"] = check.iterations;
  state.counters["evaluations"] = check.functionEvaluations;
}
BENCHMARK(BM_QiFit_points_164_segments_6)->Unit(benchmark::kMillisecond);

// How the fit's cost grows: the same noisy conical spiral (1.5 turns, noise 0.5 % of its length)
// sampled with `points` points and cut into `segments` equal runs of points. Per LM iteration the
// work is one residual and one Jacobian sweep over the quadrature nodes (about 8 per data point plus
// 64 per segment) and the normal equations; the iteration count depends on the data.
static void BM_QiFitScaling(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int segments = static_cast<int>(state.range(1));
  Eigen::MatrixX3d p(n, 3);
  std::mt19937 gen(164);
  for (int i = 0; i < n; ++i) {
    const double t = 3.0 * M_PI * i / (n - 1);
    const double r = 50.0 - 3.0 * t;
    p.row(i) << r * std::cos(t), r * std::sin(t), 6.0 * t;
    for (int c = 0; c < 3; ++c) p(i, c) += 1.72066449 * (2.0 * (static_cast<double>(gen()) / 4294967296.0) - 1.0);
  }
  std::vector<int> breaks;
  for (int s = 0; s <= segments; ++s) breaks.push_back(static_cast<int>(std::lround(static_cast<double>(s) * (n - 1) / segments)));
  const q::FitResult check = q::fitQiChain(p, breaks);
  if (!(check.rms < check.initialRms)) state.SkipWithError("fit did not improve on its initial curve");
  for (auto _ : state) {
    benchmark::DoNotOptimize(q::fitQiChain(p, breaks));
  }
  state.counters["lm_iterations"] = check.iterations;
  state.counters["seconds_per_lm_iteration"] = benchmark::Counter(check.iterations, benchmark::Counter::kIsIterationInvariantRate |
                                                                                benchmark::Counter::kInvert);
  state.counters["rms"] = check.rms;
}
BENCHMARK(BM_QiFitScaling)
    ->ArgNames({"points", "segments"})
    ->ArgsProduct({{82, 164, 328}, {3, 6, 12}})
    ->Unit(benchmark::kMillisecond);

// Sphere-tangent report, Fig. 15 analogue: one quadratic end-condition optimisation.
static void BM_SphereTangentFit_degree_2(benchmark::State& state) {
  q::SphereTangentSegmentSpec spec;
  spec.endPoint = Eigen::Vector3d(1, 1, 1);
  spec.endTangent = Eigen::Vector3d::UnitZ();
  const q::SphereTangentFitResult check = q::fitSphereTangentSegment(spec);
  if (!check.converged) state.SkipWithError("O2 fit did not converge");
  for (auto _ : state) {
    benchmark::DoNotOptimize(q::fitSphereTangentSegment(spec));
  }
  state.counters["simplex_iterations"] = check.iterations;
  state.counters["evaluations"] = check.evaluations;
}
BENCHMARK(BM_SphereTangentFit_degree_2)->Unit(benchmark::kMillisecond);
