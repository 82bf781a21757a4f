// boxBernsteinDeform (ffd/box_bernstein_deform.h), the one-pass FFD behind ffdkit.pygem.FFD.
// Run: bench_ffd --benchmark_filter=BM_BoxBernsteinDeform --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// The case is bench/python/bench_pygem.py's: points uniform in a rotated box 20 % larger than
// the lattice box (58 % inside), a Bernstein lattice with random displacements (weights:dense)
// or one displaced control point (weights:sparse). Each case checks a sample of its result against
// Lattice::evaluate (eq. (6.1) from scratch) before timing.
// layout:rows = numpy's C order (x y z of a point adjacent), layout:columns = Eigen's MatrixX3d.
// out:reused writes into the same output every iteration; out:fresh into newly mapped memory
// each time (what a new numpy array per call is, huge pages advised as numpy does), so its time
// includes the page faults of first touching the output.

#include <sys/mman.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include <benchmark/benchmark.h>

#include "ffdkit/ffd/box_bernstein_deform.h"
#include "ffdkit/ffd/lattice.h"

using namespace ffdkit::ffd;

namespace {

struct BoxCase {
  BoxBernsteinLattice box;
  Lattice lattice;  // the same FFD as a general lattice, for the check
  PointRows rows;   // C order
  Eigen::MatrixX3d columns;
};

BoxCase makeCase(int count, Eigen::Index n, bool sparse) {
  BoxBernsteinLattice box;
  box.counts = {count, count, count};
  // bench_pygem.py's box: origin (-0.5, 0.2, 0.1), lengths (2, 1, 1.5), rotated Rx(10) Ry(-20) Rz(30).
  const double degree = 3.14159265358979323846 / 180.0;
  box.frame = Eigen::Affine3d(Eigen::Translation3d(-0.5, 0.2, 0.1)) *
              Eigen::AngleAxisd(10 * degree, Eigen::Vector3d::UnitX()) *
              Eigen::AngleAxisd(-20 * degree, Eigen::Vector3d::UnitY()) *
              Eigen::AngleAxisd(30 * degree, Eigen::Vector3d::UnitZ()) * Eigen::Scaling(2.0, 1.0, 1.5);
  std::mt19937 rng(1);
  std::normal_distribution<double> N(0.0, 0.2);
  box.displacements = Eigen::MatrixX3d::Zero(count * count * count, 3);
  if (sparse) {
    box.displacements.row(1 + count * (1 + count)) << 0.1, -0.2, 0.3;
  } else {
    for (Eigen::Index r = 0; r < box.displacements.rows(); ++r)
      for (int c = 0; c < 3; ++c) box.displacements(r, c) = N(rng);
  }
  Lattice lattice = toLattice(box);
  std::uniform_real_distribution<double> U(-0.1, 1.1);
  PointRows rows(n, 3);
  for (Eigen::Index r = 0; r < n; ++r) rows.row(r) = (box.frame * Eigen::Vector3d(U(rng), U(rng), U(rng))).transpose();
  Eigen::MatrixX3d columns = rows;
  return {std::move(box), std::move(lattice), std::move(rows), std::move(columns)};
}

bool matchesLattice(const BoxCase& c, const PointRows& out) {
  const Eigen::Affine3d toBox = c.box.frame.inverse();
  const Eigen::Index n = out.rows();
  for (Eigen::Index r = 0; r < n; r += std::max<Eigen::Index>(1, n / 997)) {
    const Eigen::Vector3d q = c.rows.row(r).transpose();
    const Eigen::Vector3d s = toBox * q;
    const bool inside = (s.array() >= 0.0).all() && (s.array() <= 1.0).all();
    const Eigen::Vector3d expected = inside ? Eigen::Vector3d(c.lattice.frame() * c.lattice.evaluate(s)) : q;
    if ((out.row(r).transpose() - expected).norm() > 1e-12 * (1.0 + q.norm())) return false;
  }
  return true;
}

// Anonymous memory mapped for one output and unmapped after (a new array's fresh pages).
struct FreshBlock {
  explicit FreshBlock(std::size_t bytes) : bytes(bytes) {
    data = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (data == MAP_FAILED) data = nullptr;
#ifdef MADV_HUGEPAGE
    if (data) (void)::madvise(data, bytes, MADV_HUGEPAGE);
#endif
  }
  ~FreshBlock() {
    if (data) ::munmap(data, bytes);
  }
  void* data;
  std::size_t bytes;
};

void BM_BoxBernsteinDeform(benchmark::State& state, int count, Eigen::Index n, bool sparse, bool columns, bool fresh) {
  static std::unique_ptr<BoxCase> cached;
  static std::string cachedKey;
  const std::string key = std::to_string(count) + "/" + std::to_string(n) + "/" + std::to_string(sparse);
  if (!cached || cachedKey != key) {
    cached.reset();  // one big case in memory at a time
    cached = std::make_unique<BoxCase>(makeCase(count, n, sparse));
    cachedKey = key;
  }
  const BoxCase& c = *cached;
  const Eigen::Map<const PointRows, 0, PointRowsStride> input =
      columns ? Eigen::Map<const PointRows, 0, PointRowsStride>(c.columns.data(), n, 3, PointRowsStride(1, n))
              : Eigen::Map<const PointRows, 0, PointRowsStride>(c.rows.data(), n, 3, PointRowsStride(3, 1));
  PointRows out(n, 3);
  Eigen::Index inside = boxBernsteinDeform(c.box, input, out).insidePoints;
  if (!matchesLattice(c, out)) {
    state.SkipWithError("boxBernsteinDeform disagrees with Lattice::evaluate");
    return;
  }
  for (auto _ : state) {
    if (fresh) {
      FreshBlock block(sizeof(double) * 3 * std::size_t(n));
      if (!block.data) {
        state.SkipWithError("mmap failed");
        return;
      }
      Eigen::Map<PointRows> target(static_cast<double*>(block.data), n, 3);
      inside = boxBernsteinDeform(c.box, input, target).insidePoints;
      benchmark::DoNotOptimize(block.data);
    } else {
      inside = boxBernsteinDeform(c.box, input, out).insidePoints;
      benchmark::DoNotOptimize(out.data());
    }
    benchmark::ClobberMemory();
  }
  state.counters["inside"] = double(inside) / double(n);
  state.SetItemsProcessed(state.iterations() * n);
}

const bool registered = [] {
  auto name = [](Eigen::Index n, int count, const char* rest) {
    const std::string c = std::to_string(count);
    return "BM_BoxBernsteinDeform/points:" + std::to_string(n) + "/lattice:" + c + "x" + c + "x" + c + rest;
  };
  auto add = [&](Eigen::Index n, int count, bool sparse, bool columns, bool fresh) {
    const std::string rest = std::string(sparse ? "/weights:sparse" : "/weights:dense") +
                             (columns ? "/layout:columns" : "/layout:rows") + (fresh ? "/out:fresh" : "/out:reused");
    benchmark::RegisterBenchmark(name(n, count, rest.c_str()).c_str(), BM_BoxBernsteinDeform, count, n, sparse, columns,
                                 fresh)
        ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
  };
  for (Eigen::Index n : {100000, 1000000, 10000000}) {
    add(n, 4, false, false, false);
    add(n, 4, false, false, true);
  }
  add(1000000, 4, false, true, false);
  add(1000000, 4, true, false, false);
  add(1000000, 3, false, false, false);
  return true;
}();

}  // namespace
