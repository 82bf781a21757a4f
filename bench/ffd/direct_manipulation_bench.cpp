// Direct manipulation (Hsu, Hughes & Kaufman 1992): the least-norm control change for k point
// constraints on an 8x8x8 cubic B-spline lattice (a drag step of the application solves k = 1;
// scripts may pin many points). Cost: k sparse weight rows, a k x k Gram matrix and its
// complete orthogonal decomposition, O(k^2 (p+1)^3 + k^3).
#include <random>

#include <benchmark/benchmark.h>

#include "ffdkit/ffd/direct_manipulation.h"

namespace {

using namespace ffdkit::ffd;

void BM_LeastNormControlChange(benchmark::State& state) {
  const Eigen::Index k = state.range(0);
  BoxLatticeOptions options;
  options.counts = Eigen::Vector3i::Constant(8);
  options.bases = {AxisBasis::bspline(3), AxisBasis::bspline(3), AxisBasis::bspline(3)};
  const Lattice lattice = makeBoxLattice(options);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Eigen::MatrixX3d uvw(k, 3);
  for (Eigen::Index r = 0; r < k; ++r) uvw.row(r) << U(rng), U(rng), U(rng);
  const Eigen::MatrixX3d d = 0.05 * Eigen::MatrixX3d::Random(k, 3);
  for (auto _ : state) benchmark::DoNotOptimize(leastNormControlChange(lattice, uvw, d).data());
  state.SetItemsProcessed(state.iterations() * k);
}
BENCHMARK(BM_LeastNormControlChange)->ArgName("points")->Arg(1)->Arg(16)->Arg(256)->Unit(benchmark::kMicrosecond);

}  // namespace
