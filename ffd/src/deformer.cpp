#include "ffdkit/ffd/deformer.h"

#include <algorithm>
#include <string>
#include <vector>

// The hot loops are compiled twice, for baseline x86-64 and for AVX2 + FMA, and picked at load
// time (GCC function multiversioning), so the library stays portable without -march flags.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define FFDKIT_VECTOR_CLONES __attribute__((target_clones("default", "arch=x86-64-v3")))
#else
#define FFDKIT_VECTOR_CLONES
#endif

namespace ffdkit::ffd {
namespace detail {

constexpr int kLanes = 8;
constexpr int kMaxBasis = 33;

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
  const double* blend;         // indexed by q - blendBegin
  std::uint32_t blendBegin;
  const double* qx;  // input columns (original order), may be null for updates
  const double* qy;
  const double* qz;
  Eigen::Index qStride;  // column stride of the input
  double* ox;            // output columns
  double* oy;
  double* oz;
};

// The degree+1 basis values of `lanes` parameters on one span (Cox-de Boor, The NURBS Book A2.2),
// vectorised across lanes: the knots are the same for every lane of a cell.
inline void basisLanes(const AxisView& axis, int cell, const double* t, double (*N)[kLanes]) {
  const int p = axis.degree;
  const int s = axis.cellSpan[cell];
  const double* U = axis.knots;
  double left[kMaxBasis][kLanes];
  double right[kMaxBasis][kLanes];
  for (int l = 0; l < kLanes; ++l) N[0][l] = 1.0;
  for (int j = 1; j <= p; ++j) {
    const double kl = U[s + 1 - j];
    const double kr = U[s + j];
    for (int l = 0; l < kLanes; ++l) {
      left[j][l] = t[l] - kl;
      right[j][l] = kr - t[l];
    }
    double saved[kLanes] = {};
    for (int r = 0; r < j; ++r) {
      const double inv = 1.0 / (U[s + r + 1] - U[s + 1 - j + r]);
      for (int l = 0; l < kLanes; ++l) {
        const double temp = N[r][l] * inv;
        N[r][l] = saved[l] + right[r + 1][l] * temp;
        saved[l] = left[j - r][l] * temp;
      }
    }
    for (int l = 0; l < kLanes; ++l) N[j][l] = saved[l];
  }
}

inline void loadLanes(const double* src, std::uint32_t q, int count, double* dst) {
  for (int l = 0; l < kLanes; ++l) dst[l] = src[q + std::min(l, count - 1)];
}

// Dense block: d = sum_abc Bu Bv Bw W_abc over the cell window W (world displacement or its change).
// mode 0: out = Q + s d;  mode 1: out += s d.
FFDKIT_VECTOR_CLONES
void denseBlock(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                const double* Wx, const double* Wy, const double* Wz, int mode) {
  const int nu = in.axis[0].degree + 1;
  const int nv = in.axis[1].degree + 1;
  const int nw = in.axis[2].degree + 1;
  double bu[kMaxBasis][kLanes];
  double bv[kMaxBasis][kLanes];
  double bw[kMaxBasis][kLanes];
  double t[kLanes];
  for (std::uint32_t q0 = begin; q0 < end; q0 += kLanes) {
    const int count = static_cast<int>(std::min<std::uint32_t>(kLanes, end - q0));
    loadLanes(in.u, q0, count, t);
    basisLanes(in.axis[0], cell[0], t, bu);
    loadLanes(in.v, q0, count, t);
    basisLanes(in.axis[1], cell[1], t, bv);
    loadLanes(in.w, q0, count, t);
    basisLanes(in.axis[2], cell[2], t, bw);
    double dx[kLanes] = {}, dy[kLanes] = {}, dz[kLanes] = {};
    int wi = 0;
    for (int c = 0; c < nw; ++c) {
      for (int b = 0; b < nv; ++b) {
        double sx[kLanes] = {}, sy[kLanes] = {}, sz[kLanes] = {};
        for (int a = 0; a < nu; ++a, ++wi) {
          const double px = Wx[wi], py = Wy[wi], pz = Wz[wi];
          for (int l = 0; l < kLanes; ++l) {
            sx[l] += bu[a][l] * px;
            sy[l] += bu[a][l] * py;
            sz[l] += bu[a][l] * pz;
          }
        }
        for (int l = 0; l < kLanes; ++l) {
          const double nn = bv[b][l] * bw[c][l];
          dx[l] += nn * sx[l];
          dy[l] += nn * sy[l];
          dz[l] += nn * sz[l];
        }
      }
    }
    for (int l = 0; l < count; ++l) {
      const std::uint32_t q = q0 + l;
      const Eigen::Index p = in.order ? in.order[q] : q;
      const double s = blended ? in.blend[q - in.blendBegin] : 1.0;
      if (mode == 0) {
        in.ox[p] = in.qx[p] + s * dx[l];
        in.oy[p] = in.qy[p] + s * dy[l];
        in.oz[p] = in.qz[p] + s * dz[l];
      } else {
        in.ox[p] += s * dx[l];
        in.oy[p] += s * dy[l];
        in.oz[p] += s * dz[l];
      }
    }
  }
}

struct SparseTerm {
  int a, b, c;
  double dx, dy, dz;
};

// Sparse block: out += s * sum over changed control points of Bu_a Bv_b Bw_c dP.
FFDKIT_VECTOR_CLONES
void sparseBlock(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                 const SparseTerm* terms, int termCount) {
  double bu[kMaxBasis][kLanes];
  double bv[kMaxBasis][kLanes];
  double bw[kMaxBasis][kLanes];
  double t[kLanes];
  for (std::uint32_t q0 = begin; q0 < end; q0 += kLanes) {
    const int count = static_cast<int>(std::min<std::uint32_t>(kLanes, end - q0));
    loadLanes(in.u, q0, count, t);
    basisLanes(in.axis[0], cell[0], t, bu);
    loadLanes(in.v, q0, count, t);
    basisLanes(in.axis[1], cell[1], t, bv);
    loadLanes(in.w, q0, count, t);
    basisLanes(in.axis[2], cell[2], t, bw);
    double dx[kLanes] = {}, dy[kLanes] = {}, dz[kLanes] = {};
    for (int i = 0; i < termCount; ++i) {
      const SparseTerm& term = terms[i];
      for (int l = 0; l < kLanes; ++l) {
        const double weight = bu[term.a][l] * bv[term.b][l] * bw[term.c][l];
        dx[l] += weight * term.dx;
        dy[l] += weight * term.dy;
        dz[l] += weight * term.dz;
      }
    }
    for (int l = 0; l < count; ++l) {
      const std::uint32_t q = q0 + l;
      const Eigen::Index p = in.order ? in.order[q] : q;
      const double s = blended ? in.blend[q - in.blendBegin] : 1.0;
      in.ox[p] += s * dx[l];
      in.oy[p] += s * dy[l];
      in.oz[p] += s * dz[l];
    }
  }
}

}  // namespace detail

