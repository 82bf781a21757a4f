#include "ffdkit/ffd/embedding.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <string>

#include <Eigen/LU>
#include <omp.h>

namespace ffdkit::ffd {
namespace {

constexpr int kMaxBasis = 33;
// Below this many points a parallel region costs more than it saves (thread wake-up, barriers).
constexpr Eigen::Index kParallelPoints = 16384;

// Evaluates Xbar and its Jacobian on the rest lattice; one per thread-safe call, no allocation.
class RestSolver {
 public:
  RestSolver(const Lattice& lattice, const EmbedOptions& options)
      : lattice_(lattice), rest_(lattice.restPoints()), options_(options) {
    for (int a = 0; a < 3; ++a) {
      axis_[a] = &lattice.axis(a);
      lo_[a] = axis_[a]->domainMin();
      hi_[a] = axis_[a]->domainMax();
    }
    range_ = hi_ - lo_;
    tol_ = options.tolerance * lattice.restSize();
    affineInverse_ = lattice.restAffineLinear().inverse();
    if (!affineInverse_.allFinite()) affineInverse_ = Eigen::Matrix3d::Identity();
    cylinder_ = lattice.cylinderRestShape();
    buildWindows();
    if (!lattice.restIsAffine()) buildSamples();
  }

  Eigen::Vector3d evaluate(const Eigen::Vector3d& uvw, Eigen::Matrix3d& J) const {
    double N[3][kMaxBasis];
    double D[3][kMaxBasis];
    int cell[3];
    for (int a = 0; a < 3; ++a) {
      cell[a] = axis_[a]->cellOf(uvw[a]);
      axis_[a]->basis(cell[a], uvw[a], N[a], D[a]);
    }
    const int nu = axis_[0]->degree() + 1;
    const int nv = axis_[1]->degree() + 1;
    const int nw = axis_[2]->degree() + 1;
    const double* W = windows_.data() +
                      3 * windowSize_ * (cell[0] + cells_[0] * (cell[1] + static_cast<std::size_t>(cells_[1]) * cell[2]));
    double x[3] = {0, 0, 0}, ju[3] = {0, 0, 0}, jv[3] = {0, 0, 0}, jw[3] = {0, 0, 0};
    for (int c = 0; c < nw; ++c) {
      for (int b = 0; b < nv; ++b) {
        double s[3] = {0, 0, 0}, su[3] = {0, 0, 0};
        for (int a = 0; a < nu; ++a, W += 3) {
          for (int d = 0; d < 3; ++d) {
            s[d] += N[0][a] * W[d];
            su[d] += D[0][a] * W[d];
          }
        }
        const double nn = N[1][b] * N[2][c];
        const double dn = D[1][b] * N[2][c];
        const double nd = N[1][b] * D[2][c];
        for (int d = 0; d < 3; ++d) {
          x[d] += nn * s[d];
          ju[d] += nn * su[d];
          jv[d] += dn * s[d];
          jw[d] += nd * s[d];
        }
      }
    }
    J << ju[0], jv[0], jw[0], ju[1], jv[1], jw[1], ju[2], jv[2], jw[2];
    return Eigen::Vector3d(x[0], x[1], x[2]);
  }

  // Wraps periodic axes, reflects through the axis of a solid cylinder, keeps iterates bounded.
  void normalize(Eigen::Vector3d& uvw) const {
    if (cylinder_ && cylinder_->innerRadius == 0.0 && uvw[0] < lo_[0]) {
      if (lattice_.counts()[1] % 2 == 0) {
        // Xbar(lo - d, v) == Xbar(lo + d, v + 1/2) when the ring of control points is point-symmetric.
        uvw[0] = 2.0 * lo_[0] - uvw[0];
        uvw[1] += 0.5;
      } else {
        uvw[0] = lo_[0];
      }
    }
    for (int a = 0; a < 3; ++a) {
      if (axis_[a]->periodic()) {
        uvw[a] = axis_[a]->wrap(uvw[a]);
      } else {
        uvw[a] = std::clamp(uvw[a], lo_[a] - 2.0 * range_[a], hi_[a] + 2.0 * range_[a]);
      }
    }
  }

  Eigen::Vector3d initialGuess(const Eigen::Vector3d& q) const {
    Eigen::Vector3d uvw;
    if (cylinder_) {
      const double r = std::hypot(q.x(), q.y());
      const double angle = r > 0.0 ? std::atan2(q.y(), q.x()) : 0.0;
      uvw[0] = lo_[0] + range_[0] * (r - cylinder_->innerRadius) / (cylinder_->outerRadius - cylinder_->innerRadius);
      uvw[1] = angle / (2.0 * std::numbers::pi);
      uvw[2] = lo_[2] + range_[2] * (q.z() - cylinder_->zMin) / (cylinder_->zMax - cylinder_->zMin);
    } else {
      uvw = affineInverse_ * (q - lattice_.restAffineOffset());
    }
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(uvw[a])) uvw[a] = 0.5 * (lo_[a] + hi_[a]);
      if (!axis_[a]->periodic()) uvw[a] = std::clamp(uvw[a], lo_[a] - 0.5 * range_[a], hi_[a] + 0.5 * range_[a]);
    }
    normalize(uvw);
    return uvw;
  }

