#include "ffdkit/ffd/deformer.h"

#include <algorithm>
#include <string>
#include <vector>

#include "ffdkit/ffd/huge_pages.h"
#include "vector_clones.h"

namespace ffdkit::ffd {
namespace detail {

constexpr int kLanes = 8;
constexpr int kMaxBasis = 33;

// Eight lanes of doubles: one AVX-512 register, two AVX2 registers, or four SSE2 registers,
// depending on the clone. GCC vector extensions keep the lane structure explicit.
typedef double Lane __attribute__((vector_size(kLanes * sizeof(double))));

// Everything a block kernel needs, flattened into plain arrays.
struct AxisView {
  const double* knots;
  int degree;
  const int* cellSpan;
};

struct KernelInput {
  AxisView axis[3];
  const double* u;
  const double* v;
  const double* w;
  const std::uint32_t* order;  // null: identity
  const double* blend;         // weights of the current Blended block, indexed by q - blendBegin
  std::uint32_t blendBegin;
  const double* qx;  // input columns (original order), null for updates
  const double* qy;
  const double* qz;
  double* ox;  // output columns
  double* oy;
  double* oz;
};

FFDKIT_INLINE Lane splat(double x) { return Lane{} + x; }

// The degree+1 basis values of eight parameters on one span (Cox-de Boor, The NURBS Book A2.2),
// vectorised across lanes: the knots are the same for every lane of a cell. P >= 0 fixes the
// degree at compile time (full unrolling); P < 0 reads it from the axis.
template <int P>
FFDKIT_INLINE void basisLanes(const AxisView& axis, int cell, Lane t, Lane* N) {
  const int p = P >= 0 ? P : axis.degree;
  const int s = axis.cellSpan[cell];
  const double* U = axis.knots;
  Lane left[kMaxBasis];
  Lane right[kMaxBasis];
  N[0] = splat(1.0);
  for (int j = 1; j <= p; ++j) {
    left[j] = t - U[s + 1 - j];
    right[j] = U[s + j] - t;
    Lane saved = splat(0.0);
    for (int r = 0; r < j; ++r) {
      const Lane temp = N[r] * (1.0 / (U[s + r + 1] - U[s + 1 - j + r]));
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
}

FFDKIT_INLINE Lane loadLanes(const double* src, std::uint32_t q, int count) {
  Lane x;
  if (count == kLanes) {
    __builtin_memcpy(&x, src + q, sizeof(Lane));
  } else {
    for (int l = 0; l < kLanes; ++l) x[l] = src[q + std::min(l, count - 1)];
  }
  return x;
}

FFDKIT_INLINE void storeLanes(const KernelInput& in, std::uint32_t q0, int count, bool blended, Lane dx, Lane dy, Lane dz,
                       bool accumulate) {
  if (blended) {
    Lane s = splat(1.0);
    for (int l = 0; l < kLanes; ++l) s[l] = in.blend[q0 + std::min(l, count - 1) - in.blendBegin];
    dx *= s;
    dy *= s;
    dz *= s;
  }
  if (!in.order && count == kLanes) {
    // Identity order: contiguous vector loads and stores.
    Lane x, y, z;
    if (accumulate) {
      __builtin_memcpy(&x, in.ox + q0, sizeof(Lane));
      __builtin_memcpy(&y, in.oy + q0, sizeof(Lane));
      __builtin_memcpy(&z, in.oz + q0, sizeof(Lane));
    } else {
      __builtin_memcpy(&x, in.qx + q0, sizeof(Lane));
      __builtin_memcpy(&y, in.qy + q0, sizeof(Lane));
      __builtin_memcpy(&z, in.qz + q0, sizeof(Lane));
    }
    x += dx;
    y += dy;
    z += dz;
    __builtin_memcpy(in.ox + q0, &x, sizeof(Lane));
    __builtin_memcpy(in.oy + q0, &y, sizeof(Lane));
    __builtin_memcpy(in.oz + q0, &z, sizeof(Lane));
    return;
  }
  for (int l = 0; l < count; ++l) {
    const std::uint32_t q = q0 + l;
    const std::size_t p = in.order ? in.order[q] : q;
    if (accumulate) {
      in.ox[p] += dx[l];
      in.oy[p] += dy[l];
      in.oz[p] += dz[l];
    } else {
      in.ox[p] = in.qx[p] + dx[l];
      in.oy[p] = in.qy[p] + dy[l];
      in.oz[p] = in.qz[p] + dz[l];
    }
  }
}

// Dense block: d = sum_abc Bu_a Bv_b Bw_c W_abc over the cell window W (world displacements, or
// their change); accumulate = false: out = Q + s d, true: out += s d.
template <int P>
FFDKIT_INLINE void denseBlockT(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                        const double* Wx, const double* Wy, const double* Wz, bool accumulate) {
  const int nu = (P >= 0 ? P : in.axis[0].degree) + 1;
  const int nv = (P >= 0 ? P : in.axis[1].degree) + 1;
  const int nw = (P >= 0 ? P : in.axis[2].degree) + 1;
  Lane bu[kMaxBasis], bv[kMaxBasis], bw[kMaxBasis];
  for (std::uint32_t q0 = begin; q0 < end; q0 += kLanes) {
    const int count = static_cast<int>(std::min<std::uint32_t>(kLanes, end - q0));
    basisLanes<P>(in.axis[0], cell[0], loadLanes(in.u, q0, count), bu);
    basisLanes<P>(in.axis[1], cell[1], loadLanes(in.v, q0, count), bv);
    basisLanes<P>(in.axis[2], cell[2], loadLanes(in.w, q0, count), bw);
    Lane dx = splat(0.0), dy = splat(0.0), dz = splat(0.0);
    int wi = 0;
    for (int c = 0; c < nw; ++c) {
      for (int b = 0; b < nv; ++b) {
        Lane sx = splat(0.0), sy = splat(0.0), sz = splat(0.0);
        for (int a = 0; a < nu; ++a, ++wi) {
          sx += bu[a] * Wx[wi];
          sy += bu[a] * Wy[wi];
          sz += bu[a] * Wz[wi];
        }
        const Lane nn = bv[b] * bw[c];
        dx += nn * sx;
        dy += nn * sy;
        dz += nn * sz;
      }
    }
    storeLanes(in, q0, count, blended, dx, dy, dz, accumulate);
  }
}

FFDKIT_VECTOR_CLONES
void denseBlock(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                const double* Wx, const double* Wy, const double* Wz, bool accumulate) {
  const int p = in.axis[0].degree;
  if (p == in.axis[1].degree && p == in.axis[2].degree) {
    switch (p) {
      case 1: return denseBlockT<1>(in, cell, begin, end, blended, Wx, Wy, Wz, accumulate);
      case 2: return denseBlockT<2>(in, cell, begin, end, blended, Wx, Wy, Wz, accumulate);
      case 3: return denseBlockT<3>(in, cell, begin, end, blended, Wx, Wy, Wz, accumulate);
      default: break;
    }
  }
  denseBlockT<-1>(in, cell, begin, end, blended, Wx, Wy, Wz, accumulate);
}

struct SparseTerm {
  int a, b, c;
  double dx, dy, dz;
};

// Sparse block: out += s * sum over changed control points of Bu_a Bv_b Bw_c dP.
FFDKIT_VECTOR_CLONES
void sparseBlock(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                 const SparseTerm* terms, int termCount) {
  Lane bu[kMaxBasis], bv[kMaxBasis], bw[kMaxBasis];
  for (std::uint32_t q0 = begin; q0 < end; q0 += kLanes) {
    const int count = static_cast<int>(std::min<std::uint32_t>(kLanes, end - q0));
    basisLanes<-1>(in.axis[0], cell[0], loadLanes(in.u, q0, count), bu);
    basisLanes<-1>(in.axis[1], cell[1], loadLanes(in.v, q0, count), bv);
    basisLanes<-1>(in.axis[2], cell[2], loadLanes(in.w, q0, count), bw);
    Lane dx = splat(0.0), dy = splat(0.0), dz = splat(0.0);
    for (int i = 0; i < termCount; ++i) {
      const SparseTerm& term = terms[i];
      const Lane weight = bu[term.a] * bv[term.b] * bw[term.c];
      dx += weight * term.dx;
      dy += weight * term.dy;
      dz += weight * term.dz;
    }
    storeLanes(in, q0, count, blended, dx, dy, dz, true);
  }
}

}  // namespace detail

namespace {

// Below this many points a parallel region costs more than it saves (thread wake-up, barriers).
constexpr Eigen::Index kParallelPoints = 16384;

detail::KernelInput makeInput(const Lattice& lattice, const Embedding& e, Eigen::MatrixX3d& out) {
  detail::KernelInput in{};
  for (int a = 0; a < 3; ++a) {
    // cellSpan is stored per cell inside AxisSpline; expose it as a plain array.
    in.axis[a].knots = lattice.axis(a).knots().data();
    in.axis[a].degree = lattice.axis(a).degree();
  }
  in.u = e.sortedU().data();
  in.v = e.sortedV().data();
  in.w = e.sortedW().data();
  in.order = e.order().empty() ? nullptr : e.order().data();
  in.ox = out.col(0).data();
  in.oy = out.col(1).data();
  in.oz = out.col(2).data();
  return in;
}

// Per axis: cell -> knot span, and the control indices of each cell's window.
struct AxisTables {
  std::vector<int> span[3];
  std::vector<int> window[3];  // window[a][cell * (p+1) + r] = control index
};

AxisTables makeTables(const Lattice& lattice) {
  AxisTables t;
  for (int a = 0; a < 3; ++a) {
    const AxisSpline& axis = lattice.axis(a);
    for (int c = 0; c < axis.cellCount(); ++c) {
      t.span[a].push_back(axis.cellSpan(c));
      for (int r = 0; r <= axis.degree(); ++r) t.window[a].push_back(axis.controlIndex(c, r));
    }
  }
  return t;
}

void gatherWindow(const Lattice& lattice, const AxisTables& tables, const int cell[3], const Eigen::MatrixX3d& D,
                  std::vector<double>& W) {
  const int nu = lattice.axis(0).degree() + 1;
  const int nv = lattice.axis(1).degree() + 1;
  const int nw = lattice.axis(2).degree() + 1;
  const std::size_t size = static_cast<std::size_t>(nu) * nv * nw;
  W.resize(3 * size);
  std::size_t wi = 0;
  for (int c = 0; c < nw; ++c) {
    const int k = tables.window[2][cell[2] * nw + c];
    for (int b = 0; b < nv; ++b) {
      const int j = tables.window[1][cell[1] * nv + b];
      for (int a = 0; a < nu; ++a, ++wi) {
        const Eigen::Index f = lattice.index(tables.window[0][cell[0] * nu + a], j, k);
        W[wi] = D(f, 0);
        W[size + wi] = D(f, 1);
        W[2 * size + wi] = D(f, 2);
      }
    }
  }
}

}  // namespace

Deformer::Deformer(Embedding embedding) : embedding_(std::move(embedding)) {}

const Eigen::MatrixX3d& Deformer::deform(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& input) {
  embedding_.checkLattice(lattice);
  return deformStale(lattice, input);
}

const Eigen::MatrixX3d& Deformer::deformStale(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& input) {
  if (lattice.counts() != embedding_.latticeCounts()) embedding_.checkLattice(lattice);  // throws with the details
  const Eigen::Index n = embedding_.pointCount();
  if (input.rows() != n) {
    throw LatticeError("Deformer::deform: expected " + std::to_string(n) + " x 3 input points (the embedded ones), got " +
                       std::to_string(input.rows()) + " x 3");
  }
  if (output_.rows() != n) {
    output_.resize(n, 3);
    adviseHugePages(output_);
  }
  evaluateBlocks(lattice, input, nullptr);
  lastControl_ = lattice.controlPoints();
  deformed_ = true;
  stats_ = DeformStats{true, 0, n};
  return output_;
}

Eigen::Index Deformer::evaluateBlocks(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& input,
                                      const std::vector<char>* cellFilter) {
  const Eigen::Index n = embedding_.pointCount();
  // World displacement of every control point: F.linear * (P - Pbar).
  const Eigen::MatrixX3d D = (lattice.controlPoints() - lattice.restPoints()) * lattice.frame().linear().transpose();
  const AxisTables tables = makeTables(lattice);
  detail::KernelInput in = makeInput(lattice, embedding_, output_);
  for (int a = 0; a < 3; ++a) in.axis[a].cellSpan = tables.span[a].data();
  in.qx = input.col(0).data();
  in.qy = input.col(1).data();
  in.qz = input.col(2).data();
  const int cells[2] = {lattice.axis(0).cellCount(), lattice.axis(1).cellCount()};
  const auto& blocks = embedding_.blocks();
  const auto& tiles = embedding_.tileBlocks();
  const std::int64_t tileCount = static_cast<std::int64_t>(tiles.size()) - 1;
  auto inFilter = [&](const Embedding::Block& block) {
    return !cellFilter ||
           (*cellFilter)[block.cell[0] + cells[0] * (block.cell[1] + static_cast<std::size_t>(cells[1]) * block.cell[2])];
  };
  // Few points to evaluate (a small incremental update): stay on this thread; waking OpenMP
  // workers costs more, and on a busy machine their spinning slows everything else down.
  Eigen::Index work = n;
  if (cellFilter) {
    work = 0;
    for (const Embedding::Block& block : blocks) work += inFilter(block) ? block.end - block.begin : 0;
  }
  const bool parallel = parallel_ && work >= kParallelPoints;
  Eigen::Index evaluated = 0;
#pragma omp parallel if (parallel) reduction(+ : evaluated)
  {
    std::vector<double> W;
    int lastCell[3] = {-1, -1, -1};
    detail::KernelInput local = in;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t t = 0; t < tileCount; ++t) {
      for (std::uint32_t bi = tiles[t]; bi < tiles[t + 1]; ++bi) {
        const Embedding::Block& block = blocks[bi];
        if (!inFilter(block)) continue;
        if (block.kind == Embedding::BlockKind::Frozen) {
          // Identity outside, Failed, beyond Falloff: the input unchanged.
          for (std::uint32_t q = block.begin; q < block.end; ++q) {
            const Eigen::Index p = in.order ? in.order[q] : q;
            output_.row(p) = input.row(p);
          }
          continue;
        }
        if (!std::equal(block.cell, block.cell + 3, lastCell)) {
          gatherWindow(lattice, tables, block.cell, D, W);
          std::copy(block.cell, block.cell + 3, lastCell);
        }
        const bool blended = block.kind == Embedding::BlockKind::Blended;
        if (blended) {
          local.blend = embedding_.blendWeight().data() + block.blendOffset;
          local.blendBegin = block.begin;
        }
        evaluated += block.end - block.begin;
        const std::size_t size = W.size() / 3;
        detail::denseBlock(local, block.cell, block.begin, block.end, blended, W.data(), W.data() + size,
                           W.data() + 2 * size, false);
      }
    }
  }
  return evaluated;
}

const Eigen::MatrixX3d& Deformer::update(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& input) {
  embedding_.checkLattice(lattice);
  if (!deformed_) throw LatticeError("Deformer::update: call deform() once before incremental updates");
  if (input.rows() != embedding_.pointCount()) {
    throw LatticeError("Deformer::update: expected " + std::to_string(embedding_.pointCount()) +
                       " x 3 input points (the embedded ones), got " + std::to_string(input.rows()) + " x 3");
  }
  const Eigen::MatrixX3d& P = lattice.controlPoints();
  // Cells whose window holds a control point that moved since the last call.
  int np[3], cells[3];
  for (int a = 0; a < 3; ++a) {
    np[a] = lattice.axis(a).degree() + 1;
    cells[a] = lattice.axis(a).cellCount();
  }
  std::vector<std::vector<int>> cellsOf[3];  // cellsOf[a][i]: cells whose window holds index i on axis a
  for (int a = 0; a < 3; ++a) {
    cellsOf[a].resize(lattice.counts()[a]);
    for (int c = 0; c < cells[a]; ++c)
      for (int r = 0; r < np[a]; ++r) cellsOf[a][lattice.axis(a).controlIndex(c, r)].push_back(c);
  }
  std::vector<char> touched(static_cast<std::size_t>(cells[0]) * cells[1] * cells[2], 0);
  Eigen::Index changed = 0;
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    if (P.row(f) == lastControl_.row(f)) continue;
    ++changed;
    const Eigen::Vector3i g = lattice.gridIndex(f);
    for (int cw : cellsOf[2][g[2]])
      for (int cv : cellsOf[1][g[1]])
        for (int cu : cellsOf[0][g[0]]) touched[cu + cells[0] * (cv + static_cast<std::size_t>(cells[1]) * cw)] = 1;
  }
  stats_ = DeformStats{false, changed, 0};
  if (changed == 0) return output_;
  stats_.evaluatedPoints = evaluateBlocks(lattice, input, &touched);
  lastControl_ = P;
  return output_;
}

const Eigen::MatrixX3d& Deformer::update(const Lattice& lattice) {
  embedding_.checkLattice(lattice);
  if (!deformed_) throw LatticeError("Deformer::update: call deform() once before incremental updates");
  const Eigen::MatrixX3d& P = lattice.controlPoints();
  std::vector<Eigen::Index> changed;
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    if (P.row(f) != lastControl_.row(f)) changed.push_back(f);
  }
  stats_ = DeformStats{false, static_cast<Eigen::Index>(changed.size()), 0};
  if (changed.empty()) return output_;
  const Eigen::MatrixX3d D = (P - lastControl_) * lattice.frame().linear().transpose();

