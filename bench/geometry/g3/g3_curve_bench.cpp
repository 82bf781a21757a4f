// Benchmarks of the G3 curve topic on the paper's data (seed 002 Appendix 2). Each benchmark
// checks its result once before timing (a wrong answer fast is no result).

#include <cmath>
#include <stdexcept>

#include <benchmark/benchmark.h>

#include "ffdkit/geometry/g3/clothoid_approximation.h"
#include "ffdkit/geometry/g3/cubic_spline_initial_guess.h"
#include "ffdkit/geometry/g3/g3_curve_solver.h"

namespace g3 = ffdkit::geometry::g3;

namespace {

Eigen::MatrixX2d rows(std::initializer_list<double> xy) {
  Eigen::MatrixX2d m(static_cast<Eigen::Index>(xy.size() / 2), 2);
  Eigen::Index k = 0;
  for (double value : xy) {
    m(k / 2, k % 2) = value;
    ++k;
  }
  return m;
}

// Fig. 3: 11 points, 10 spans (l.353); T4 conditions of the spec (square system).
Eigen::MatrixX2d figure3() {
  return rows({11.5, 6.4, 5.2, 2.6, 2, 1.6, 1.2, 5, 5.3, 4.7, 9.1, 1.3, 9.5, 2.9, 7, 5.7, 12.5, 5.7, 12.5, 3.7, 10.5, 3.2});
}
std::vector<g3::Condition> t4() {
  return {g3::Condition::curvature(0, 0.43212079), g3::Condition::curvature(g3::kLast, -0.40518471),
          g3::Condition::tangentAngle(0, 2.65)};
}
// Fig. 4: 21 points, 20 spans (l.354); T5 conditions.
Eigen::MatrixX2d figure4() {
  return rows({5.44,  14.16, 7.59,  15.88,  10.12, 16.9,   12.87, 16.86, 15.16, 15.34, 15.92, 12.69, 14.305,
               10.465, 11.55, 10.35, 9.35,  11.99, 7.86,   14.3,   5.615, 15.9,  3,     15.075, 1.55,  12.75,
               1.61,  10,    2.79,  7.5,    4.8,   5.61,   7.395,  4.66,  10.12, 5.035, 12.045, 7.03,  12.5,
               9.75,  12.3,  12.48});
}
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
  const Eigen::MatrixX2d p = figure3();
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
  const Eigen::MatrixX2d p = figure4();
  solveOrDie(p, t5(), 55.859545841);
  for (auto _ : state) {
    const g3::G3SolveResult r = g3::solveG3Curve(p, t5());
    benchmark::DoNotOptimize(r.unknowns.data());
  }
}
BENCHMARK(BM_SolveG3Curve_points21_spans20)->Unit(benchmark::kMicrosecond);

static void BM_CubicSplineInitialGuess_points11(benchmark::State& state) {
  const Eigen::MatrixX2d p = figure3();
  for (auto _ : state) benchmark::DoNotOptimize(g3::initialGuessFromCubicSpline(p).unknowns.data());
}
BENCHMARK(BM_CubicSplineInitialGuess_points11)->Unit(benchmark::kMicrosecond);

// Bi-clothoid (levels:1) and 4-clothoid (levels:2) approximation of the 10-span curve, without
// and with the sampled error measurement (512 samples per span).
static void BM_ClothoidApproximation_spans10(benchmark::State& state) {
  const g3::QuadraticCurvatureSpline curve = solveOrDie(figure3(), t4(), 43.763128326);
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
