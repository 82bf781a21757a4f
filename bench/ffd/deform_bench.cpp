// FFD engine benchmarks (issue 3). Names carry their sizes so results compare across commits.
// Run: bench_ffd --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// Each benchmark checks its result against the reference path once before timing.
// Time = wall clock; CPU = process CPU time summed over all threads (on a busy shared machine,
// CPU / threads estimates the wall time the same work takes on an idle one).

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <string>

#include <benchmark/benchmark.h>

#include "ffdkit/ffd/cylindrical_lattice.h"
#include "ffdkit/ffd/deformer.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"

using namespace ffdkit::ffd;

namespace {

Lattice boxLattice(int count, AxisBasis basis) {
  BoxLatticeOptions options;
  options.counts = {count, count, count};
  options.bases = {basis, basis, basis};
  return makeBoxLattice(options);
}

// Uniform random points in the unit box, in random order (the worst case for the cell grouping).
Eigen::MatrixX3d randomPoints(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Eigen::MatrixX3d Q(n, 3);
  for (Eigen::Index r = 0; r < n; ++r) Q.row(r) << U(rng), U(rng), U(rng);
  return Q;
}

// Points on a regular 100 x 100 x 100 grid in x-fastest order: the spatially coherent order of a
// real mesh or volume, for comparison with the random order above.
Eigen::MatrixX3d gridPoints(Eigen::Index n) {
  const Eigen::Index side = static_cast<Eigen::Index>(std::llround(std::cbrt(double(n))));
  Eigen::MatrixX3d Q(side * side * side, 3);
  for (Eigen::Index r = 0; r < Q.rows(); ++r) {
    Q.row(r) << (r % side + 0.5) / side, ((r / side) % side + 0.5) / side, (r / (side * side) + 0.5) / side;
  }
  return Q;
}

Eigen::MatrixX3d moved(const Lattice& lattice, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-0.1, 0.1);
  Eigen::MatrixX3d P = lattice.controlPoints();
  for (Eigen::Index r = 0; r < P.rows(); ++r)
    for (int c = 0; c < 3; ++c) P(r, c) += U(rng);
  return P;
}

// Spot check of the fast path against Lattice::evaluate (eq. (6.1) from scratch).
void check(const Lattice& lattice, const Deformer& deformer, benchmark::State& state) {
  const Eigen::MatrixX3d uvw = deformer.embedding().parameters();
  const Eigen::Index n = uvw.rows();
  for (Eigen::Index r = 0; r < n; r += std::max<Eigen::Index>(1, n / 997)) {
    const Eigen::Vector3d x = lattice.frame() * lattice.evaluate(uvw.row(r).transpose());
    if ((x - deformer.points().row(r).transpose()).norm() > 1e-12 * (1.0 + x.norm())) {
      state.SkipWithError("deformed point disagrees with Lattice::evaluate");
      return;
    }
  }
}

struct DeformCase {
  Lattice lattice;
  Eigen::MatrixX3d Q;
  std::unique_ptr<Deformer> deformer;
};

DeformCase& deformCase(const std::string& key, int count, AxisBasis basis, Eigen::Index n) {
  const bool grid = key.find("order:grid") != std::string::npos;
  static std::map<std::string, std::unique_ptr<DeformCase>> cache;
  auto& slot = cache[key];
  if (!slot) {
    cache.clear();  // keep one big case in memory at a time
    auto c = std::make_unique<DeformCase>(
        DeformCase{boxLattice(count, basis), grid ? gridPoints(n) : randomPoints(n, 1), nullptr});
    c->deformer = std::make_unique<Deformer>(embed(c->lattice, c->Q));
    c->lattice.setControlPoints(moved(c->lattice, 2));
    cache[key] = std::move(c);
  }
  return *cache[key];
}