  // For every cell touched by a changed control point: the list of (window position, change),
  // or, when most of its window changed, the dense window of changes.
  const AxisTables tables = makeTables(lattice);
  int np[3], cells[3];
  for (int a = 0; a < 3; ++a) {
    np[a] = lattice.axis(a).degree() + 1;
    cells[a] = lattice.axis(a).cellCount();
  }
  // cellsOf[a][i] = (cell, r) pairs whose window holds control index i on axis a.
  std::vector<std::vector<std::pair<int, int>>> cellsOf[3];
  for (int a = 0; a < 3; ++a) {
    cellsOf[a].resize(lattice.counts()[a]);
    for (int c = 0; c < cells[a]; ++c)
      for (int r = 0; r < np[a]; ++r) cellsOf[a][tables.window[a][c * np[a] + r]].push_back({c, r});
  }
  const int windowSize = np[0] * np[1] * np[2];
  const std::size_t cellTotal = static_cast<std::size_t>(cells[0]) * cells[1] * cells[2];
  std::vector<std::vector<detail::SparseTerm>> terms(cellTotal);
  for (Eigen::Index f : changed) {
    const Eigen::Vector3i g = lattice.gridIndex(f);
    for (const auto& [cw, rw] : cellsOf[2][g[2]])
      for (const auto& [cv, rv] : cellsOf[1][g[1]])
        for (const auto& [cu, ru] : cellsOf[0][g[0]]) {
          terms[cu + cells[0] * (cv + static_cast<std::size_t>(cells[1]) * cw)].push_back(
              {ru, rv, rw, D(f, 0), D(f, 1), D(f, 2)});
        }
  }
  std::vector<std::vector<double>> dense(cellTotal);
  for (std::size_t cell = 0; cell < cellTotal; ++cell) {
    // Most of the window moved: the dense contraction is cheaper than one term per point.
    if (3 * terms[cell].size() > static_cast<std::size_t>(windowSize)) {
      const int c[3] = {static_cast<int>(cell % cells[0]), static_cast<int>((cell / cells[0]) % cells[1]),
                        static_cast<int>(cell / (static_cast<std::size_t>(cells[0]) * cells[1]))};
      gatherWindow(lattice, tables, c, D, dense[cell]);
    }
  }

