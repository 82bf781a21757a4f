// The rational half of Deformer: lattices with control-point weights (NURBS-based FFD,
// Lamousin & Waggenspack 1994), X(u,v,w) = sum B w P / sum B w.
#include <algorithm>
#include <string>
#include <vector>

#include "ffdkit/ffd/deformer.h"

namespace ffdkit::ffd {
namespace {

// Below this many points a parallel region costs more than it saves (as in deformer.cpp).
constexpr Eigen::Index kParallelPoints = 16384;
constexpr int kMaxBasis = 33;

// (x, y, z, w) of one homogeneous control point or sum: one AVX register.
typedef double Lane4 __attribute__((vector_size(4 * sizeof(double))));

// The basis values of one point on each axis, for the cell it lies in.
struct PointBasis {
  double N[3][kMaxBasis];
};

void basisAt(const Lattice& lattice, const int cell[3], double u, double v, double w, PointBasis& b) {
  lattice.axis(0).basis(cell[0], u, b.N[0]);
  lattice.axis(1).basis(cell[1], v, b.N[1]);
  lattice.axis(2).basis(cell[2], w, b.N[2]);
}

// Homogeneous control points (w P, w), one per row, for the current or the rest lattice.
std::vector<Lane4> homogeneousPoints(const Eigen::MatrixX3d& P, const Eigen::VectorXd& weights) {
  std::vector<Lane4> H(static_cast<std::size_t>(P.rows()));
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    const double w = weights.size() > 0 ? weights[f] : 1.0;
    H[static_cast<std::size_t>(f)] = Lane4{w * P(f, 0), w * P(f, 1), w * P(f, 2), w};
  }
  return H;
}

// One cell's window of homogeneous points, a fastest (the order of the basis sums below).
void gather(const Lattice& lattice, const std::vector<Lane4>& H, const int cell[3], std::vector<Lane4>& window) {
  window.clear();
  const AxisSpline *x = &lattice.axis(0), *y = &lattice.axis(1), *z = &lattice.axis(2);
  for (int c = 0; c <= z->degree(); ++c)
    for (int b = 0; b <= y->degree(); ++b)
      for (int a = 0; a <= x->degree(); ++a)
        window.push_back(H[static_cast<std::size_t>(
            lattice.index(x->controlIndex(cell[0], a), y->controlIndex(cell[1], b), z->controlIndex(cell[2], c)))]);
}

// sum_abc N_a(u) N_b(v) N_c(w) window_abc.
inline Lane4 basisSum(const PointBasis& b, const Lane4* window, int nu, int nv, int nw) {
  Lane4 x = {0, 0, 0, 0};
  for (int c = 0; c < nw; ++c) {
    Lane4 y = {0, 0, 0, 0};
    for (int bb = 0; bb < nv; ++bb) {
      Lane4 s = {0, 0, 0, 0};
      for (int a = 0; a < nu; ++a, ++window) s += b.N[0][a] * *window;
      y += b.N[1][bb] * s;
    }
    x += b.N[2][c] * y;
  }
  return x;
}

// The ratio of a homogeneous sum, lattice-local.
inline Eigen::Vector3d ratio(const Lane4& h) { return Eigen::Vector3d(h[0] / h[3], h[1] / h[3], h[2] / h[3]); }

// A changed control point's change of homogeneous point at window position (ru, rv, rw) of a cell.
struct RationalTerm {
  int ru, rv, rw;
  Lane4 dh;
};

}  // namespace