// Precision::Single also reports how far it lands from the double evaluation (max_diff_vs_double,
// in the units of the unit-box lattice) and fails above 1e-6 (docs/ffd-engine.md).
void BM_Deform(benchmark::State& state, int count, AxisBasis basis, Eigen::Index n, std::string key,
               Precision precision) {
  DeformCase& c = deformCase(key, count, basis, n);
  c.deformer->setPrecision(Precision::Double);
  c.deformer->deform(c.lattice, c.Q);
  check(c.lattice, *c.deformer, state);
  if (precision == Precision::Single) {
    const Eigen::MatrixX3d reference = c.deformer->points();
    c.deformer->setPrecision(Precision::Single);
    const double diff = (c.deformer->deform(c.lattice, c.Q) - reference).cwiseAbs().maxCoeff();
    state.counters["max_diff_vs_double"] = diff;
    if (!(diff <= 1e-6)) state.SkipWithError("single precision strays from the double evaluation");
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(c.deformer->deform(c.lattice, c.Q).data());
    benchmark::ClobberMemory();
  }
  c.deformer->setPrecision(Precision::Double);
  state.SetItemsProcessed(state.iterations() * n);
  state.counters["embed_bytes_per_point"] = double(c.deformer->embedding().memoryBytes()) / double(n);
}

// exact = true: Deformer::update(lattice, input), re-evaluating the touched cells (what Pipeline
// uses); false: the multiply-add delta update(lattice).
void BM_Update(benchmark::State& state, Eigen::Vector3i control, Eigen::Index n, std::string key, bool exact,
               Precision precision) {
  DeformCase& c = deformCase(key, 8, AxisBasis::bspline(3), n);
  const Eigen::Index flat = c.lattice.index(control[0], control[1], control[2]);
  const Eigen::Vector3d base = c.lattice.controlPoints().row(flat).transpose();
  c.deformer->setPrecision(precision);
  c.deformer->deform(c.lattice, c.Q);
  double step = 0.0;
  Eigen::Index evaluated = 0;
  for (auto _ : state) {
    state.PauseTiming();
    step += 1e-3;
    c.lattice.setControlPoint(flat, base + Eigen::Vector3d(step, -step, step));
    state.ResumeTiming();
    benchmark::DoNotOptimize((exact ? c.deformer->update(c.lattice, c.Q) : c.deformer->update(c.lattice)).data());
    evaluated = c.deformer->lastStats().evaluatedPoints;
  }
  // The incremental result must still match a full evaluation: exactly for the exact variant; the
  // delta variant accumulates rounding over the thousands of updates of a benchmark run.
  const Eigen::MatrixX3d incremental = c.deformer->points();
  Deformer full(embed(c.lattice, c.Q));
  full.setPrecision(precision);
  const double drift = (full.deform(c.lattice, c.Q) - incremental).rowwise().norm().maxCoeff();
  if (exact ? drift != 0.0 : drift > 1e-9) state.SkipWithError("incremental update disagrees with full evaluation");
  c.deformer->setPrecision(Precision::Double);
  c.deformer->deform(c.lattice, c.Q);  // resynchronise for the next run
  state.counters["points_touched"] = double(evaluated);
  state.counters["max_diff_vs_full"] = drift;
}

