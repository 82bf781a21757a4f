// The rational half of Deformer: lattices with control-point weights (NURBS-based FFD,
// Lamousin & Waggenspack 1994), X(u,v,w) = sum B w P / sum B w.
//
// Evaluated in homogeneous form (Piegl & Tiller 1997, sec. 4.2): the numerator N = sum B w F.linear P
// and the denominator D = sum B w are tensor-product polynomials like the displacement of a
// polynomial lattice, so the power-form kernels of deform_kernels.h run on the four components
// (and on the four of the base the displacement is taken against), and one reciprocal per point
// turns them into points. Lattices of degree above 3 sum Cox-de Boor basis values per point.
#include <algorithm>
#include <string>
#include <vector>

#include "deform_kernels.h"
#include "ffdkit/ffd/deformer.h"

namespace ffdkit::ffd {
namespace {

// Below this many points a parallel region costs more than it saves (as in deformer.cpp).
constexpr Eigen::Index kParallelPoints = 16384;
constexpr int kMaxBasis = 33;
// The components of a homogeneous point and of a cell's window: N (x, y, z) and D, current then base.
constexpr int kComponents = 8;

// Homogeneous control points (w F.linear P, w), one per row.
Eigen::Matrix<double, Eigen::Dynamic, 4> homogeneousPoints(const Eigen::MatrixX3d& P, const Eigen::VectorXd& weights,
                                                           const Eigen::Matrix3d& L) {
  Eigen::Matrix<double, Eigen::Dynamic, 4> H(P.rows(), 4);
  H.leftCols<3>() = (P * L.transpose()).array().colwise() * weights.array();
  H.col(3) = weights;
  return H;
}

// Per cell, what the rational kernels read: the power form's coefficient sets (lattices of degree
// <= 3; detail::rationalSetCount() sets of (K+1)^3) or the window itself (kComponents + 1 blocks
// of nu nv nw values, a fastest). Precomputed for the cells to evaluate while they fit in
// max(1 MiB, 16 bytes per evaluated point), else computed per block (as CellFields in
// deformer.cpp); both give the same bits.
class RationalCells {
 public:
  RationalCells(const Lattice& lattice, const Eigen::Matrix<double, Eigen::Dynamic, 4>& current,
                const Eigen::Matrix<double, Eigen::Dynamic, 4>& base)
      : lattice_(lattice), current_(current), base_(base) {
    const int degrees[3] = {lattice.axis(0).degree(), lattice.axis(1).degree(), lattice.axis(2).degree()};
    K_ = detail::powerDegree(degrees);
    for (int a = 0; a < 3; ++a) {
      counts_[a] = degrees[a] + 1;
      cells_[a] = lattice.axis(a).cellCount();
      if (K_ >= 0) poly_[a] = detail::axisPolynomials(lattice.axis(a), K_);
    }
    window_ = static_cast<std::size_t>(counts_[0]) * counts_[1] * counts_[2];
    block_ = power() ? static_cast<std::size_t>((K_ + 1) * (K_ + 1) * (K_ + 1)) : window_;
  }
  bool power() const { return K_ >= 0; }
  const detail::AxisPolynomials* polynomials(int axis) const { return power() ? &poly_[axis] : nullptr; }
  int windowCount(int axis) const { return counts_[axis]; }
  std::size_t blockSize() const { return block_; }
  std::size_t size() const { return (kComponents + 1) * block_; }

  void plan(std::vector<std::uint32_t> flats, Eigen::Index work) {
    if (flats.size() * size() * sizeof(double) > std::max<std::size_t>(std::size_t(1) << 20, 16 * std::size_t(work)))
      return;
    slot_.assign(static_cast<std::size_t>(cells_[0]) * cells_[1] * cells_[2], -1);
    for (std::size_t i = 0; i < flats.size(); ++i) slot_[flats[i]] = static_cast<std::int32_t>(i);
    flats_ = std::move(flats);
    table_.resize(flats_.size() * size());
  }
  // Fills the planned table; call from every thread of a parallel region (work-shared, ends with a barrier).
  void fillTable() const {
    std::vector<double> window;
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(flats_.size()); ++i)
      compute(flats_[static_cast<std::size_t>(i)], window, table_.data() + i * size());
  }
  // One thread's view of the cells' data, caching the last cell computed outside the table.
  class Reader {
   public:
    explicit Reader(const RationalCells& cells) : cells_(cells) {}
    const double* at(std::uint32_t flat) {
      if (!cells_.slot_.empty() && cells_.slot_[flat] >= 0)
        return cells_.table_.data() + static_cast<std::size_t>(cells_.slot_[flat]) * cells_.size();
      if (flat != last_) {
        own_.resize(cells_.size());
        cells_.compute(flat, window_, own_.data());
        last_ = flat;
      }
      return own_.data();
    }

