#include <benchmark/benchmark.h>

#include "ffdkit/ffd/bernstein_basis.h"

static void BM_BernsteinBasis(benchmark::State& state) {
  const int degree = static_cast<int>(state.range(0));
  double t = 0.3;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ffdkit::ffd::bernsteinBasis(degree, t));
    t = t < 0.9 ? t + 0.01 : 0.1;
  }
}
BENCHMARK(BM_BernsteinBasis)->ArgName("degree")->Arg(3)->Arg(9);
