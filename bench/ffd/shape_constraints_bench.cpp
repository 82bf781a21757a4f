// Constrained and guarded deformation: one Keep Volume drag step (a control point moved, then the
// least-norm control change that restores the enclosed volume to 1e-12, shape_constraints.h) on
// a closed UV sphere in a 4x4x4 cubic lattice; and the certified fold-over bound of an n x n x n
// cubic lattice (fold_check.h). BM_KeepVolumeDragStep evaluates the volume by its precomputed
// polynomial (a step costs O(lattice)); BM_KeepVolumeDragStepPerVertex deforms the points and sums
// over the triangles in every Newton step (O(vertices)); BM_KeepVolumePrecompute is keepVolume()
// building the polynomial (one pass over the vertices). BM_KeepCentreDragStep is the same drag with
// the centroid of the solid kept instead (keepCentroid: passes over the vertices and triangles in
// each Newton step, no precompute).
#include <cmath>
#include <random>

#include <benchmark/benchmark.h>

#include "ffdkit/ffd/fold_check.h"
#include "ffdkit/ffd/shape_constraints.h"

namespace {

using namespace ffdkit::ffd;

// A UV sphere of radius 0.35 about (0.5, 0.5, 0.5) with about `vertices` vertices (rings x 2 rings).
void sphere(Eigen::Index vertices, Eigen::MatrixX3d& points, TriangleMatrix& triangles) {
  const int rings = std::max(4, int(std::sqrt(double(vertices) / 2.0)));
  const int segments = 2 * rings;
  const int n = 2 + (rings - 1) * segments;
  points.resize(n, 3);
  const Eigen::RowVector3d centre(0.5, 0.5, 0.5);
  points.row(0) = centre + Eigen::RowVector3d(0, 0, 0.35);
  points.row(n - 1) = centre - Eigen::RowVector3d(0, 0, 0.35);
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double theta = M_PI * r / rings, phi = 2 * M_PI * s / segments;
      points.row(1 + (r - 1) * segments + s) =
          centre + 0.35 * Eigen::RowVector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
  const auto at = [segments](int ring, int s) { return 1 + (ring - 1) * segments + (s % segments); };
  triangles.resize(2 * segments * (rings - 1), 3);
  Eigen::Index t = 0;
  for (int s = 0; s < segments; ++s) triangles.row(t++) << 0, at(1, s), at(1, s + 1);
  for (int r = 1; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      triangles.row(t++) << at(r, s), at(r + 1, s), at(r + 1, s + 1);
      triangles.row(t++) << at(r, s), at(r + 1, s + 1), at(r, s + 1);
    }
  for (int s = 0; s < segments; ++s) triangles.row(t++) << n - 1, at(rings - 1, s + 1), at(rings - 1, s);
}

void keepVolumeDragStep(benchmark::State& state, VolumeEvaluation evaluation) {
  Eigen::MatrixX3d points;
  TriangleMatrix triangles;
  sphere(state.range(0), points, triangles);
  Lattice lattice = makeBoxLattice();  // 4x4x4 cubic on the unit box
  const ClosedSurface surface(triangles, points.rows());
  const double rest = enclosedVolume(points, surface);
  ShapeConstraints constraints(lattice, points);
  constraints.keepVolume(surface, rest, evaluation);
  int step = 0;
  double iterations = 0, worst = 0;
  for (auto _ : state) {
    // The drag: one corner-adjacent control point moves by 1% of the box, alternating direction.
    Eigen::MatrixX3d p = lattice.controlPoints();
    p.row(lattice.index(2, 1, 2)) += (step++ % 2 ? -0.01 : 0.01) * Eigen::RowVector3d(1.0, 0.5, -0.3);
    lattice.setControlPoints(p);
    const ShapeSolveResult result = constraints.solve(lattice);
    lattice.setControlPoints(lattice.controlPoints() + result.change);
    iterations += result.iterations;
    worst = std::max(worst, result.volumeRelativeError);
  }
  state.counters["newton_steps"] = iterations / double(state.iterations());
  state.counters["volume_error"] = worst;
  state.SetItemsProcessed(state.iterations() * points.rows());
}
void BM_KeepVolumeDragStep(benchmark::State& state) { keepVolumeDragStep(state, VolumeEvaluation::Polynomial); }
void BM_KeepVolumeDragStepPerVertex(benchmark::State& state) { keepVolumeDragStep(state, VolumeEvaluation::PerVertex); }
BENCHMARK(BM_KeepVolumeDragStep)->ArgName("vertices")->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KeepVolumeDragStepPerVertex)
    ->ArgName("vertices")
    ->Arg(10000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond);