namespace {

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
  in.blend = e.blendWeight().data();
  in.blendBegin = e.blendBegin();
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
  const Eigen::Index n = embedding_.pointCount();
  if (input.rows() != n) {
    throw LatticeError("Deformer::deform: expected " + std::to_string(n) + " x 3 input points (the embedded ones), got " +
                       std::to_string(input.rows()) + " x 3");
  }
  output_.resize(n, 3);
  // World displacement of every control point: F.linear * (P - Pbar).
  const Eigen::MatrixX3d D = (lattice.controlPoints() - lattice.restPoints()) * lattice.frame().linear().transpose();
  const AxisTables tables = makeTables(lattice);
  detail::KernelInput in = makeInput(lattice, embedding_, output_);
  for (int a = 0; a < 3; ++a) in.axis[a].cellSpan = tables.span[a].data();
  in.qx = input.col(0).data();
  in.qy = input.col(1).data();
  in.qz = input.col(2).data();
  const auto& blocks = embedding_.blocks();
  const std::int64_t blockCount = static_cast<std::int64_t>(blocks.size());
  const bool parallel = parallel_;
#pragma omp parallel if (parallel)
  {
    std::vector<double> W;
    int lastCell[3] = {-1, -1, -1};
#pragma omp for schedule(dynamic, 2) nowait
    for (std::int64_t bi = 0; bi < blockCount; ++bi) {
      const Embedding::Block& block = blocks[bi];
      if (!std::equal(block.cell, block.cell + 3, lastCell)) {
        gatherWindow(lattice, tables, block.cell, D, W);
        std::copy(block.cell, block.cell + 3, lastCell);
      }
      const std::size_t size = W.size() / 3;
      detail::denseBlock(in, block.cell, block.begin, block.end, block.blended, W.data(), W.data() + size,
                         W.data() + 2 * size, 0);
    }
    // Frozen points (Identity outside, Failed, beyond Falloff) are the input unchanged.
#pragma omp for schedule(static)
    for (std::int64_t q = embedding_.frozenBegin(); q < n; ++q) {
      const Eigen::Index p = in.order ? in.order[q] : q;
      output_.row(p) = input.row(p);
    }
  }
  lastControl_ = lattice.controlPoints();
  deformed_ = true;
  stats_ = DeformStats{true, 0, n};
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