Eigen::Index Deformer::evaluateRational(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& input,
                                        const std::vector<char>* cellFilter) {
  const Eigen::Index n = embedding_.pointCount();
  homogeneous_.resize(static_cast<std::size_t>(4 * n));
  const std::vector<Lane4> H = homogeneousPoints(lattice.controlPoints(), lattice.isRational() ? lattice.weights() : Eigen::VectorXd());
  const bool restRational = lattice.restIsRational();
  const std::vector<Lane4> R = homogeneousPoints(lattice.restPoints(), restRational ? lattice.restWeights() : Eigen::VectorXd());
  const Eigen::Matrix3d L = lattice.frame().linear();
  const int nu = lattice.axis(0).degree() + 1, nv = lattice.axis(1).degree() + 1, nw = lattice.axis(2).degree() + 1;
  const auto& blocks = embedding_.blocks();
  const auto& order = embedding_.order();
  const auto& blend = embedding_.blendWeight();
  const double* U = embedding_.sortedU().data();
  const double* V = embedding_.sortedV().data();
  const double* W = embedding_.sortedW().data();
  double* hom = homogeneous_.data();
  auto selected = [&](const Embedding::Block& block) { return !cellFilter || (*cellFilter)[block.cell]; };
  Eigen::Index work = 0;
  for (const Embedding::Block& block : blocks)
    if (selected(block)) work += block.end - block.begin;
  const bool parallel = parallel_ && work >= kParallelPoints;
  Eigen::Index evaluated = 0;
#pragma omp parallel if (parallel) reduction(+ : evaluated)
  {
    std::vector<Lane4> current, rest;
    int last[3] = {-1, -1, -1};
    PointBasis basis;
#pragma omp for schedule(dynamic, 64)
    for (std::int64_t bi = 0; bi < static_cast<std::int64_t>(blocks.size()); ++bi) {
      const Embedding::Block& block = blocks[static_cast<std::size_t>(bi)];
      if (!selected(block)) continue;
      if (block.kind == Embedding::BlockKind::Frozen) {
        for (std::uint32_t q = block.begin; q < block.end; ++q) {
          const Eigen::Index p = order.empty() ? q : order[q];
          output_.row(p) = input.row(p);
        }
        continue;
      }
      const std::array<int, 3> cell = embedding_.cellOf(block);
      if (!std::equal(cell.begin(), cell.end(), last)) {
        gather(lattice, H, cell.data(), current);
        gather(lattice, R, cell.data(), rest);
        std::copy(cell.begin(), cell.end(), last);
      }
      const bool blended = block.kind == Embedding::BlockKind::Blended;
      for (std::uint32_t q = block.begin; q < block.end; ++q) {
        basisAt(lattice, cell.data(), U[q], V[q], W[q], basis);
        const Lane4 h = basisSum(basis, current.data(), nu, nv, nw);
        const Lane4 r = basisSum(basis, rest.data(), nu, nv, nw);
        // Rest weights 1: Xbar is the polynomial sum itself, as on the polynomial path.
        const Eigen::Vector3d xbar = restRational ? ratio(r) : Eigen::Vector3d(r[0], r[1], r[2]);
        const double s = blended ? blend[block.blendOffset + (q - block.begin)] : 1.0;
        const Eigen::Index p = order.empty() ? q : order[q];
        output_.row(p) = input.row(p) + (s * (L * (ratio(h) - xbar))).transpose();
        for (int k = 0; k < 4; ++k) hom[4 * q + k] = h[k];
      }
      evaluated += block.end - block.begin;
    }
  }
  if (!cellFilter) homogeneousValid_ = true;
  return evaluated;
}