  // Damped Newton; returns true on convergence. uvw: initial guess in, last iterate out.
  bool newton(const Eigen::Vector3d& q, Eigen::Vector3d& uvw) const {
    Eigen::Matrix3d J;
    Eigen::Vector3d F = evaluate(uvw, J) - q;
    double f = F.norm();
    for (int it = 0; it < options_.maxIterations; ++it) {
      if (f <= tol_) return true;
      Eigen::Vector3d delta;
      const double det = J.determinant();
      const double scale = J.norm();
      if (std::abs(det) > 1e-10 * scale * scale * scale) {
        delta = -(J.inverse() * F);
      } else {
        // Levenberg-Marquardt step where the Jacobian is (nearly) singular, e.g. on a cylinder's axis.
        const Eigen::Matrix3d JtJ = J.transpose() * J;
        const double mu = 1e-8 * JtJ.trace() + std::numeric_limits<double>::min();
        delta = -(JtJ + mu * Eigen::Matrix3d::Identity()).ldlt().solve(J.transpose() * F);
      }
      if (!delta.allFinite()) return false;
      bool accepted = false;
      double step = 1.0;
      for (int halving = 0; halving < 30; ++halving, step *= 0.5) {
        Eigen::Vector3d trial = uvw + step * delta;
        normalize(trial);
        Eigen::Matrix3d Jt;
        const Eigen::Vector3d Ft = evaluate(trial, Jt) - q;
        const double ft = Ft.norm();
        if (ft < f || ft <= tol_) {
          uvw = trial;
          F = Ft;
          f = ft;
          J = Jt;
          accepted = true;
          break;
        }
      }
      if (!accepted) return f <= tol_;
    }
    return f <= tol_;
  }

  // Nearest sample of a coarse parameter grid: the restart point when Newton from the first guess fails.
  Eigen::Vector3d nearestSample(const Eigen::Vector3d& q) const {
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector3d uvw = 0.5 * (lo_ + hi_);
    for (std::size_t s = 0; s < sampleX_.size(); ++s) {
      const double d = (sampleX_[s] - q).squaredNorm();
      if (d < best) {
        best = d;
        uvw = sampleUvw_[s];
      }
    }
    return uvw;
  }

  bool insideBox(const Eigen::Vector3d& uvw) const {
    for (int a = 0; a < 3; ++a) {
      if (axis_[a]->periodic()) continue;
      const double eps = options_.boundaryEpsilon * range_[a];
      if (uvw[a] < lo_[a] - eps || uvw[a] > hi_[a] + eps) return false;
    }
    return true;
  }

  Eigen::Vector3d clampToBox(Eigen::Vector3d uvw) const {
    for (int a = 0; a < 3; ++a) {
      if (!axis_[a]->periodic()) uvw[a] = std::clamp(uvw[a], lo_[a], hi_[a]);
    }
    return uvw;
  }

  const Eigen::Vector3d& lo() const { return lo_; }
  const Eigen::Vector3d& hi() const { return hi_; }

 private:
  // Each cell's rest control points, contiguous (x, y, z per point, a fastest): Newton evaluates
  // Xbar many times per point, and gathering through the lattice's index map dominated it.
  void buildWindows() {
    const int nu = axis_[0]->degree() + 1;
    const int nv = axis_[1]->degree() + 1;
    const int nw = axis_[2]->degree() + 1;
    windowSize_ = static_cast<std::size_t>(nu) * nv * nw;
    for (int a = 0; a < 3; ++a) cells_[a] = axis_[a]->cellCount();
    windows_.reserve(3 * windowSize_ * cells_[0] * cells_[1] * cells_[2]);
    for (int cw = 0; cw < cells_[2]; ++cw)
      for (int cv = 0; cv < cells_[1]; ++cv)
        for (int cu = 0; cu < cells_[0]; ++cu)
          for (int c = 0; c < nw; ++c)
            for (int b = 0; b < nv; ++b)
              for (int a = 0; a < nu; ++a) {
                const Eigen::Index f = lattice_.index(axis_[0]->controlIndex(cu, a), axis_[1]->controlIndex(cv, b),
                                                      axis_[2]->controlIndex(cw, c));
                for (int d = 0; d < 3; ++d) windows_.push_back(rest_(f, d));
              }
  }