   private:
    const RationalCells& cells_;
    std::vector<double> window_, own_;
    std::uint32_t last_ = ~0u;
  };

 private:
  void compute(std::uint32_t flat, std::vector<double>& window, double* out) const {
    const int cell[3] = {int(flat % unsigned(cells_[0])), int(flat / unsigned(cells_[0]) % unsigned(cells_[1])),
                         int(flat / unsigned(cells_[0]) / unsigned(cells_[1]))};
    // Blocks N x, y, z, D, Nb x, y, z, Db, and Db again (cellCoefficients contracts three at a time).
    double* W = out;
    if (power()) {
      window.resize((kComponents + 1) * window_);
      W = window.data();
    }
    const AxisSpline *x = &lattice_.axis(0), *y = &lattice_.axis(1), *z = &lattice_.axis(2);
    std::size_t wi = 0;
    for (int c = 0; c < counts_[2]; ++c)
      for (int b = 0; b < counts_[1]; ++b)
        for (int a = 0; a < counts_[0]; ++a, ++wi) {
          const Eigen::Index f = lattice_.index(x->controlIndex(cell[0], a), y->controlIndex(cell[1], b),
                                                z->controlIndex(cell[2], c));
          for (int k = 0; k < 4; ++k) {
            W[k * window_ + wi] = current_(f, k);
            W[(4 + k) * window_ + wi] = base_(f, k);
          }
          W[8 * window_ + wi] = base_(f, 3);
        }
    if (!power()) return;
    for (int group = 0; group < 3; ++group)
      detail::cellCoefficients(poly_, cell, W + 3 * group * window_, counts_, out + 3 * group * block_);
  }

  const Lattice& lattice_;
  const Eigen::Matrix<double, Eigen::Dynamic, 4>& current_;
  const Eigen::Matrix<double, Eigen::Dynamic, 4>& base_;
  int K_ = -1;
  int counts_[3] = {};
  int cells_[3] = {};
  std::size_t window_ = 0, block_ = 0;
  detail::AxisPolynomials poly_[3];
  std::vector<std::int32_t> slot_;
  std::vector<std::uint32_t> flats_;
  mutable std::vector<double> table_;
};

// Cox-de Boor path (degree > 3): the eight sums of one point from its cell's window.
void rationalSums(const Lattice& lattice, const int cell[3], double u, double v, double w, const double* W,
                  std::size_t window, double sums[kComponents]) {
  double N[3][kMaxBasis];
  lattice.axis(0).basis(cell[0], u, N[0]);
  lattice.axis(1).basis(cell[1], v, N[1]);
  lattice.axis(2).basis(cell[2], w, N[2]);
  const int nu = lattice.axis(0).degree() + 1, nv = lattice.axis(1).degree() + 1, nw = lattice.axis(2).degree() + 1;
  std::fill_n(sums, kComponents, 0.0);
  std::size_t wi = 0;
  for (int c = 0; c < nw; ++c)
    for (int b = 0; b < nv; ++b) {
      double row[kComponents] = {};
      for (int a = 0; a < nu; ++a, ++wi)
        for (int k = 0; k < kComponents; ++k) row[k] += N[0][a] * W[k * window + wi];
      for (int k = 0; k < kComponents; ++k) sums[k] += N[1][b] * N[2][c] * row[k];
    }
}

void cellSpans(const Lattice& lattice, std::vector<int> spans[3]) {
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < lattice.axis(a).cellCount(); ++c) spans[a].push_back(lattice.axis(a).cellSpan(c));
}

}  // namespace

