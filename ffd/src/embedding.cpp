#include "ffdkit/ffd/embedding.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <numeric>
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

namespace {

// The blocks, blend weights and counts of every tile, joined in tile order.
struct JoinedTiles {
  std::vector<Embedding::Block> blocks;
  std::vector<double> blend;
  std::vector<std::uint32_t> tileBlocks{0};
  Eigen::Index inside = 0, outside = 0, failed = 0;
  bool identity = true;  // every tile kept the original order
};

// One embed() call (Kuriyama 1996, eq. (6.2)), as the steps it takes: solve each point of a
// tile for (u, v, w) (closed form for an affine rest map, Newton otherwise), apply the outside
// policy, sort the tile by (class, cell) into blocks, and join the tiles. The per-point arrays
// are written here and moved into the Embedding by embed().
class EmbedRun {
 public:
  EmbedRun(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& points, const EmbedOptions& options,
           const detail::RestSolver& solver);

  // Solves and groups every tile in one parallel region, calling the progress hook.
  void solveTiles();
  // Rethrows the progress hook's exception, throws for the first non-finite point, or Cancelled.
  void throwIfStopped() const;
  // The tiles' blocks, blend weights and counts in tile order; fills the original order of the
  // tiles that kept it when another did not, and drops the order when none was permuted.
  JoinedTiles joinTiles();
  // The final progress call (all points done).
  void reportDone();

  Embedding::StatusVector status;
  Embedding::ParameterVector u, v, w;
  Embedding::IndexVector order;

 private:
  PointClass applyOutsidePolicy(const Eigen::Vector3d& q, bool noPreimageOutside, Eigen::Vector3d& uvw,
                                double& weight) const;
  void solvePoint(Eigen::Index p, std::uint32_t i, TileScratch& t, const FirstSteps* first = nullptr,
                  std::uint32_t runIndex = 0);
  void solveAffineTile(Eigen::Index begin, std::uint32_t m, TileScratch& t);
  void solveNewtonTile(Eigen::Index begin, Eigen::Index end, TileScratch& t, FirstSteps* first);
  void sortTileByKey(std::uint32_t m, TileScratch& t) const;
  void permuteTile(Eigen::Index begin, std::uint32_t m, const TileScratch& t);
  void partitionTileByClass(Eigen::Index begin, std::uint32_t m, TileScratch& t);
  void groupTile(std::int64_t tile, TileScratch& t);
  std::uint32_t cellKey(double pu, double pv, double pw) const;
  void callHook(Eigen::Index done);
  Cancelled cancelled() const;

  const Eigen::Ref<const Eigen::MatrixX3d>& points_;
  const EmbedOptions& options_;
  const detail::RestSolver& solver_;
  const Eigen::Index n_;
  const std::int64_t tileCount_;
  const Eigen::Affine3d toLocal_;
  const OutsidePolicy policy_;
  const AxisSpline* axes_[3];
  const std::array<detail::CellLocator, 3> locate_;
  int cells_[3];
  std::int64_t cellTotal_;
  bool periodic_[3];
  bool affine_;
  bool batched_;  // Newton's first steps across points
  Eigen::Matrix3d Ainv_;
  Eigen::Vector3d b_;
  // The closed form's coefficients (affineTile): F^-1, F^-1 translation - b, A^-1, the box.
  double affineCoef_[27];
  // Identity and Extrapolate keep an outside point's parameters as solved: no per-point policy work.
  bool outsideKeepsParameters_;
  std::int64_t outsideClass_;
  std::size_t keyCount_;
  bool counting_;  // few enough keys for a counting sort