  detail::KernelInput in = makeInput(lattice, embedding_, output_);
  for (int a = 0; a < 3; ++a) in.axis[a].cellSpan = tables.span[a].data();
  const auto& blocks = embedding_.blocks();
  const auto& tiles = embedding_.tileBlocks();
  const std::int64_t tileCount = static_cast<std::int64_t>(tiles.size()) - 1;
  Eigen::Index evaluated = 0;
  Eigen::Index work = 0;
  for (const Embedding::Block& block : blocks) {
    const std::size_t cell = block.cell[0] + cells[0] * (block.cell[1] + static_cast<std::size_t>(cells[1]) * block.cell[2]);
    if (block.kind != Embedding::BlockKind::Frozen && !terms[cell].empty()) work += block.end - block.begin;
  }
  const bool parallel = parallel_ && work >= kParallelPoints;
#pragma omp parallel if (parallel) reduction(+ : evaluated)
  {
    detail::KernelInput local = in;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t t = 0; t < tileCount; ++t) {
      for (std::uint32_t bi = tiles[t]; bi < tiles[t + 1]; ++bi) {
        const Embedding::Block& block = blocks[bi];
        if (block.kind == Embedding::BlockKind::Frozen) continue;
        const std::size_t cell =
            block.cell[0] + cells[0] * (block.cell[1] + static_cast<std::size_t>(cells[1]) * block.cell[2]);
        const auto& cellTerms = terms[cell];
        if (cellTerms.empty()) continue;
        evaluated += block.end - block.begin;
        const bool blended = block.kind == Embedding::BlockKind::Blended;
        if (blended) {
          local.blend = embedding_.blendWeight().data() + block.blendOffset;
          local.blendBegin = block.begin;
        }
        const std::vector<double>& W = dense[cell];
        if (!W.empty()) {
          const std::size_t size = W.size() / 3;
          detail::denseBlock(local, block.cell, block.begin, block.end, blended, W.data(), W.data() + size,
                             W.data() + 2 * size, true);
        } else {
          detail::sparseBlock(local, block.cell, block.begin, block.end, blended, cellTerms.data(),
                              static_cast<int>(cellTerms.size()));
        }
      }
    }
  }
  stats_.evaluatedPoints = evaluated;
  lastControl_ = P;
  return output_;
}

}  // namespace ffdkit::ffd