// Rational lattices (Lamousin & Waggenspack 1994): the same 4x4x4 cubic lattice and 10^6 random
// points as BM_Deform, with every weight drawn from [0.5, 2]. Full evaluation (the rational path
// of Deformer::deform) and the delta step of update(lattice) after one control point and its
// weight moved (the homogeneous sums kept per point). Checked against Lattice::evaluate first.
void BM_RationalDeform(benchmark::State& state, Eigen::Index n) {
  Lattice lattice = boxLattice(4, AxisBasis::bspline(3));
  const Eigen::MatrixX3d Q = randomPoints(n, 1);
  Deformer deformer(embed(lattice, Q));
  lattice.setControlPoints(moved(lattice, 2));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0.5, 2.0);
  Eigen::VectorXd w(lattice.pointCount());
  for (Eigen::Index i = 0; i < w.size(); ++i) w[i] = U(rng);
  lattice.setWeights(w);
  deformer.deform(lattice, Q);
  check(lattice, deformer, state);
  for (auto _ : state) {
    benchmark::DoNotOptimize(deformer.deform(lattice, Q).data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
}

// weighted: random weights; weightEdit: each step also changes the moved point's weight (a
// re-evaluation of the cells it touches) instead of keeping it (the numerator-only delta).
void BM_RationalUpdate(benchmark::State& state, Eigen::Index n, bool weighted, bool weightEdit) {
  Lattice lattice = boxLattice(8, AxisBasis::bspline(3));
  const Eigen::MatrixX3d Q = randomPoints(n, 1);
  Deformer deformer(embed(lattice, Q));
  lattice.setControlPoints(moved(lattice, 2));
  if (weighted) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(0.5, 2.0);
    Eigen::VectorXd w(lattice.pointCount());
    for (Eigen::Index i = 0; i < w.size(); ++i) w[i] = U(rng);
    lattice.setWeights(w);
  }
  deformer.deform(lattice, Q);
  const Eigen::Index flat = lattice.index(3, 3, 3);
  const Eigen::Vector3d base = lattice.controlPoints().row(flat).transpose();
  const double weight = lattice.weight(flat);
  double step = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    step += 1e-3;
    lattice.setControlPoint(flat, base + Eigen::Vector3d(step, -step, step));
    if (weightEdit) lattice.setWeight(flat, weight * (1.0 + step));
    state.ResumeTiming();
    benchmark::DoNotOptimize(deformer.update(lattice).data());
  }
  Deformer full(embed(lattice, Q));
  const double drift = (full.deform(lattice, Q) - deformer.points()).rowwise().norm().maxCoeff();
  if (drift > 1e-9) state.SkipWithError("delta step disagrees with full evaluation");
  state.counters["max_diff_vs_full"] = drift;
  state.counters["points_touched"] = double(deformer.lastStats().evaluatedPoints);
}

// Closed-form embedding into a box lattice (affine rest map), points in random order: the
// embedding every box lattice of the CLI and the scene deformer does. grow = 1: every point
// inside (a lattice fitted to the object, as `ffdkit-cli deform --fit`); grow = 1.1: the box
// grown by 10 %, a quarter of the points outside. The result is checked against
// Lattice::evaluateRest once before timing.
void BM_EmbedBox(benchmark::State& state, int count, AxisBasis basis, Eigen::Index n, double grow) {
  Lattice lattice = boxLattice(count, basis);
  lattice.setFrame(Eigen::Affine3d(Eigen::Translation3d(0.25, -0.5, 1.0)) * Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()) *
                   Eigen::Scaling(2.0, 1.5, 0.5));
  Eigen::MatrixX3d Q = (randomPoints(n, 5).array() * grow - 0.5 * (grow - 1.0)).matrix();
  Q = (lattice.frame() * Q.transpose()).transpose();
  Eigen::Index inside = 0;
  {
    const Embedding e = embed(lattice, Q);
    const Eigen::MatrixX3d uvw = e.parameters();
    for (Eigen::Index r = 0; r < n; r += std::max<Eigen::Index>(1, n / 997)) {
      const Eigen::Vector3d x = lattice.frame() * lattice.evaluateRest(uvw.row(r).transpose());
      const bool in = (uvw.row(r).array() >= -1e-9).all() && (uvw.row(r).array() <= 1.0 + 1e-9).all();
      if ((x - Q.row(r).transpose()).norm() > 1e-12 * (1.0 + x.norm()) ||
          in != (e.status(r) == PointStatus::Inside)) {
        state.SkipWithError("closed-form embedding disagrees with Lattice::evaluateRest");
        return;
      }
    }
  }
  double bytes = 0;
  for (auto _ : state) {
    Embedding e = embed(lattice, Q);
    inside = e.insideCount();
    bytes = double(e.memoryBytes()) / double(n);
    benchmark::DoNotOptimize(e.sortedU().data());
  }
  state.counters["inside"] = double(inside);
  state.counters["embed_bytes_per_point"] = bytes;
  state.SetItemsProcessed(state.iterations() * n);
}