  void buildSamples() {
    int n[3];
    for (int a = 0; a < 3; ++a) n[a] = std::min(2 * axis_[a]->cellCount() + 1, 12) + (axis_[a]->periodic() ? 0 : 1);
    Eigen::Matrix3d J;
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          const int idx[3] = {i, j, k};
          Eigen::Vector3d uvw;
          for (int a = 0; a < 3; ++a) {
            const double t = axis_[a]->periodic() ? double(idx[a]) / n[a] : double(idx[a]) / (n[a] - 1);
            uvw[a] = lo_[a] + range_[a] * t;
          }
          sampleUvw_.push_back(uvw);
          sampleX_.push_back(evaluate(uvw, J));
        }
  }

  const Lattice& lattice_;
  const Eigen::MatrixX3d& rest_;
  EmbedOptions options_;
  const AxisSpline* axis_[3];
  Eigen::Vector3d lo_, hi_, range_;
  double tol_;
  Eigen::Matrix3d affineInverse_;
  std::optional<CylinderRestShape> cylinder_;
  std::vector<double> windows_;
  std::size_t windowSize_ = 0;
  int cells_[3] = {0, 0, 0};
  std::vector<Eigen::Vector3d> sampleUvw_;
  std::vector<Eigen::Vector3d> sampleX_;
};