Eigen::Index Deformer::evaluateRational(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>* input,
                                        const std::vector<char>* cellFilter) {
  const Eigen::Index n = embedding_.pointCount();
  if (denominators_.size() != static_cast<std::size_t>(n)) {
    denominators_.assign(static_cast<std::size_t>(n), 1.0);
    denominatorsValid_ = false;
  }
  const Eigen::Matrix3d L = lattice.frame().linear();
  const Eigen::Matrix<double, Eigen::Dynamic, 4> current = homogeneousPoints(lattice.controlPoints(), lattice.weights(), L);
  // The base: the rest map (out = Q + s F.linear (X - Xbar)) or the last state (out += s F.linear (X - Xlast)).
  const Eigen::Matrix<double, Eigen::Dynamic, 4> base =
      input ? homogeneousPoints(lattice.restPoints(), lattice.restWeights(), L)
            : homogeneousPoints(lastControl_, lastWeights_, L);
  // Rest weights 1: Xbar is the polynomial sum itself, as on the polynomial path.
  const bool baseRational = input ? lattice.restIsRational() : true;
  const detail::Store mode = input ? detail::Store::Replace : detail::Store::Accumulate;
  RationalCells cells(lattice, current, base);
  std::vector<int> spans[3];
  cellSpans(lattice, spans);
  const detail::AxisPolynomials* const poly[3] = {cells.polynomials(0), cells.polynomials(1), cells.polynomials(2)};
  detail::KernelInput in = detail::kernelInput(lattice, embedding_, spans, poly, output_);
  if (input) {
    in.qx = input->col(0).data();
    in.qy = input->col(1).data();
    in.qz = input->col(2).data();
  }
  const auto& blocks = embedding_.blocks();
  auto selected = [&](const Embedding::Block& block) { return !cellFilter || (*cellFilter)[block.cell]; };
  Eigen::Index work = 0;
  {
    std::vector<char> used(cellFilter ? cellFilter->size() : std::size_t(lattice.axis(0).cellCount()) *
                                                                   lattice.axis(1).cellCount() * lattice.axis(2).cellCount(),
                           0);
    std::vector<std::uint32_t> flats;
    for (const Embedding::Block& block : blocks) {
      if (!selected(block) || block.kind == Embedding::BlockKind::Frozen) continue;
      work += block.end - block.begin;
      if (!used[block.cell]) flats.push_back(block.cell);
      used[block.cell] = 1;
    }
    cells.plan(std::move(flats), work);
  }
  const bool parallel = parallel_ && work >= kParallelPoints;
  const auto& order = embedding_.order();
  double* denominators = denominators_.data();
  Eigen::Index evaluated = 0;
#pragma omp parallel if (parallel) reduction(+ : evaluated)
  {
    cells.fillTable();
    RationalCells::Reader reader(cells);
    detail::KernelInput local = in;
#pragma omp for schedule(dynamic, 16)
    for (std::int64_t bi = 0; bi < static_cast<std::int64_t>(blocks.size()); ++bi) {
      const Embedding::Block& block = blocks[static_cast<std::size_t>(bi)];
      if (!selected(block)) continue;
      if (block.kind == Embedding::BlockKind::Frozen) {
        if (!input) continue;
        for (std::uint32_t q = block.begin; q < block.end; ++q) {
          const Eigen::Index p = order.empty() ? q : order[q];
          output_.row(p) = input->row(p);
        }
        continue;
      }
      const std::array<int, 3> cell = embedding_.cellOf(block);
      const bool blended = block.kind == Embedding::BlockKind::Blended;
      if (blended) {
        local.blend = embedding_.blendWeight().data() + block.blendOffset;
        local.blendBegin = block.begin;
      }
      const double* data = reader.at(block.cell);
      evaluated += block.end - block.begin;
      if (cells.power()) {
        detail::rationalPowerBlock(local, cell.data(), block.begin, block.end, blended, data, baseRational, denominators,
                                   mode);
        continue;
      }
      for (std::uint32_t q = block.begin; q < block.end; ++q) {
        double h[kComponents];
        rationalSums(lattice, cell.data(), in.u[q], in.v[q], in.w[q], data, cells.blockSize(), h);
        const Eigen::Vector3d x = Eigen::Vector3d(h[0], h[1], h[2]) / h[3];
        const Eigen::Vector3d xb = baseRational ? Eigen::Vector3d(Eigen::Vector3d(h[4], h[5], h[6]) / h[7])
                                                : Eigen::Vector3d(h[4], h[5], h[6]);
        const double s = blended ? local.blend[q - block.begin] : 1.0;
        const Eigen::Index p = order.empty() ? q : order[q];
        if (input) {
          output_.row(p) = input->row(p) + (s * (x - xb)).transpose();
        } else {
          output_.row(p) += (s * (x - xb)).transpose();
        }
        denominators[q] = h[3];
      }
    }
  }
  if (!cellFilter) denominatorsValid_ = true;
  return evaluated;
}