  std::vector<TileGroups> groups_;
  // Non-finite input points are found in the same pass (a separate check cost as much as the
  // closed-form embedding itself); embed() then throws for the first one.
  std::atomic<bool> nonFinite_{false};
  std::atomic<bool> stop_{false};
  std::exception_ptr hookError_;
  Eigen::Index reported_ = 0;
};

EmbedRun::EmbedRun(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& points, const EmbedOptions& options,
                   const detail::RestSolver& solver)
    : points_(points),
      options_(options),
      solver_(solver),
      n_(points.rows()),
      tileCount_((points.rows() + kTile - 1) / kTile),
      toLocal_(lattice.frame().inverse()),
      policy_(lattice.outsidePolicy()),
      axes_{&lattice.axis(0), &lattice.axis(1), &lattice.axis(2)},
      locate_{detail::CellLocator(lattice.axis(0)), detail::CellLocator(lattice.axis(1)),
              detail::CellLocator(lattice.axis(2))} {
  for (int a = 0; a < 3; ++a) {
    cells_[a] = axes_[a]->cellCount();
    periodic_[a] = axes_[a]->periodic();
  }
  cellTotal_ = std::int64_t(cells_[0]) * cells_[1] * cells_[2];
  affine_ = lattice.restIsAffine();
  batched_ = !affine_ && solver.batchedFirstStep();
  Ainv_ = lattice.restAffineLinear().inverse();
  b_ = lattice.restAffineOffset();

  const Eigen::Matrix3d L = toLocal_.linear();
  const Eigen::Vector3d T = toLocal_.translation();
  for (int r = 0; r < 3; ++r) {
    const double eps = options.boundaryEpsilon * (axes_[r]->domainMax() - axes_[r]->domainMin());
    for (int c = 0; c < 3; ++c) {
      affineCoef_[3 * r + c] = L(r, c);
      affineCoef_[12 + 3 * r + c] = Ainv_(r, c);
    }
    affineCoef_[9 + r] = T[r] - b_[r];
    affineCoef_[21 + r] = axes_[r]->domainMin() - eps;  // the epsilon-grown parameter box
    affineCoef_[24 + r] = axes_[r]->domainMax() + eps;
  }
  outsideKeepsParameters_ =
      policy_.kind == OutsidePolicy::Kind::Identity || policy_.kind == OutsidePolicy::Kind::Extrapolate;
  outsideClass_ = static_cast<std::int64_t>(policy_.kind == OutsidePolicy::Kind::Identity ? PointClass::Frozen
                                                                                            : PointClass::Evaluated);
  keyCount_ = static_cast<std::size_t>(3 * cellTotal_);
  counting_ = keyCount_ <= 4 * kTile;

  // Written once, tile by tile in parallel: no zero fill first (see NoInitAllocator).
  status.resize(static_cast<std::size_t>(n_));
  u.resize(n_);
  v.resize(n_);
  w.resize(n_);
  order.resize(n_);
  groups_.resize(static_cast<std::size_t>(tileCount_));
}

std::uint32_t EmbedRun::cellKey(double pu, double pv, double pw) const {
  if (cellTotal_ == 1) return 0u;
  return static_cast<std::uint32_t>(locate_[0](pu) + cells_[0] * (locate_[1](pv) + std::int64_t(cells_[1]) * locate_[2](pw)));
}

// What the outside policy does with a point outside the rest lattice: its class, its (clamped)
// parameters, and its blend weight.
PointClass EmbedRun::applyOutsidePolicy(const Eigen::Vector3d& q, bool noPreimageOutside, Eigen::Vector3d& uvw,
                                        double& weight) const {
  switch (policy_.kind) {
    case OutsidePolicy::Kind::Identity:
      return PointClass::Frozen;
    case OutsidePolicy::Kind::Extrapolate:
      return noPreimageOutside ? PointClass::Blended : PointClass::Evaluated;
    case OutsidePolicy::Kind::ClampEdge:
      uvw = solver_.clampToBox(uvw);
      return PointClass::Blended;
    case OutsidePolicy::Kind::Falloff: {
      uvw = solver_.clampToBox(uvw);
      Eigen::Matrix3d J;
      const double x = (solver_.evaluate(uvw, J) - q).norm() / policy_.distance;
      if (x >= 1.0) return PointClass::Frozen;
      weight = 1.0 - x * x * (3.0 - 2.0 * x);  // smoothstep from 1 at the boundary to 0 at `distance`
      return PointClass::Blended;
    }
  }
  return PointClass::Evaluated;
}

// Point p of a tile: (u, v, w), blend weight, (class, cell) key, status (Kuriyama 1996,
// eq. (6.2)). first: the batched first Newton steps of the run point p belongs to (null: none),
// at `runIndex`.
void EmbedRun::solvePoint(Eigen::Index p, std::uint32_t i, TileScratch& t, const FirstSteps* first,
                          std::uint32_t runIndex) {
  if (!points_.row(p).allFinite()) {
    nonFinite_.store(true, std::memory_order_relaxed);
    t.pu[i] = t.pv[i] = t.pw[i] = 0.0;
    t.weight[i] = 0.0;
    t.key[i] = 0;
    status[p] = PointStatus::Failed;
    return;
  }
  const Eigen::Vector3d q = toLocal_ * points_.row(p).transpose();
  Eigen::Vector3d uvw;
  bool converged = true;
  if (affine_) {
    uvw = Ainv_ * (q - b_);
  } else {
    converged = first ? solveNewtonAfterSteps(solver_, q, first, runIndex, uvw) : solveNewton(solver_, q, uvw);
  }
  PointStatus pointStatus = PointStatus::Inside;
  PointClass cls = PointClass::Evaluated;
  double s = 1.0;
  // Outside for certain, yet Newton found no preimage (the lattice's polynomial extension does
  // not reach q): Outside, not Failed, with the closest boundary parameters; no extrapolated
  // preimage exists, so Extrapolate keeps the offset like ClampEdge.
  const bool noPreimageOutside = !converged && solver_.outsideRestHull(q);
  if (noPreimageOutside) uvw = solver_.closestInBox(q);
  if (!converged && !noPreimageOutside) {
    pointStatus = PointStatus::Failed;
    cls = PointClass::Frozen;
    uvw = solver_.clampToBox(uvw);
  } else if (noPreimageOutside || !solver_.insideBox(uvw)) {
    pointStatus = PointStatus::Outside;
    cls = applyOutsidePolicy(q, noPreimageOutside, uvw, s);
  }
  for (int a = 0; a < 3; ++a) {
    if (periodic_[a]) uvw[a] = axes_[a]->wrap(uvw[a]);
  }
  t.pu[i] = uvw[0];
  t.pv[i] = uvw[1];
  t.pw[i] = uvw[2];
  t.weight[i] = s;
  status[p] = pointStatus;
  t.key[i] = static_cast<std::uint32_t>(static_cast<std::int64_t>(cls) * cellTotal_ + cellKey(uvw[0], uvw[1], uvw[2]));
}

// The closed form of an affine rest map, uvw = A^-1 (F^-1 x - b), a tile at a time: the
// arithmetic runs over the columns of the tile (vectorised across points); the few points
// outside the box go through solvePoint for their outside policy.
void EmbedRun::solveAffineTile(Eigen::Index begin, std::uint32_t m, TileScratch& t) {
  t.pu = u.data() + begin;
  t.pv = v.data() + begin;
  t.pw = w.data() + begin;
  const bool anyNonFinite = affineTile(points_.col(0).data() + begin, points_.col(1).data() + begin,
                                       points_.col(2).data() + begin, m, affineCoef_, t.pu, t.pv, t.pw, t.flagged.data());
  if (anyNonFinite) nonFinite_.store(true, std::memory_order_relaxed);
  PointStatus* tileStatus = status.data() + begin;
  std::fill_n(t.weight.data(), m, 1.0);
  const std::uint32_t outsideBase = static_cast<std::uint32_t>(outsideClass_ * cellTotal_);  // an outside point's key offset
  if (outsideKeepsParameters_ && !anyNonFinite) {
    // Every point is finite and keeps its parameters, so flagged means outside: status and key
    // are computed from the flag, not branched on (outside points come in any order, and a
    // branch on them was one of the hot spots of a box embedding with outside points).
    for (std::uint32_t i = 0; i < m; ++i) {
      const std::uint32_t outside = t.flagged[i];  // 0 or 1
      tileStatus[i] = outside ? PointStatus::Outside : PointStatus::Inside;
      t.key[i] = outside * outsideBase + cellKey(t.pu[i], t.pv[i], t.pw[i]);
    }
    return;
  }
  for (std::uint32_t i = 0; i < m; ++i) {
    if (!t.flagged[i]) {
      tileStatus[i] = PointStatus::Inside;
      t.key[i] = cellKey(t.pu[i], t.pv[i], t.pw[i]);
    } else if (outsideKeepsParameters_ && points_.row(begin + i).allFinite()) {
      tileStatus[i] = PointStatus::Outside;
      t.key[i] = outsideBase + cellKey(t.pu[i], t.pv[i], t.pw[i]);
    } else {
      solvePoint(begin + i, i, t);
    }
  }
}

// Newton for points [begin, end) of a tile, into the scratch arrays; with `first`, the first two
// steps batched across runs of FirstSteps::kChunk points.
void EmbedRun::solveNewtonTile(Eigen::Index begin, Eigen::Index end, TileScratch& t, FirstSteps* first) {
  t.pu = t.u.data();
  t.pv = t.v.data();
  t.pw = t.w.data();
  if (!first) {
    for (Eigen::Index p = begin; p < end; ++p) solvePoint(p, static_cast<std::uint32_t>(p - begin), t);
    return;
  }
  for (Eigen::Index run = begin; run < end; run += FirstSteps::kChunk) {
    const std::uint32_t m = static_cast<std::uint32_t>(std::min<Eigen::Index>(end - run, FirstSteps::kChunk));
    firstSteps(solver_, toLocal_, points_.col(0).data() + run, points_.col(1).data() + run,
               points_.col(2).data() + run, m, *first);
    for (std::uint32_t j = 0; j < m; ++j) solvePoint(run + j, static_cast<std::uint32_t>(run + j - begin), t, first, j);
  }
}

// Whether the tile's m keys never decrease, so that sorting by key keeps the original order (a
// stable sort is the identity exactly then). Counted, not searched for: the loop vectorises.
bool keysInOrder(const std::uint32_t* key, std::uint32_t m) {
  std::uint32_t descents = 0;
  for (std::uint32_t i = 1; i < m; ++i) descents += key[i] < key[i - 1];
  return descents == 0;
}

// t.order = the tile's m points sorted by key, stably: a counting sort when the keys are few,
// else a stable sort.
void EmbedRun::sortTileByKey(std::uint32_t m, TileScratch& t) const {
  std::uint32_t* sorted = t.order.data();
  const std::uint32_t* key = t.key.data();
  if (counting_) {
    t.start.assign(keyCount_ + 1, 0u);
    for (std::uint32_t i = 0; i < m; ++i) ++t.start[key[i] + 1];
    for (std::size_t k = 0; k < keyCount_; ++k) t.start[k + 1] += t.start[k];
    for (std::uint32_t i = 0; i < m; ++i) sorted[t.start[key[i]]++] = i;
  } else {
    for (std::uint32_t i = 0; i < m; ++i) sorted[i] = i;
    std::stable_sort(sorted, sorted + m, [key](std::uint32_t lhs, std::uint32_t rhs) { return key[lhs] < key[rhs]; });
  }
}

// The tile's parameters (from the scratch copy) and order in key order t.order.
void EmbedRun::permuteTile(Eigen::Index begin, std::uint32_t m, const TileScratch& t) {
  const std::uint32_t* sorted = t.order.data();
  double* tu = u.data() + begin;
  double* tv = v.data() + begin;
  double* tw = w.data() + begin;
  std::uint32_t* globalOrder = order.data() + begin;
  for (std::uint32_t i = 0; i < m; ++i) {
    tu[i] = t.u[sorted[i]];
    tv[i] = t.v[sorted[i]];
    tw[i] = t.w[sorted[i]];
    globalOrder[i] = static_cast<std::uint32_t>(begin) + sorted[i];
  }
}

// permuteTile(sortTileByKey()) for a single-cell lattice, where the key is the class (0, 1, 2),
// in one pass: a stable partition that moves each point to the cursor of its class as it goes.
// The cursor is selected by masks, not by a branch (outside points come in any order) or by
// indexing an array of counters in memory (each point then waited for the previous one's
// store to the same counter).
void EmbedRun::partitionTileByClass(Eigen::Index begin, std::uint32_t m, TileScratch& t) {
  const std::uint32_t* key = t.key.data();
  std::uint32_t blended = 0, frozen = 0;
  for (std::uint32_t i = 0; i < m; ++i) {
    blended += key[i] == 1;
    frozen += key[i] == 2;
  }
  std::uint32_t atEvaluated = 0, atBlended = m - blended - frozen, atFrozen = m - frozen;
  std::uint32_t* sorted = t.order.data();
  double* tu = u.data() + begin;
  double* tv = v.data() + begin;
  double* tw = w.data() + begin;
  std::uint32_t* globalOrder = order.data() + begin;
  for (std::uint32_t i = 0; i < m; ++i) {
    const std::uint32_t isBlended = key[i] == 1, isFrozen = key[i] == 2;
    const std::uint32_t isEvaluated = 1 - isBlended - isFrozen;
    const std::uint32_t at =
        (atEvaluated & (0u - isEvaluated)) | (atBlended & (0u - isBlended)) | (atFrozen & (0u - isFrozen));
    tu[at] = t.u[i];
    tv[at] = t.v[i];
    tw[at] = t.w[i];
    globalOrder[at] = static_cast<std::uint32_t>(begin) + i;
    sorted[at] = i;
    atEvaluated += isEvaluated;
    atBlended += isBlended;
    atFrozen += isFrozen;
  }
}

// The end of the run of equal keys that starts at sorted position i of m: the keys in sorted
// order never decrease, so a search that doubles its step and then halves it finds the end in
// about 2 log2(run length) probes (a single-cell tile is one or two runs of thousands of points,
// a many-cell tile in random order runs of a few).
std::uint32_t endOfRun(const std::uint32_t* key, const std::uint32_t* sorted, std::uint32_t m, std::uint32_t i) {
  const std::uint32_t k = key[sorted[i]];
  std::uint32_t in = i, step = 1;  // key[sorted[in]] == k
  while (in + step < m && key[sorted[in + step]] == k) {
    in += step;
    step *= 2;
  }
  std::uint32_t out = std::min(in + step, m);  // out == m or key[sorted[out]] > k
  while (out - in > 1) {
    const std::uint32_t mid = in + (out - in) / 2;
    (key[sorted[mid]] == k ? in : out) = mid;
  }
  return out;
}

// Sorts a solved tile by (class, cell), stably, and writes its parameters, order and blocks:
// a block streams one cell's control points over its points in Deformer, while reads and
// writes in original order stay within the tile (cache-local). A tile whose keys are in order
// already (any single-cell lattice with every point inside) keeps the original order.
void EmbedRun::groupTile(std::int64_t tile, TileScratch& t) {
  const Eigen::Index begin = tile * kTile;
  const std::uint32_t m = static_cast<std::uint32_t>(std::min<Eigen::Index>(n_ - begin, kTile));
  TileGroups& g = groups_[static_cast<std::size_t>(tile)];
  const std::uint32_t* sorted = t.order.data();
  const std::uint32_t* key = t.key.data();
  double* tu = u.data() + begin;
  double* tv = v.data() + begin;
  double* tw = w.data() + begin;
  g.identity = keysInOrder(key, m);
  if (g.identity) {
    std::iota(t.order.begin(), t.order.begin() + m, 0u);
    if (t.pu != tu) {
      std::copy_n(t.pu, m, tu);
      std::copy_n(t.pv, m, tv);
      std::copy_n(t.pw, m, tw);
    }
  } else {
    if (t.pu == tu) {  // solved in place: permute from a copy
      std::copy_n(tu, m, t.u.data());
      std::copy_n(tv, m, t.v.data());
      std::copy_n(tw, m, t.w.data());
    }
    if (cellTotal_ == 1) {  // the key is the class
      partitionTileByClass(begin, m, t);
    } else {
      sortTileByKey(m, t);
      permuteTile(begin, m, t);
    }
  }
  // Runs of equal key become blocks.
  for (std::uint32_t i = 0; i < m;) {
    const std::uint32_t k = key[sorted[i]];
    const std::uint32_t runEnd = endOfRun(key, sorted, m, i);
    Embedding::Block block{};
    block.cell = static_cast<std::uint32_t>(k % cellTotal_);  // < 1e8 cells (Lattice's limit on control points)
    block.begin = static_cast<std::uint32_t>(begin + i);
    block.end = static_cast<std::uint32_t>(begin + runEnd);
    block.kind = static_cast<Embedding::BlockKind>(k / cellTotal_);
    block.blendOffset = static_cast<std::uint32_t>(g.blend.size());
    if (block.kind == Embedding::BlockKind::Blended) {
      for (std::uint32_t r = i; r < runEnd; ++r) g.blend.push_back(t.weight[sorted[r]]);
    }
    g.blocks.push_back(block);
    i = runEnd;
  }
  for (Eigen::Index p = begin; p < begin + m; ++p) {
    const PointStatus s = status[p];
    g.inside += s == PointStatus::Inside;
    g.outside += s == PointStatus::Outside;
    g.failed += s == PointStatus::Failed;
  }
}

void EmbedRun::callHook(Eigen::Index done) {
  try {
    if (!options_.progress(done, n_)) stop_ = true;
  } catch (...) {
    hookError_ = std::current_exception();
    stop_ = true;
  }
  reported_ = done;
}

Cancelled EmbedRun::cancelled() const {
  return Cancelled("embed: cancelled after " + std::to_string(reported_) + " of " + std::to_string(n_) + " points");
}

// One parallel region; threads take tiles from a shared counter, solve and group them. The
// calling thread (OpenMP thread 0 of the team) calls the progress hook between its own tiles,
// each time the points finished by all threads pass another kEmbedProgressChunk; a `false`
// makes every thread stop after its current tile. Cutting the loop into chunks run one after
// another instead put a barrier at every chunk end, which on a loaded machine (a thread
// descheduled while its team-mate waits) cost 7-43 % of the median wall time (docs/ffd-engine.md).
void EmbedRun::solveTiles() {
  std::atomic<std::int64_t> next{0};
  std::atomic<Eigen::Index> finished{0};
  if (options_.progress) callHook(0);
#pragma omp parallel if (options_.parallel && n_ >= kParallelPoints)
  {
    const bool caller = omp_get_thread_num() == 0;
    const auto scratch = std::make_unique<TileScratch>();
    const auto first = batched_ ? std::make_unique<FirstSteps>() : nullptr;
    while (!stop_.load(std::memory_order_relaxed)) {
      const std::int64_t tile = next.fetch_add(1, std::memory_order_relaxed);
      if (tile >= tileCount_) break;
      const Eigen::Index begin = tile * kTile;
      const Eigen::Index end = std::min<Eigen::Index>(n_, begin + kTile);
      if (affine_) {
        solveAffineTile(begin, static_cast<std::uint32_t>(end - begin), *scratch);
      } else {
        solveNewtonTile(begin, end, *scratch, first.get());
      }
      groupTile(tile, *scratch);
      const Eigen::Index done = finished.fetch_add(end - begin, std::memory_order_acq_rel) + (end - begin);
      if (caller && options_.progress && done < n_ && done - reported_ >= kEmbedProgressChunk) callHook(done);
    }
  }
}

void EmbedRun::throwIfStopped() const {
  if (hookError_) std::rethrow_exception(hookError_);
  if (nonFinite_) {
    for (Eigen::Index r = 0; r < n_; ++r) {
      if (!points_.row(r).allFinite()) throw LatticeError("embed: point " + std::to_string(r) + " is not finite");
    }
  }
  if (stop_) throw cancelled();
}

JoinedTiles EmbedRun::joinTiles() {
  JoinedTiles joined;
  for (const TileGroups& g : groups_) {
    const std::uint32_t blendBase = static_cast<std::uint32_t>(joined.blend.size());
    for (Embedding::Block block : g.blocks) {
      block.blendOffset += blendBase;
      joined.blocks.push_back(block);
    }
    joined.blend.insert(joined.blend.end(), g.blend.begin(), g.blend.end());
    joined.tileBlocks.push_back(static_cast<std::uint32_t>(joined.blocks.size()));
    joined.inside += g.inside;
    joined.outside += g.outside;
    joined.failed += g.failed;
    joined.identity = joined.identity && g.identity;
  }
  if (joined.identity) {
    Embedding::IndexVector().swap(order);  // never written: only address space was reserved
  } else {
#pragma omp parallel for if (options_.parallel && n_ >= kParallelPoints)
    for (std::int64_t tile = 0; tile < tileCount_; ++tile) {
      if (!groups_[static_cast<std::size_t>(tile)].identity) continue;
      const Eigen::Index begin = tile * kTile;
      const Eigen::Index end = std::min<Eigen::Index>(n_, begin + kTile);
      for (Eigen::Index p = begin; p < end; ++p) order[p] = static_cast<std::uint32_t>(p);
    }
  }
  return joined;
}

void EmbedRun::reportDone() {
  if (!options_.progress) return;
  callHook(n_);
  if (hookError_) std::rethrow_exception(hookError_);
  if (stop_) throw cancelled();
}

}  // namespace