enum class PointClass : std::uint8_t { Evaluated = 0, Blended = 1, Frozen = 2 };

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
  if (!points.allFinite()) {
    for (Eigen::Index r = 0; r < n; ++r) {
      if (!points.row(r).allFinite()) throw LatticeError("embed: point " + std::to_string(r) + " is not finite");
    }
  }
  const RestSolver solver(lattice, options);
  const Eigen::Affine3d toLocal = lattice.frame().inverse();
  const OutsidePolicy policy = lattice.outsidePolicy();
  const AxisSpline* axes[3] = {&lattice.axis(0), &lattice.axis(1), &lattice.axis(2)};
  const int cells[3] = {axes[0]->cellCount(), axes[1]->cellCount(), axes[2]->cellCount()};
  const std::int64_t cellTotal = std::int64_t(cells[0]) * cells[1] * cells[2];

  Embedding e;
  e.restRevision_ = lattice.restRevision();
  e.counts_ = lattice.counts();
  e.policy_ = policy;
  e.status_.resize(static_cast<std::size_t>(n));
  std::vector<double> u(n), v(n), w(n), weight(n);
  std::vector<std::uint32_t> key(n);
  const bool affine = lattice.restIsAffine();
  const Eigen::Matrix3d Ainv = lattice.restAffineLinear().inverse();
  const Eigen::Vector3d b = lattice.restAffineOffset();

  // Solves point p into u, v, w, weight, key and e.status_.
  const auto solve = [&](Eigen::Index p) {
    const Eigen::Vector3d q = toLocal * points.row(p).transpose();
    Eigen::Vector3d uvw;
    bool converged = true;
    if (affine) {
      uvw = Ainv * (q - b);
    } else {
      uvw = solver.initialGuess(q);
      converged = solver.newton(q, uvw);
      if (!converged) {
        Eigen::Vector3d restart = solver.nearestSample(q);
        if (solver.newton(q, restart)) {
          uvw = restart;
          converged = true;
        }
      }
    }
    PointStatus status = PointStatus::Inside;
    PointClass cls = PointClass::Evaluated;
    double s = 1.0;
    if (!converged) {
      status = PointStatus::Failed;
      cls = PointClass::Frozen;
      uvw = solver.clampToBox(uvw);
    } else if (!solver.insideBox(uvw)) {
      status = PointStatus::Outside;
      switch (policy.kind) {
        case OutsidePolicy::Kind::Identity:
          cls = PointClass::Frozen;
          break;
        case OutsidePolicy::Kind::Extrapolate:
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
    for (int a = 0; a < 3; ++a) uvw[a] = axes[a]->wrap(uvw[a]);
    u[p] = uvw[0];
    v[p] = uvw[1];
    w[p] = uvw[2];
    weight[p] = s;
    e.status_[p] = status;
    const std::int64_t cell = axes[0]->cellOf(uvw[0]) + cells[0] * (axes[1]->cellOf(uvw[1]) + std::int64_t(cells[1]) * axes[2]->cellOf(uvw[2]));
    key[p] = static_cast<std::uint32_t>(static_cast<std::int64_t>(cls) * cellTotal + cell);
  };

  // One parallel region; threads take blocks of kBlock points from a shared counter. The calling
  // thread (OpenMP thread 0 of the team) calls the progress hook between its own blocks, each
  // time the points finished by all threads pass another kEmbedProgressChunk; a `false` makes
  // every thread stop after its current block. Cutting the loop into chunks run one after
  // another instead put a barrier at every chunk end, which on a loaded machine (a thread
  // descheduled while its team-mate waits) cost 7-43 % of the median wall time (docs/ffd-engine.md).
  constexpr Eigen::Index kBlock = 1024;
  std::atomic<Eigen::Index> next{0};
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
    while (!stop.load(std::memory_order_relaxed)) {
      const Eigen::Index begin = next.fetch_add(kBlock, std::memory_order_relaxed);
      if (begin >= n) break;
      const Eigen::Index end = std::min(n, begin + kBlock);
      for (Eigen::Index p = begin; p < end; ++p) solve(p);
      const Eigen::Index done = finished.fetch_add(end - begin, std::memory_order_acq_rel) + (end - begin);
      if (caller && options.progress && done < n && done - reported >= kEmbedProgressChunk) callHook(done);
    }
  }
  if (hookError) std::rethrow_exception(hookError);
  const auto cancelled = [&reported, n] {
    return Cancelled("embed: cancelled after " + std::to_string(reported) + " of " + std::to_string(n) + " points");
  };
  if (stop) throw cancelled();

  // Per tile of consecutive points, a counting sort by (class, cell): stable, so a single-cell
  // lattice keeps the original order, and reads/writes in original order stay within the tile.
  const std::size_t keyCount = static_cast<std::size_t>(3 * cellTotal);
  std::vector<std::uint32_t> order(n);
  std::vector<std::uint32_t> start(keyCount + 1);
  const bool counting = keyCount <= 4 * Embedding::kTileSize;
  for (Eigen::Index tileBegin = 0; tileBegin < n; tileBegin += Embedding::kTileSize) {
    const Eigen::Index tileEnd = std::min<Eigen::Index>(n, tileBegin + Embedding::kTileSize);
    std::uint32_t* tileOrder = order.data() + tileBegin;
    for (Eigen::Index p = tileBegin; p < tileEnd; ++p) tileOrder[p - tileBegin] = static_cast<std::uint32_t>(p);
    if (counting) {
      std::fill(start.begin(), start.end(), 0u);
      for (Eigen::Index p = tileBegin; p < tileEnd; ++p) ++start[key[p] + 1];
      for (std::size_t k = 0; k < keyCount; ++k) start[k + 1] += start[k];
      for (Eigen::Index p = tileBegin; p < tileEnd; ++p) tileOrder[start[key[p]]++] = static_cast<std::uint32_t>(p);
    } else {
      std::stable_sort(tileOrder, tileOrder + (tileEnd - tileBegin),
                       [&key](std::uint32_t lhs, std::uint32_t rhs) { return key[lhs] < key[rhs]; });
    }
    // Runs of equal key become blocks.
    for (Eigen::Index q = tileBegin; q < tileEnd;) {
      const std::uint32_t k = key[order[q]];
      Eigen::Index runEnd = q + 1;
      while (runEnd < tileEnd && key[order[runEnd]] == k) ++runEnd;
      const std::int64_t cls = k / cellTotal;
      const std::int64_t cell = k % cellTotal;
      Embedding::Block block{};
      block.cell[0] = static_cast<int>(cell % cells[0]);
      block.cell[1] = static_cast<int>((cell / cells[0]) % cells[1]);
      block.cell[2] = static_cast<int>(cell / (std::int64_t(cells[0]) * cells[1]));
      block.begin = static_cast<std::uint32_t>(q);
      block.end = static_cast<std::uint32_t>(runEnd);
      block.kind = static_cast<Embedding::BlockKind>(cls);
      block.blendOffset = static_cast<std::uint32_t>(e.blend_.size());
      if (block.kind == Embedding::BlockKind::Blended) {
        for (Eigen::Index r = q; r < runEnd; ++r) e.blend_.push_back(weight[order[r]]);
      }
      e.blocks_.push_back(block);
      q = runEnd;
    }
    e.tileBlocks_.push_back(static_cast<std::uint32_t>(e.blocks_.size()));
  }
  e.u_.resize(n);
  e.v_.resize(n);
  e.w_.resize(n);
  bool identity = true;
  for (Eigen::Index q = 0; q < n; ++q) {
    const std::uint32_t p = order[q];
    identity = identity && p == static_cast<std::uint32_t>(q);
    e.u_[q] = u[p];
    e.v_[q] = v[p];
    e.w_[q] = w[p];
  }
  if (!identity) e.order_ = std::move(order);
  e.blend_.shrink_to_fit();
  for (const PointStatus s : e.status_) {
    if (s == PointStatus::Inside) ++e.inside_;
    else if (s == PointStatus::Outside) ++e.outside_;
    else ++e.failed_;
  }
  if (options.progress) {
    callHook(n);
    if (hookError) std::rethrow_exception(hookError);
    if (stop) throw cancelled();
  }
  return e;
}

}  // namespace ffdkit::ffd
