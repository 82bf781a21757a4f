#include "ffdkit/ffd/embedding.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <string>

#include <omp.h>

#include "cell_locator.h"
#include "rest_solver.h"
#include "vector_clones.h"

namespace ffdkit::ffd {
namespace {

// Below this many points a parallel region costs more than it saves (thread wake-up, barriers).
constexpr Eigen::Index kParallelPoints = 16384;
constexpr std::uint32_t kTile = Embedding::kTileSize;

enum class PointClass : std::uint8_t { Evaluated = 0, Blended = 1, Frozen = 2 };

// One tile's solved points in original order, before grouping: (u, v, w) in pu, pv, pw (the
// arrays below, or the closed form's output written straight into the Embedding).
struct TileScratch {
  double *pu = nullptr, *pv = nullptr, *pw = nullptr;
  std::array<double, kTile> u, v, w, weight;
  std::array<std::uint32_t, kTile> key, order;
  std::array<std::uint8_t, kTile> flagged;
  std::vector<std::uint32_t> start;  // counting-sort buckets
};

// One tile's blocks (sorted positions are global), its blend weights (blendOffset relative to
// the tile's first weight) and status counts; `identity`: the sorted order is the original one.
struct TileGroups {
  std::vector<Embedding::Block> blocks;
  std::vector<double> blend;
  bool identity = true;
  Eigen::Index inside = 0, outside = 0, failed = 0;
};

// The closed form of an affine rest map over m points, uvw = A^-1 (F^-1 x - b), across points
// (vectorised): coef = F^-1 row-major (9), F^-1 translation - b (3), A^-1 row-major (9), the
// epsilon-grown parameter box lo (3), hi (3). flagged[i] = 1 for a point outside the box or
// not finite (solved again one by one); returns whether any point is not finite.
FFDKIT_VECTOR_CLONES
bool affineTile(const double* __restrict X, const double* __restrict Y, const double* __restrict Z, std::uint32_t m,
                const double* __restrict coef, double* __restrict U, double* __restrict V, double* __restrict W,
                std::uint8_t* __restrict flagged) {
  double c[27];
  for (int k = 0; k < 27; ++k) c[k] = coef[k];
  bool anyNonFinite = false;
  for (std::uint32_t i = 0; i < m; ++i) {
    const double qx = c[0] * X[i] + c[1] * Y[i] + c[2] * Z[i] + c[9];
    const double qy = c[3] * X[i] + c[4] * Y[i] + c[5] * Z[i] + c[10];
    const double qz = c[6] * X[i] + c[7] * Y[i] + c[8] * Z[i] + c[11];
    const double u = c[12] * qx + c[13] * qy + c[14] * qz;
    const double v = c[15] * qx + c[16] * qy + c[17] * qz;
    const double w = c[18] * qx + c[19] * qy + c[20] * qz;
    U[i] = u;
    V[i] = v;
    W[i] = w;
    const double sum = X[i] + Y[i] + Z[i];
    const bool nonFinite = !(sum - sum == 0.0);  // Inf and NaN (or an overflowing sum: rechecked)
    anyNonFinite |= nonFinite;
    flagged[i] = nonFinite | (u < c[21]) | (v < c[22]) | (w < c[23]) | (u > c[24]) | (v > c[25]) | (w > c[26]);
  }
  return anyNonFinite;
}

// Damped Newton from the first guess, else from the nearest sample of the coarse grid; the
// solver's evaluation is inlined into each clone (vectorised per coordinate).
FFDKIT_VECTOR_CLONES
bool solveNewton(const detail::RestSolver& solver, const Eigen::Vector3d& q, Eigen::Vector3d& uvw) {
  uvw = solver.initialGuess(q);
  if (solver.newton(q, uvw)) return true;
  Eigen::Vector3d restart = solver.nearestSample(q);
  if (!solver.newton(q, restart)) return false;
  uvw = restart;
  return true;
}

// Nodes [begin, end) of the solver's tabulated inverse (RestSolver::solveGridNode).
FFDKIT_VECTOR_CLONES
void solveGridNodes(const detail::RestSolver& solver, std::int64_t begin, std::int64_t end, Eigen::Vector3d* uvw,
                    char* valid) {
  for (std::int64_t node = begin; node < end; ++node) valid[node] = solver.solveGridNode(node, uvw[node]);
}

// The solver's tabulated inverse, its nodes shared by the threads (one thread took a serial
// tenth of a 10^6-point embedding).
void buildInverseGrid(detail::RestSolver& solver, bool parallel) {
  constexpr std::int64_t kNodes = detail::RestSolver::kGridNodes, kChunk = 64;
  std::vector<Eigen::Vector3d> uvw(static_cast<std::size_t>(kNodes));
  std::vector<char> valid(uvw.size(), 0);
#pragma omp parallel for schedule(dynamic, 1) if (parallel)
  for (std::int64_t chunk = 0; chunk < (kNodes + kChunk - 1) / kChunk; ++chunk) {
    solveGridNodes(solver, chunk * kChunk, std::min(kNodes, (chunk + 1) * kChunk), uvw.data(), valid.data());
  }
  solver.setInverseGrid(std::move(uvw), std::move(valid));
}

// Newton's first two steps over a run of points, batched across points (RestSolver::firstSteps):
// the guesses, their residual norms, the first full steps and, where Newton stopped at the
// second iterate, its result. Non-finite points get any finite values (solvePoint rejects them
// before looking).
struct FirstSteps {
  static constexpr std::uint32_t kChunk = 256;  // points per run, a multiple of kBatch
  alignas(64) double q[3][kChunk];
  alignas(64) double guess[3][kChunk];
  alignas(64) double step[3][kChunk];
  alignas(64) double fGuess[kChunk];
  alignas(64) double done[kChunk];
  alignas(64) double result[3][kChunk];
};

FFDKIT_VECTOR_CLONES
void firstSteps(const detail::RestSolver& solver, const Eigen::Affine3d& toLocal, const double* X, const double* Y,
                const double* Z, std::uint32_t m, FirstSteps& out) {
  constexpr int kBatch = detail::RestSolver::kBatch;
  const std::uint32_t padded = (m + kBatch - 1) / kBatch * kBatch;
  const Eigen::Vector3d mid = 0.5 * (solver.lo() + solver.hi());
  for (std::uint32_t i = 0; i < padded; ++i) {
    Eigen::Vector3d q = Eigen::Vector3d::Zero(), uvw = mid;
    if (i < m) {
      const Eigen::Vector3d x(X[i], Y[i], Z[i]);
      if (x.allFinite()) {
        q = toLocal * x;
        uvw = solver.initialGuess(q);
      }
    }
    for (int a = 0; a < 3; ++a) {
      out.q[a][i] = q[a];
      out.guess[a][i] = uvw[a];
    }
  }
  for (std::uint32_t i = 0; i < padded; i += kBatch) {
    const double* q[3] = {out.q[0] + i, out.q[1] + i, out.q[2] + i};
    const double* uvw[3] = {out.guess[0] + i, out.guess[1] + i, out.guess[2] + i};
    double* step[3] = {out.step[0] + i, out.step[1] + i, out.step[2] + i};
    double* result[3] = {out.result[0] + i, out.result[1] + i, out.result[2] + i};
    solver.firstSteps(q, uvw, out.fGuess + i, step, out.done + i, result);
  }
}

// solveNewton() for point i of a run whose first steps firstSteps() took (s; null: none): the
// same iterates up to rounding (the guess if it already converged, the second iterate's result
// if Newton stopped there, else newton() from the full step when that lowers the residual, else
// newton() from the guess with its halvings).
FFDKIT_VECTOR_CLONES
bool solveNewtonAfterSteps(const detail::RestSolver& solver, const Eigen::Vector3d& q, const FirstSteps* first,
                           std::uint32_t i, Eigen::Vector3d& uvw) {
  if (!first) return solveNewton(solver, q, uvw);
  const FirstSteps& s = *first;
  if (s.fGuess[i] <= solver.tolerance()) {
    uvw = Eigen::Vector3d(s.guess[0][i], s.guess[1][i], s.guess[2][i]);
    return true;
  }
  if (s.done[i] != 0.0) {
    uvw = Eigen::Vector3d(s.result[0][i], s.result[1][i], s.result[2][i]);
    return true;
  }
  uvw = Eigen::Vector3d(s.step[0][i], s.step[1][i], s.step[2][i]);
  if (uvw.allFinite()) {
    solver.normalize(uvw);
    switch (solver.newtonAfterStep(q, uvw, s.fGuess[i])) {
      case detail::RestSolver::AfterStep::Converged:
        return true;
      case detail::RestSolver::AfterStep::Failed: {
        Eigen::Vector3d restart = solver.nearestSample(q);
        if (!solver.newton(q, restart)) return false;
        uvw = restart;
        return true;
      }
      case detail::RestSolver::AfterStep::Rejected:
        break;
    }
  }
  return solveNewton(solver, q, uvw);
}

}  // namespace

PointStatus Embedding::status(Eigen::Index point) const {
  if (point < 0 || point >= pointCount()) {
    throw LatticeError("embedding point index " + std::to_string(point) + " out of range [0, " +
                       std::to_string(pointCount()) + ")");
  }
  return status_[static_cast<std::size_t>(point)];
}

Eigen::MatrixX3d Embedding::parameters() const {
  Eigen::MatrixX3d uvw(pointCount(), 3);
  for (std::size_t q = 0; q < u_.size(); ++q) {
    const Eigen::Index p = order_.empty() ? static_cast<Eigen::Index>(q) : order_[q];
    uvw.row(p) << u_[q], v_[q], w_[q];
  }
  return uvw;
}

void Embedding::checkLattice(const Lattice& lattice) const {
  if (lattice.counts() != counts_ || lattice.restRevision() != restRevision_) {
    throw LatticeError("embedding is stale: built for rest revision " + std::to_string(restRevision_) +
                       " of a (" + std::to_string(counts_[0]) + ", " + std::to_string(counts_[1]) + ", " +
                       std::to_string(counts_[2]) + ") lattice, lattice is at rest revision " +
                       std::to_string(lattice.restRevision()) + "; re-embed");
  }
}

std::size_t Embedding::memoryBytes() const {
  return status_.capacity() * sizeof(PointStatus) + (u_.capacity() + v_.capacity() + w_.capacity()) * sizeof(double) +
         order_.capacity() * sizeof(std::uint32_t) + blend_.capacity() * sizeof(double) +
         blocks_.capacity() * sizeof(Block) + tileBlocks_.capacity() * sizeof(std::uint32_t);
}

Embedding embed(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& points, const EmbedOptions& options) {
  const Eigen::Index n = points.rows();
  if (n >= static_cast<Eigen::Index>(std::numeric_limits<std::uint32_t>::max())) {
    throw LatticeError("embed: at most 2^32-2 points, got " + std::to_string(n));
  }
  // The tabulated inverse (about 5000 Newton solves) pays for itself from a few 10^4 points on.
  detail::RestSolver gridSolver(lattice, options, /*inverseGrid=*/n >= 4 * kParallelPoints);
  if (gridSolver.wantsInverseGrid()) buildInverseGrid(gridSolver, options.parallel);
  const detail::RestSolver& solver = gridSolver;
  const Eigen::Affine3d toLocal = lattice.frame().inverse();
  const OutsidePolicy policy = lattice.outsidePolicy();
  const AxisSpline* axes[3] = {&lattice.axis(0), &lattice.axis(1), &lattice.axis(2)};
  const detail::CellLocator locate[3] = {detail::CellLocator(*axes[0]), detail::CellLocator(*axes[1]),
                                         detail::CellLocator(*axes[2])};
  const int cells[3] = {axes[0]->cellCount(), axes[1]->cellCount(), axes[2]->cellCount()};
  const std::int64_t cellTotal = std::int64_t(cells[0]) * cells[1] * cells[2];
  const bool periodic[3] = {axes[0]->periodic(), axes[1]->periodic(), axes[2]->periodic()};
  const bool affine = lattice.restIsAffine();
  const bool batched = !affine && solver.batchedFirstStep();  // Newton's first steps across points
  const Eigen::Matrix3d Ainv = lattice.restAffineLinear().inverse();
  const Eigen::Vector3d b = lattice.restAffineOffset();

  Embedding e;
  e.restRevision_ = lattice.restRevision();
  e.counts_ = lattice.counts();
  e.cellsU_ = cells[0];
  e.cellsV_ = cells[1];
  e.policy_ = policy;
  // Written once below, tile by tile in parallel: no zero fill first (see NoInitAllocator).
  e.status_.resize(static_cast<std::size_t>(n));
  e.u_.resize(n);
  e.v_.resize(n);
  e.w_.resize(n);
  e.order_.resize(n);
  const std::int64_t tileCount = (n + kTile - 1) / kTile;
  std::vector<TileGroups> groups(static_cast<std::size_t>(tileCount));
  // Non-finite input points are found in the same pass (a separate check cost as much as the
  // closed-form embedding itself); embed() then throws for the first one.
  std::atomic<bool> nonFinite{false};

  // Point p of a tile: (u, v, w), blend weight, (class, cell) key, status (Kuriyama 1996,
  // eq. (6.2)). first: the batched first Newton steps of the run point p belongs to (null: none), at
  // `runIndex`.
  const auto solvePoint = [&](Eigen::Index p, std::uint32_t i, TileScratch& t, const FirstSteps* first = nullptr,
                              std::uint32_t runIndex = 0) {
    if (!points.row(p).allFinite()) {
      nonFinite.store(true, std::memory_order_relaxed);
      t.pu[i] = t.pv[i] = t.pw[i] = 0.0;
      t.weight[i] = 0.0;
      t.key[i] = 0;
      e.status_[p] = PointStatus::Failed;
      return;
    }
    const Eigen::Vector3d q = toLocal * points.row(p).transpose();
    Eigen::Vector3d uvw;
    bool converged = true;
    if (affine) {
      uvw = Ainv * (q - b);
    } else {
      converged = first ? solveNewtonAfterSteps(solver, q, first, runIndex, uvw) : solveNewton(solver, q, uvw);
    }
    PointStatus status = PointStatus::Inside;
    PointClass cls = PointClass::Evaluated;
    double s = 1.0;
    // Outside for certain, yet Newton found no preimage (the lattice's polynomial extension does
    // not reach q): Outside, not Failed, with the closest boundary parameters; no extrapolated
    // preimage exists, so Extrapolate keeps the offset like ClampEdge.
    const bool noPreimageOutside = !converged && solver.outsideRestHull(q);
    if (noPreimageOutside) uvw = solver.closestInBox(q);
    if (!converged && !noPreimageOutside) {
      status = PointStatus::Failed;
      cls = PointClass::Frozen;
      uvw = solver.clampToBox(uvw);
    } else if (noPreimageOutside || !solver.insideBox(uvw)) {
      status = PointStatus::Outside;
      switch (policy.kind) {
        case OutsidePolicy::Kind::Identity:
          cls = PointClass::Frozen;
          break;
        case OutsidePolicy::Kind::Extrapolate:
          if (noPreimageOutside) cls = PointClass::Blended;
          break;
        case OutsidePolicy::Kind::ClampEdge:
          cls = PointClass::Blended;
          uvw = solver.clampToBox(uvw);
          break;
        case OutsidePolicy::Kind::Falloff: {
          uvw = solver.clampToBox(uvw);
          Eigen::Matrix3d J;
          const double x = (solver.evaluate(uvw, J) - q).norm() / policy.distance;
          if (x >= 1.0) {
            cls = PointClass::Frozen;
          } else {
            cls = PointClass::Blended;
            s = 1.0 - x * x * (3.0 - 2.0 * x);  // smoothstep from 1 at the boundary to 0 at `distance`
          }
          break;
        }
      }
    }
    for (int a = 0; a < 3; ++a) {
      if (periodic[a]) uvw[a] = axes[a]->wrap(uvw[a]);
    }
    t.pu[i] = uvw[0];
    t.pv[i] = uvw[1];
    t.pw[i] = uvw[2];
    t.weight[i] = s;
    e.status_[p] = status;
    const std::int64_t cell =
        cellTotal == 1 ? 0 : locate[0](uvw[0]) + cells[0] * (locate[1](uvw[1]) + std::int64_t(cells[1]) * locate[2](uvw[2]));
    t.key[i] = static_cast<std::uint32_t>(static_cast<std::int64_t>(cls) * cellTotal + cell);
  };

  // The closed form of an affine rest map, uvw = A^-1 (F^-1 x - b), a tile at a time: the
  // arithmetic runs over the columns of the tile (vectorised across points); the few points
  // outside the box go through solvePoint for their outside policy.
  const Eigen::Matrix3d L = toLocal.linear();
  const Eigen::Vector3d T = toLocal.translation();
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const double eps = options.boundaryEpsilon * (axes[a]->domainMax() - axes[a]->domainMin());
    lo[a] = axes[a]->domainMin() - eps;
    hi[a] = axes[a]->domainMax() + eps;
  }
  const bool singleCell = cellTotal == 1;
  // Identity and Extrapolate keep an outside point's parameters as solved: no per-point policy work.
  const bool outsideKeepsParameters =
      policy.kind == OutsidePolicy::Kind::Identity || policy.kind == OutsidePolicy::Kind::Extrapolate;
  const std::int64_t outsideClass = static_cast<std::int64_t>(
      policy.kind == OutsidePolicy::Kind::Identity ? PointClass::Frozen : PointClass::Evaluated);
  double affineCoef[27];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      affineCoef[3 * r + c] = L(r, c);
      affineCoef[12 + 3 * r + c] = Ainv(r, c);
    }
    affineCoef[9 + r] = T[r] - b[r];
    affineCoef[21 + r] = lo[r];
    affineCoef[24 + r] = hi[r];
  }
  const auto solveAffineTile = [&](Eigen::Index begin, std::uint32_t m, TileScratch& t) {
    t.pu = e.u_.data() + begin;
    t.pv = e.v_.data() + begin;
    t.pw = e.w_.data() + begin;
    const double* U = t.pu;
    const double* V = t.pv;
    const double* W = t.pw;
    if (affineTile(points.col(0).data() + begin, points.col(1).data() + begin, points.col(2).data() + begin, m,
                   affineCoef, t.pu, t.pv, t.pw, t.flagged.data())) {
      nonFinite.store(true, std::memory_order_relaxed);
    }
    PointStatus* status = e.status_.data() + begin;
    const auto cellKey = [&](std::uint32_t i) -> std::uint32_t {
      return singleCell ? 0u
                        : static_cast<std::uint32_t>(locate[0](U[i]) +
                                                     cells[0] * (locate[1](V[i]) + std::int64_t(cells[1]) * locate[2](W[i])));
    };
    for (std::uint32_t i = 0; i < m; ++i) {
      t.weight[i] = 1.0;
      if (!t.flagged[i]) {
        status[i] = PointStatus::Inside;
        t.key[i] = cellKey(i);
      } else if (outsideKeepsParameters && points.row(begin + i).allFinite()) {
        status[i] = PointStatus::Outside;
        t.key[i] = static_cast<std::uint32_t>(outsideClass * cellTotal) + cellKey(i);
      } else {
        solvePoint(begin + i, i, t);
      }
    }
  };

  // Sorts a solved tile by (class, cell), stably, and writes its parameters, order and blocks:
  // a block streams one cell's control points over its points in Deformer, while reads and
  // writes in original order stay within the tile (cache-local). A tile of one key (any
  // single-cell lattice with every point inside) keeps the original order.
  const std::size_t keyCount = static_cast<std::size_t>(3 * cellTotal);
  const bool counting = keyCount <= 4 * kTile;
  const auto groupTile = [&](std::int64_t tile, TileScratch& t) {
    const Eigen::Index begin = tile * kTile;
    const std::uint32_t m = static_cast<std::uint32_t>(std::min<Eigen::Index>(n - begin, kTile));
    TileGroups& g = groups[static_cast<std::size_t>(tile)];
    std::uint32_t* order = t.order.data();
    const std::uint32_t* key = t.key.data();
    bool uniform = true;
    for (std::uint32_t i = 1; i < m; ++i) uniform &= key[i] == key[0];
    if (uniform) {
      for (std::uint32_t i = 0; i < m; ++i) order[i] = i;
    } else if (counting) {
      t.start.assign(keyCount + 1, 0u);
      for (std::uint32_t i = 0; i < m; ++i) ++t.start[key[i] + 1];
      for (std::size_t k = 0; k < keyCount; ++k) t.start[k + 1] += t.start[k];
      for (std::uint32_t i = 0; i < m; ++i) order[t.start[key[i]]++] = i;
    } else {
      for (std::uint32_t i = 0; i < m; ++i) order[i] = i;
      std::stable_sort(order, order + m, [key](std::uint32_t lhs, std::uint32_t rhs) { return key[lhs] < key[rhs]; });
    }
    for (std::uint32_t i = 0; i < m; ++i) g.identity &= order[i] == i;
    double* u = e.u_.data() + begin;
    double* v = e.v_.data() + begin;
    double* w = e.w_.data() + begin;
    if (g.identity) {
      if (t.pu != u) {
        std::copy_n(t.pu, m, u);
        std::copy_n(t.pv, m, v);
        std::copy_n(t.pw, m, w);
      }
    } else {
      if (t.pu == u) {  // solved in place: permute from a copy
        std::copy_n(u, m, t.u.data());
        std::copy_n(v, m, t.v.data());
        std::copy_n(w, m, t.w.data());
      }
      std::uint32_t* globalOrder = e.order_.data() + begin;
      for (std::uint32_t i = 0; i < m; ++i) {
        u[i] = t.u[order[i]];
        v[i] = t.v[order[i]];
        w[i] = t.w[order[i]];
        globalOrder[i] = static_cast<std::uint32_t>(begin) + order[i];
      }
    }
    // Runs of equal key become blocks.
    for (std::uint32_t i = 0; i < m;) {
      const std::uint32_t k = key[order[i]];
      std::uint32_t runEnd = i + 1;
      while (runEnd < m && key[order[runEnd]] == k) ++runEnd;
      const std::int64_t cell = k % cellTotal;
      Embedding::Block block{};
      block.cell = static_cast<std::uint32_t>(cell);  // < 1e8 cells (Lattice's limit on control points)
      block.begin = static_cast<std::uint32_t>(begin + i);
      block.end = static_cast<std::uint32_t>(begin + runEnd);
      block.kind = static_cast<Embedding::BlockKind>(k / cellTotal);
      block.blendOffset = static_cast<std::uint32_t>(g.blend.size());
      if (block.kind == Embedding::BlockKind::Blended) {
        for (std::uint32_t r = i; r < runEnd; ++r) g.blend.push_back(t.weight[order[r]]);
      }
      g.blocks.push_back(block);
      i = runEnd;
    }
    for (Eigen::Index p = begin; p < begin + m; ++p) {
      const PointStatus s = e.status_[p];
      g.inside += s == PointStatus::Inside;
      g.outside += s == PointStatus::Outside;
      g.failed += s == PointStatus::Failed;
    }
  };

  // One parallel region; threads take tiles from a shared counter, solve and group them. The
  // calling thread (OpenMP thread 0 of the team) calls the progress hook between its own tiles,
  // each time the points finished by all threads pass another kEmbedProgressChunk; a `false`
  // makes every thread stop after its current tile. Cutting the loop into chunks run one after
  // another instead put a barrier at every chunk end, which on a loaded machine (a thread
  // descheduled while its team-mate waits) cost 7-43 % of the median wall time (docs/ffd-engine.md).
  std::atomic<std::int64_t> next{0};
  std::atomic<Eigen::Index> finished{0};
  std::atomic<bool> stop{false};
  std::exception_ptr hookError;
  Eigen::Index reported = 0;
  const auto callHook = [&](Eigen::Index done) {
    try {
      if (!options.progress(done, n)) stop = true;
    } catch (...) {
      hookError = std::current_exception();
      stop = true;
    }
    reported = done;
  };
  if (options.progress) callHook(0);