// Newton embedding into a non-affine lattice.
// withProgress: the GUI's hook (publish the fraction in an atomic, read an atomic cancel flag),
// to show that the progress calls cost nothing measurable.
void BM_EmbedNewton(benchmark::State& state, bool cylindrical, Eigen::Index n, bool withProgress) {
  Lattice lattice = makeBoxLattice();
  if (cylindrical) {
    lattice = makeCylindricalLattice(CylindricalLatticeOptions{});
  } else {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(-0.06, 0.06);
    Eigen::MatrixX3d rest = lattice.restPoints();
    for (Eigen::Index r = 0; r < rest.rows(); ++r)
      for (int c = 0; c < 3; ++c) rest(r, c) += U(rng);
    lattice.setRestPoints(rest);
  }
  // Points inside the rest lattice: images of random parameters.
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Eigen::MatrixX3d Q(n, 3);
  for (Eigen::Index r = 0; r < n; ++r) Q.row(r) = lattice.evaluateRest(Eigen::Vector3d(U(rng), U(rng), U(rng))).transpose();
  Eigen::Index failed = 0, inside = 0;
  double bytes = 0;
  std::atomic<bool> cancel{false};
  std::atomic<int> permille{0};
  EmbedOptions options;
  if (withProgress) {
    options.progress = [&cancel, &permille](Eigen::Index done, Eigen::Index total) {
      permille.store(static_cast<int>(1000 * done / std::max<Eigen::Index>(total, 1)), std::memory_order_relaxed);
      return !cancel.load(std::memory_order_relaxed);
    };
  }
  for (auto _ : state) {
    Embedding e = embed(lattice, Q, options);
    failed = e.failedCount();
    inside = e.insideCount();
    bytes = double(e.memoryBytes()) / double(n);
    benchmark::DoNotOptimize(e.sortedU().data());
  }
  if (failed != 0) state.SkipWithError("Newton failed on some points");
  if (withProgress && permille.load() != 1000) state.SkipWithError("progress did not end at 1000 permille");
  state.counters["inside"] = double(inside);
  state.counters["embed_bytes_per_point"] = bytes;
  state.SetItemsProcessed(state.iterations() * n);
}