const Eigen::MatrixX3d& Deformer::updateRational(const Lattice& lattice) {
  const Eigen::MatrixX3d& P = lattice.controlPoints();
  const Eigen::VectorXd weights = lattice.weights();
  const Eigen::Matrix3d L = lattice.frame().linear();
  int cells[3], counts[3];
  for (int a = 0; a < 3; ++a) {
    cells[a] = lattice.axis(a).cellCount();
    counts[a] = lattice.axis(a).degree() + 1;
  }
  // cellsOf[a][i]: (cell, r) windows holding control index i on axis a.
  std::vector<std::vector<std::pair<int, int>>> cellsOf[3];
  for (int a = 0; a < 3; ++a) {
    const AxisSpline& axis = lattice.axis(a);
    cellsOf[a].resize(static_cast<std::size_t>(lattice.counts()[a]));
    for (int c = 0; c < cells[a]; ++c)
      for (int r = 0; r <= axis.degree(); ++r) cellsOf[a][static_cast<std::size_t>(axis.controlIndex(c, r))].push_back({c, r});
  }
  const std::size_t cellTotal = static_cast<std::size_t>(cells[0]) * cells[1] * cells[2];
  // Per cell, the changed control points' numerator changes w F.linear dP (their weights kept).
  std::vector<std::vector<detail::SparseTerm>> terms(cellTotal);
  Eigen::Index changed = 0;
  bool weightChanged = false;
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    if (P.row(f) == lastControl_.row(f) && weights[f] == lastWeights_[f]) continue;
    ++changed;
    weightChanged = weightChanged || weights[f] != lastWeights_[f];
    const Eigen::Vector3d dN = weights[f] * (L * (P.row(f) - lastControl_.row(f)).transpose());
    const Eigen::Vector3i g = lattice.gridIndex(f);
    for (const auto& [cw, rw] : cellsOf[2][static_cast<std::size_t>(g[2])])
      for (const auto& [cv, rv] : cellsOf[1][static_cast<std::size_t>(g[1])])
        for (const auto& [cu, ru] : cellsOf[0][static_cast<std::size_t>(g[0])])
          terms[cu + cells[0] * (cv + static_cast<std::size_t>(cells[1]) * cw)].push_back(
              {ru, rv, rw, dN[0], dN[1], dN[2]});
  }
  stats_ = DeformStats{false, changed, 0};
  if (changed == 0) return output_;

  // A weight changed D, or most of a cell's window moved (a term costs about 1/16 of a power-form
  // point, which evaluates all eight sums): re-evaluate the touched cells against the last state.
  const int degrees[3] = {counts[0] - 1, counts[1] - 1, counts[2] - 1};
  const bool power = detail::powerDegree(degrees) >= 0;
  const std::size_t windowSize = static_cast<std::size_t>(counts[0]) * counts[1] * counts[2];
  bool dense = weightChanged || !denominatorsValid_ || denominators_.size() != std::size_t(embedding_.pointCount());
  for (std::size_t c = 0; c < cellTotal && !dense; ++c) dense = (power ? 32 : 3) * terms[c].size() > windowSize;
  if (dense) {
    std::vector<char> touched(cellTotal, 0);
    for (std::size_t c = 0; c < cellTotal; ++c) touched[c] = !terms[c].empty();
    stats_.evaluatedPoints = evaluateRational(lattice, nullptr, denominatorsValid_ ? &touched : nullptr);
    remember(lattice);
    return output_;
  }

  // The weights are kept: D is unchanged, and the new point is (N + sum B dN) / D.
  const Eigen::Matrix<double, Eigen::Dynamic, 4> none(0, 4);
  RationalCells fields(lattice, none, none);
  std::vector<int> spans[3];
  cellSpans(lattice, spans);
  const detail::AxisPolynomials* const poly[3] = {fields.polynomials(0), fields.polynomials(1), fields.polynomials(2)};
  const detail::KernelInput in = detail::kernelInput(lattice, embedding_, spans, poly, output_);
  const auto& blocks = embedding_.blocks();
  auto touched = [&](const Embedding::Block& block) {
    return block.kind != Embedding::BlockKind::Frozen && !terms[block.cell].empty();
  };
  Eigen::Index work = 0;
  for (const Embedding::Block& block : blocks)
    if (touched(block)) work += block.end - block.begin;
  const bool parallel = parallel_ && work >= kParallelPoints;
  const double* denominators = denominators_.data();
  Eigen::Index evaluated = 0;
#pragma omp parallel if (parallel) reduction(+ : evaluated)
  {
    detail::KernelInput local = in;
#pragma omp for schedule(dynamic, 16)
    for (std::int64_t bi = 0; bi < static_cast<std::int64_t>(blocks.size()); ++bi) {
      const Embedding::Block& block = blocks[static_cast<std::size_t>(bi)];
      if (!touched(block)) continue;
      const bool blended = block.kind == Embedding::BlockKind::Blended;
      if (blended) {
        local.blend = embedding_.blendWeight().data() + block.blendOffset;
        local.blendBegin = block.begin;
      }
      const std::vector<detail::SparseTerm>& list = terms[block.cell];
      detail::sparseBlock(local, embedding_.cellOf(block).data(), block.begin, block.end, blended, list.data(),
                          static_cast<int>(list.size()), detail::Store::Accumulate, denominators);
      evaluated += block.end - block.begin;
    }
  }
  stats_.evaluatedPoints = evaluated;
  remember(lattice);
  return output_;
}

}  // namespace ffdkit::ffd