Embedding embed(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& points, const EmbedOptions& options) {
  const Eigen::Index n = points.rows();
  if (n >= static_cast<Eigen::Index>(std::numeric_limits<std::uint32_t>::max())) {
    throw LatticeError("embed: at most 2^32-2 points, got " + std::to_string(n));
  }
  // The tabulated inverse (about 5000 Newton solves) pays for itself from a few 10^4 points on.
  detail::RestSolver solver(lattice, options, /*inverseGrid=*/n >= 4 * kParallelPoints);
  if (solver.wantsInverseGrid()) buildInverseGrid(solver, options.parallel);

  EmbedRun run(lattice, points, options, solver);
  run.solveTiles();
  run.throwIfStopped();
  JoinedTiles joined = run.joinTiles();

  Embedding e;
  e.restRevision_ = lattice.restRevision();
  e.counts_ = lattice.counts();
  e.cellsU_ = lattice.axis(0).cellCount();
  e.cellsV_ = lattice.axis(1).cellCount();
  e.policy_ = lattice.outsidePolicy();
  e.status_ = std::move(run.status);
  e.u_ = std::move(run.u);
  e.v_ = std::move(run.v);
  e.w_ = std::move(run.w);
  e.order_ = std::move(run.order);
  e.blocks_ = std::move(joined.blocks);
  e.blend_ = std::move(joined.blend);
  e.tileBlocks_ = std::move(joined.tileBlocks);
  e.inside_ = joined.inside;
  e.outside_ = joined.outside;
  e.failed_ = joined.failed;
  run.reportDone();
  return e;
}

}  // namespace ffdkit::ffd