const bool registered = [] {
  auto name = [](const char* what, Eigen::Index n, const std::string& lattice) {
    return std::string(what) + "/points:" + std::to_string(n) + "/lattice:" + lattice;
  };
  for (Eigen::Index n = 1000; n <= 10000000; n *= 10) {
    const std::string key = name("BM_Deform", n, "4x4x4/basis:bspline3");
    for (Precision precision : {Precision::Double, Precision::Single}) {
      const bool single = precision == Precision::Single;
      benchmark::RegisterBenchmark((key + (single ? "/precision:single" : "")).c_str(), BM_Deform, 4,
                                   AxisBasis::bspline(3), n, key, precision)
          ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
    }
  }
  const Eigen::Index million = 1000000;
  for (auto [count, basis, label] : {std::tuple{4, AxisBasis::bernstein(), "4x4x4/basis:bernstein"},
                                     std::tuple{10, AxisBasis::bspline(3), "10x10x10/basis:bspline3"},
                                     std::tuple{10, AxisBasis::bspline(3), "10x10x10/basis:bspline3/order:grid"},
                                     std::tuple{8, AxisBasis::bspline(3), "8x8x8/basis:bspline3"}}) {
    const std::string key = name("BM_Deform", million, label);
    benchmark::RegisterBenchmark(key.c_str(), BM_Deform, count, basis, million, key, Precision::Double)
        ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
  }
  // The same jobs with the displacement in float32 (Precision::Single), as Blender computes.
  for (auto [count, label] : {std::pair{8, "8x8x8/basis:bspline3"}, std::pair{10, "10x10x10/basis:bspline3/order:grid"}}) {
    const std::string key = name("BM_Deform", million, label);
    benchmark::RegisterBenchmark((key + "/precision:single").c_str(), BM_Deform, count, AxisBasis::bspline(3),
                                 million, key, Precision::Single)
        ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
  }
  for (const char* order : {"", "/order:grid"}) {
    for (auto [control, label] : {std::pair{Eigen::Vector3i(0, 0, 0), "corner(0,0,0)"},
                                  std::pair{Eigen::Vector3i(1, 1, 1), "(1,1,1)"},
                                  std::pair{Eigen::Vector3i(3, 3, 3), "interior(3,3,3)"}}) {
      const std::string lattice = std::string("8x8x8/basis:bspline3") + order;
      for (bool exact : {true, false}) {
        benchmark::RegisterBenchmark(
            (name("BM_Update", million, lattice) + "/moved:" + label + (exact ? "/update:exact" : "/update:delta")).c_str(),
            BM_Update, control, million, name("BM_Deform", million, lattice), exact, Precision::Double)
            ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
      }
      if (*order == '\0' && label[0] == 'i') {
        benchmark::RegisterBenchmark(
            (name("BM_Update", million, lattice) + "/moved:" + label + "/update:exact/precision:single").c_str(),
            BM_Update, control, million, name("BM_Deform", million, lattice), true, Precision::Single)
            ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
      }
    }
  }
  for (auto [count, basis, label] : {std::tuple{4, AxisBasis::bspline(3), "4x4x4/basis:bspline3"},
                                     std::tuple{3, AxisBasis::bernstein(), "3x3x3/basis:bernstein"},
                                     std::tuple{8, AxisBasis::bspline(3), "8x8x8/basis:bspline3"}}) {
    for (auto [grow, inside] : {std::pair{1.0, "/inside:100%"}, std::pair{1.1, "/inside:75%"}}) {
      benchmark::RegisterBenchmark((name("BM_EmbedBox", million, label) + inside).c_str(), BM_EmbedBox, count, basis,
                                   million, grow)
          ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
    }
  }
  benchmark::RegisterBenchmark(name("BM_RationalDeform", million, "4x4x4/basis:bspline3/weights:random").c_str(),
                               BM_RationalDeform, million)
      ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
  for (auto [weighted, weightEdit, label] : {std::tuple{false, false, "/weights:none/moved:(3,3,3)/update:delta"},
                                             std::tuple{true, false, "/weights:random/moved:(3,3,3)/update:delta"},
                                             std::tuple{true, true, "/weights:random/moved:(3,3,3)+weight/update:delta"}}) {
    benchmark::RegisterBenchmark((name("BM_RationalUpdate", million, "8x8x8/basis:bspline3") + label).c_str(),
                                 BM_RationalUpdate, million, weighted, weightEdit)
        ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
  }
  // Newton embedding at 10^5, 10^6 and 10^7 points (how the cost grows), and at 10^6 with progress.
  for (auto [n, progress] : {std::pair{million / 10, false}, std::pair{million, false}, std::pair{10 * million, false},
                             std::pair{million, true}}) {
    const std::string suffix = progress ? "/progress:atomic" : "";
    benchmark::RegisterBenchmark((name("BM_EmbedNewton", n, "4x4x4/rest:user") + suffix).c_str(), BM_EmbedNewton,
                                 false, n, progress)
        ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
    benchmark::RegisterBenchmark((name("BM_EmbedNewton", n, "3x8x4/rest:cylindrical") + suffix).c_str(),
                                 BM_EmbedNewton, true, n, progress)
        ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
  }
  return true;
}();

}  // namespace