// The drag of keepVolumeDragStep with the sphere's centroid kept: centroid_error is the largest
// relative residual |M - t V| / (|V| (size + |t - mean|)) after a step (ShapeSolveOptions::tolerance),
// jacobian_passes the passes over the vertices that computed the centroid's gradient. With the
// Jacobian of the first Newton step kept (JacobianUpdate::FirstStep, as the app's drags solve) and
// computed at every step (EveryStep: the Lagrange point).
void keepCentreDragStep(benchmark::State& state, JacobianUpdate jacobian) {
  Eigen::MatrixX3d points;
  TriangleMatrix triangles;
  sphere(state.range(0), points, triangles);
  Lattice lattice = makeBoxLattice();
  const ClosedSurface surface(triangles, points.rows());
  ShapeConstraints constraints(lattice, points);
  constraints.keepCentroid(surface, enclosedCentroid(points, surface));
  ShapeSolveOptions options;
  options.jacobian = jacobian;
  int step = 0;
  double iterations = 0, passes = 0, worst = 0;
  for (auto _ : state) {
    Eigen::MatrixX3d p = lattice.controlPoints();
    p.row(lattice.index(2, 1, 2)) += (step++ % 2 ? -0.01 : 0.01) * Eigen::RowVector3d(1.0, 0.5, -0.3);
    lattice.setControlPoints(p);
    const ShapeSolveResult result = constraints.solve(lattice, options);
    lattice.setControlPoints(lattice.controlPoints() + result.change);
    iterations += result.iterations;
    passes += result.jacobianPasses;
    worst = std::max(worst, result.largestRelativeResidual);
  }
  state.counters["newton_steps"] = iterations / double(state.iterations());
  state.counters["jacobian_passes"] = passes / double(state.iterations());
  state.counters["centroid_error"] = worst;
  state.SetItemsProcessed(state.iterations() * points.rows());
}
void BM_KeepCentreDragStep(benchmark::State& state) { keepCentreDragStep(state, JacobianUpdate::FirstStep); }
void BM_KeepCentreDragStepNewton(benchmark::State& state) { keepCentreDragStep(state, JacobianUpdate::EveryStep); }
BENCHMARK(BM_KeepCentreDragStep)->ArgName("vertices")->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KeepCentreDragStepNewton)
    ->ArgName("vertices")
    ->Arg(10000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond);

void BM_KeepVolumePrecompute(benchmark::State& state) {
  Eigen::MatrixX3d points;
  TriangleMatrix triangles;
  sphere(state.range(0), points, triangles);
  const Lattice lattice = makeBoxLattice();
  const ClosedSurface surface(triangles, points.rows());
  const double rest = enclosedVolume(points, surface);
  ShapeConstraints constraints(lattice, points);
  for (auto _ : state) constraints.keepVolume(surface, rest, VolumeEvaluation::Polynomial);
  state.SetItemsProcessed(state.iterations() * points.rows());
}
BENCHMARK(BM_KeepVolumePrecompute)->ArgName("vertices")->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

// A mildly bent n x n x n cubic B-spline lattice ((n-3)^3 cells). Rational: every weight drawn
// from [0.5, 2] (weights:random: every cell takes the bound of det[H_u, H_v, H_w, H], degree 11
// per axis, instead of det J's, degree 8), or one inner weight edited to 2 (weights:one: the 64
// cells whose window holds it; the others have equal weights and take det J's bound).
enum class Weights { None, Random, One };
void foldCheck(benchmark::State& state, Weights weights) {
  BoxLatticeOptions options;
  options.counts = Eigen::Vector3i::Constant(int(state.range(0)));
  Lattice lattice = makeBoxLattice(options);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::MatrixX3d p = lattice.controlPoints();
  for (Eigen::Index r = 0; r < p.rows(); ++r)
    for (int c = 0; c < 3; ++c) p(r, c) += 0.1 / (options.counts[c] - 1) * U(rng);  // mildly bent
  lattice.setControlPoints(p);
  if (weights == Weights::Random) {
    std::uniform_real_distribution<double> W(0.5, 2.0);
    Eigen::VectorXd w(lattice.pointCount());
    for (Eigen::Index i = 0; i < w.size(); ++i) w[i] = W(rng);
    lattice.setWeights(w);
  }
  const int middle = int(state.range(0)) / 2;
  if (weights == Weights::One) lattice.setWeight(lattice.index(middle, middle, middle), 2.0);
  Eigen::Index positive = 0;
  for (auto _ : state) positive = checkFolding(lattice).positiveCount;
  state.counters["cells"] = double(std::pow(state.range(0) - 3, 3));
  state.counters["certified"] = double(positive);
}
void BM_FoldCheck(benchmark::State& state) { foldCheck(state, Weights::None); }
BENCHMARK(BM_FoldCheck)->ArgName("lattice_n")->Arg(4)->Arg(6)->Arg(10)->Arg(13)->Arg(14)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(foldCheck, weights:random, Weights::Random)
    ->Name("BM_RationalFoldCheck/weights:random")->ArgName("lattice_n")->Arg(4)->Arg(13)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(foldCheck, weights:one, Weights::One)
    ->Name("BM_RationalFoldCheck/weights:one")->ArgName("lattice_n")->Arg(13)->Unit(benchmark::kMillisecond);

}  // namespace