const Eigen::MatrixX3d& Deformer::updateRational(const Lattice& lattice) {
  const Eigen::MatrixX3d& P = lattice.controlPoints();
  const Eigen::VectorXd weights = lattice.weights();
  const auto& blocks = embedding_.blocks();
  const int nu = lattice.axis(0).degree() + 1, nv = lattice.axis(1).degree() + 1, nw = lattice.axis(2).degree() + 1;
  const double* U = embedding_.sortedU().data();
  const double* V = embedding_.sortedV().data();
  const double* W = embedding_.sortedW().data();
  const bool parallelAll = parallel_ && embedding_.pointCount() >= kParallelPoints;
  if (!homogeneousValid_) {
    // The last output came from the polynomial path: its homogeneous sums are those of the last
    // control points with weights 1 (or the last weights); compute them once.
    homogeneous_.resize(static_cast<std::size_t>(4 * embedding_.pointCount()));
    const std::vector<Lane4> H = homogeneousPoints(lastControl_, lastWeights_);
    double* hom = homogeneous_.data();
#pragma omp parallel if (parallelAll)
    {
      std::vector<Lane4> window;
      PointBasis basis;
#pragma omp for schedule(dynamic, 64)
      for (std::int64_t bi = 0; bi < static_cast<std::int64_t>(blocks.size()); ++bi) {
        const Embedding::Block& block = blocks[static_cast<std::size_t>(bi)];
        if (block.kind == Embedding::BlockKind::Frozen) continue;
        const std::array<int, 3> cell = embedding_.cellOf(block);
        gather(lattice, H, cell.data(), window);
        for (std::uint32_t q = block.begin; q < block.end; ++q) {
          basisAt(lattice, cell.data(), U[q], V[q], W[q], basis);
          const Lane4 h = basisSum(basis, window.data(), nu, nv, nw);
          for (int k = 0; k < 4; ++k) hom[4 * q + k] = h[k];
        }
      }
    }
    homogeneousValid_ = true;
  }

  // The changed control points and, per cell of their support, the changes of (w P, w).
  int cells[3];
  for (int a = 0; a < 3; ++a) cells[a] = lattice.axis(a).cellCount();
  std::vector<std::vector<std::pair<int, int>>> cellsOf[3];  // cellsOf[a][i]: (cell, r) windows holding index i
  for (int a = 0; a < 3; ++a) {
    const AxisSpline& axis = lattice.axis(a);
    cellsOf[a].resize(static_cast<std::size_t>(lattice.counts()[a]));
    for (int c = 0; c < cells[a]; ++c)
      for (int r = 0; r <= axis.degree(); ++r) cellsOf[a][static_cast<std::size_t>(axis.controlIndex(c, r))].push_back({c, r});
  }
  const std::size_t cellTotal = static_cast<std::size_t>(cells[0]) * cells[1] * cells[2];
  std::vector<std::vector<RationalTerm>> terms(cellTotal);
  Eigen::Index changed = 0;
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    const double w0 = lastWeights_[f], w1 = weights[f];
    if (P.row(f) == lastControl_.row(f) && w0 == w1) continue;
    ++changed;
    const Lane4 dh = {w1 * P(f, 0) - w0 * lastControl_(f, 0), w1 * P(f, 1) - w0 * lastControl_(f, 1),
                      w1 * P(f, 2) - w0 * lastControl_(f, 2), w1 - w0};
    const Eigen::Vector3i g = lattice.gridIndex(f);
    for (const auto& [cw, rw] : cellsOf[2][static_cast<std::size_t>(g[2])])
      for (const auto& [cv, rv] : cellsOf[1][static_cast<std::size_t>(g[1])])
        for (const auto& [cu, ru] : cellsOf[0][static_cast<std::size_t>(g[0])])
          terms[cu + cells[0] * (cv + static_cast<std::size_t>(cells[1]) * cw)].push_back({ru, rv, rw, dh});
  }
  stats_ = DeformStats{false, changed, 0};
  if (changed == 0) return output_;

  const Eigen::Matrix3d L = lattice.frame().linear();
  const auto& order = embedding_.order();
  const auto& blend = embedding_.blendWeight();
  double* hom = homogeneous_.data();
  Eigen::Index work = 0;
  for (const Embedding::Block& block : blocks)
    if (block.kind != Embedding::BlockKind::Frozen && !terms[block.cell].empty()) work += block.end - block.begin;
  const bool parallel = parallel_ && work >= kParallelPoints;
  Eigen::Index evaluated = 0;
#pragma omp parallel if (parallel) reduction(+ : evaluated)
  {
    PointBasis basis;
#pragma omp for schedule(dynamic, 64)
    for (std::int64_t bi = 0; bi < static_cast<std::int64_t>(blocks.size()); ++bi) {
      const Embedding::Block& block = blocks[static_cast<std::size_t>(bi)];
      const std::vector<RationalTerm>& list = terms[block.cell];
      if (block.kind == Embedding::BlockKind::Frozen || list.empty()) continue;
      const std::array<int, 3> cell = embedding_.cellOf(block);
      const bool blended = block.kind == Embedding::BlockKind::Blended;
      for (std::uint32_t q = block.begin; q < block.end; ++q) {
        basisAt(lattice, cell.data(), U[q], V[q], W[q], basis);
        const Lane4 h0 = {hom[4 * q], hom[4 * q + 1], hom[4 * q + 2], hom[4 * q + 3]};
        Lane4 h = h0;
        for (const RationalTerm& t : list) h += (basis.N[0][t.ru] * basis.N[1][t.rv] * basis.N[2][t.rw]) * t.dh;
        const double s = blended ? blend[block.blendOffset + (q - block.begin)] : 1.0;
        const Eigen::Index p = order.empty() ? q : order[q];
        output_.row(p) += (s * (L * (ratio(h) - ratio(h0)))).transpose();
        for (int k = 0; k < 4; ++k) hom[4 * q + k] = h[k];
      }
      evaluated += block.end - block.begin;
    }
  }
  stats_.evaluatedPoints = evaluated;
  remember(lattice);
  return output_;
}

}  // namespace ffdkit::ffd
