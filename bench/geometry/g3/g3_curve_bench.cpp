// Benchmarks of the G3 curve topic on the paper's data (Kuroda et al. 1997, Appendix 2). Each
// benchmark checks its result once before timing (a wrong answer fast is no result).

#include <cmath>
#include <stdexcept>

#include <benchmark/benchmark.h>

#include "ffdkit/geometry/g3/clothoid_approximation.h"
#include "ffdkit/geometry/g3/cubic_spline_initial_guess.h"
#include "ffdkit/geometry/g3/g3_curve_solver.h"
#include "g3_test_data.h"

namespace g3 = ffdkit::geometry::g3;

namespace {

// Fig. 3 (11 points, 10 spans, app. 2) with the T4 conditions (square system); the
// points are the tests' own (g3_test_data), so the benchmark times what the tests check.
std::vector<g3::Condition> t4() {
  return {g3::Condition::curvature(0, 0.43212079), g3::Condition::curvature(g3::kLast, -0.40518471),
          g3::Condition::tangentAngle(0, 2.65)};
}
// Fig. 4 (21 points, 20 spans, app. 2) with the T5 conditions.
std::vector<g3::Condition> t5() {
  return {g3::Condition::curvature(0, -0.08229731), g3::Condition::curvature(g3::kLast, -0.06879707),
          g3::Condition::tangentAngle(0, 0.83)};
}

g3::QuadraticCurvatureSpline solveOrDie(const Eigen::MatrixX2d& p, const std::vector<g3::Condition>& c, double length) {
  const g3::G3SolveResult r = g3::solveG3Curve(p, c);
  if (!r.converged || std::abs(r.curve->length() - length) > 1e-7) throw std::runtime_error("g3 bench: wrong solve");
  return *r.curve;
}

}  // namespace

// The solve including the cubic-spline initial guess.
static void BM_SolveG3Curve_points11_spans10(benchmark::State& state) {
  const Eigen::MatrixX2d p = g3::testdata::figure3Points();
  solveOrDie(p, t4(), 43.763128326);
  int iterations = 0;
  for (auto _ : state) {
    const g3::G3SolveResult r = g3::solveG3Curve(p, t4());
    iterations = r.iterations;
    benchmark::DoNotOptimize(r.unknowns.data());
  }
  state.counters["newton_iterations"] = iterations;
}
BENCHMARK(BM_SolveG3Curve_points11_spans10)->Unit(benchmark::kMicrosecond);

static void BM_SolveG3Curve_points21_spans20(benchmark::State& state) {
  const Eigen::MatrixX2d p = g3::testdata::figure4Points();
  solveOrDie(p, t5(), 55.859545841);
  for (auto _ : state) {
    const g3::G3SolveResult r = g3::solveG3Curve(p, t5());
    benchmark::DoNotOptimize(r.unknowns.data());
  }
}
BENCHMARK(BM_SolveG3Curve_points21_spans20)->Unit(benchmark::kMicrosecond);

static void BM_CubicSplineInitialGuess_points11(benchmark::State& state) {
  const Eigen::MatrixX2d p = g3::testdata::figure3Points();
  for (auto _ : state) benchmark::DoNotOptimize(g3::initialGuessFromCubicSpline(p).unknowns.data());
}
BENCHMARK(BM_CubicSplineInitialGuess_points11)->Unit(benchmark::kMicrosecond);

// Bi-clothoid (levels:1) and 4-clothoid (levels:2) approximation of the 10-span curve, without
// and with the sampled error measurement (512 samples per span).
static void BM_ClothoidApproximation_spans10(benchmark::State& state) {
  const g3::QuadraticCurvatureSpline curve = solveOrDie(g3::testdata::figure3Points(), t4(), 43.763128326);
  g3::ClothoidApproximationOptions options;
  options.subdivisionLevels = static_cast<int>(state.range(0));
  options.measureErrors = state.range(1) != 0;
  if (!g3::approximateByClothoids(curve, options).converged) throw std::runtime_error("g3 bench: fit failed");
  for (auto _ : state) {
    const g3::ClothoidApproximation a = g3::approximateByClothoids(curve, options);
    benchmark::DoNotOptimize(a.arcs.data());
  }
}
BENCHMARK(BM_ClothoidApproximation_spans10)
    ->ArgNames({"levels", "errors"})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kMicrosecond);