  // Position of each changed control point in each cell's window, per axis (-1: not in the window).
  const AxisTables tables = makeTables(lattice);
  int np[3];
  std::vector<int> position[3];
  for (int a = 0; a < 3; ++a) {
    np[a] = lattice.axis(a).degree() + 1;
    const int cells = lattice.axis(a).cellCount();
    position[a].assign(static_cast<std::size_t>(cells) * lattice.counts()[a], -1);
    for (int c = 0; c < cells; ++c) {
      for (int r = 0; r < np[a]; ++r) position[a][c * lattice.counts()[a] + tables.window[a][c * np[a] + r]] = r;
    }
  }
  std::vector<Eigen::Vector3i> grid;
  for (Eigen::Index f : changed) grid.push_back(lattice.gridIndex(f));
  const int windowSize = np[0] * np[1] * np[2];

  detail::KernelInput in = makeInput(lattice, embedding_, output_);
  for (int a = 0; a < 3; ++a) in.axis[a].cellSpan = tables.span[a].data();
  const auto& blocks = embedding_.blocks();
  const std::int64_t blockCount = static_cast<std::int64_t>(blocks.size());
  Eigen::Index evaluated = 0;
  const bool parallel = parallel_;
#pragma omp parallel if (parallel) reduction(+ : evaluated)
  {
    std::vector<detail::SparseTerm> terms;
    std::vector<double> W;
    int lastCell[3] = {-1, -1, -1};
#pragma omp for schedule(dynamic, 2)
    for (std::int64_t bi = 0; bi < blockCount; ++bi) {
      const Embedding::Block& block = blocks[bi];
      if (!std::equal(block.cell, block.cell + 3, lastCell)) {
        terms.clear();
        W.clear();
        for (std::size_t i = 0; i < changed.size(); ++i) {
          int r[3];
          bool inWindow = true;
          for (int a = 0; a < 3 && inWindow; ++a) {
            r[a] = position[a][block.cell[a] * lattice.counts()[a] + grid[i][a]];
            inWindow = r[a] >= 0;
          }
          if (inWindow) terms.push_back({r[0], r[1], r[2], D(changed[i], 0), D(changed[i], 1), D(changed[i], 2)});
        }
        // Most of the window moved: the dense contraction is cheaper than one term per point.
        if (3 * terms.size() > static_cast<std::size_t>(windowSize)) gatherWindow(lattice, tables, block.cell, D, W);
        std::copy(block.cell, block.cell + 3, lastCell);
      }
      if (terms.empty()) continue;
      evaluated += block.end - block.begin;
      if (!W.empty()) {
        const std::size_t size = W.size() / 3;
        detail::denseBlock(in, block.cell, block.begin, block.end, block.blended, W.data(), W.data() + size,
                           W.data() + 2 * size, 1);
      } else {
        detail::sparseBlock(in, block.cell, block.begin, block.end, block.blended, terms.data(),
                            static_cast<int>(terms.size()));
      }
    }
  }
  stats_.evaluatedPoints = evaluated;
  lastControl_ = P;
  return output_;
}

}  // namespace ffdkit::ffd