#pragma omp parallel if (options.parallel && n >= kParallelPoints)
  {
    const bool caller = omp_get_thread_num() == 0;
    const auto scratch = std::make_unique<TileScratch>();
    const auto first = batched ? std::make_unique<FirstSteps>() : nullptr;
    while (!stop.load(std::memory_order_relaxed)) {
      const std::int64_t tile = next.fetch_add(1, std::memory_order_relaxed);
      if (tile >= tileCount) break;
      const Eigen::Index begin = tile * kTile;
      const Eigen::Index end = std::min<Eigen::Index>(n, begin + kTile);
      if (affine) {
        solveAffineTile(begin, static_cast<std::uint32_t>(end - begin), *scratch);
      } else {
        scratch->pu = scratch->u.data();
        scratch->pv = scratch->v.data();
        scratch->pw = scratch->w.data();
        if (batched) {
          for (Eigen::Index run = begin; run < end; run += FirstSteps::kChunk) {
            const std::uint32_t m = static_cast<std::uint32_t>(std::min<Eigen::Index>(end - run, FirstSteps::kChunk));
            firstSteps(solver, toLocal, points.col(0).data() + run, points.col(1).data() + run,
                       points.col(2).data() + run, m, *first);
            for (std::uint32_t j = 0; j < m; ++j) {
              solvePoint(run + j, static_cast<std::uint32_t>(run + j - begin), *scratch, first.get(), j);
            }
          }
        } else {
          for (Eigen::Index p = begin; p < end; ++p) solvePoint(p, static_cast<std::uint32_t>(p - begin), *scratch);
        }
      }
      groupTile(tile, *scratch);
      const Eigen::Index done = finished.fetch_add(end - begin, std::memory_order_acq_rel) + (end - begin);
      if (caller && options.progress && done < n && done - reported >= kEmbedProgressChunk) callHook(done);
    }
  }
  if (hookError) std::rethrow_exception(hookError);
  if (nonFinite) {
    for (Eigen::Index r = 0; r < n; ++r) {
      if (!points.row(r).allFinite()) throw LatticeError("embed: point " + std::to_string(r) + " is not finite");
    }
  }
  const auto cancelled = [&reported, n] {
    return Cancelled("embed: cancelled after " + std::to_string(reported) + " of " + std::to_string(n) + " points");
  };
  if (stop) throw cancelled();

  bool identity = true;
  for (const TileGroups& g : groups) {
    const std::uint32_t blendBase = static_cast<std::uint32_t>(e.blend_.size());
    for (Embedding::Block block : g.blocks) {
      block.blendOffset += blendBase;
      e.blocks_.push_back(block);
    }
    e.blend_.insert(e.blend_.end(), g.blend.begin(), g.blend.end());
    e.tileBlocks_.push_back(static_cast<std::uint32_t>(e.blocks_.size()));
    e.inside_ += g.inside;
    e.outside_ += g.outside;
    e.failed_ += g.failed;
    identity = identity && g.identity;
  }
  if (identity) {
    Embedding::IndexVector().swap(e.order_);  // never written: only address space was reserved
  } else {
#pragma omp parallel for if (options.parallel && n >= kParallelPoints)
    for (std::int64_t tile = 0; tile < tileCount; ++tile) {
      if (!groups[static_cast<std::size_t>(tile)].identity) continue;
      const Eigen::Index begin = tile * kTile;
      const Eigen::Index end = std::min<Eigen::Index>(n, begin + kTile);
      for (Eigen::Index p = begin; p < end; ++p) e.order_[p] = static_cast<std::uint32_t>(p);
    }
  }
  if (options.progress) {
    callHook(n);
    if (hookError) std::rethrow_exception(hookError);
    if (stop) throw cancelled();
  }
  return e;
}

}  // namespace ffdkit::ffd
