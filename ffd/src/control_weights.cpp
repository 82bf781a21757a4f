#include "ffdkit/ffd/control_weights.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "deform_kernels.h"
#include "point_window.h"

namespace ffdkit::ffd {

ControlWeights largestControlWeights(const Lattice& lattice, const Embedding& embedding, int k) {
  if (k < 1) throw LatticeError("largestControlWeights: k must be >= 1, got " + std::to_string(k));
  embedding.checkLattice(lattice);
  // With weights other than the rest weights the output is Q + s F (sum R P - Xbar): the term
  // sum R Pbar - Xbar is not a blend of control displacements, so there is no such skin.
  if (lattice.isRational() && lattice.weights() != lattice.restWeights())
    throw LatticeError("largestControlWeights: the lattice's weights differ from its rest weights; a rational "
                       "deformation is a blend of control displacements only while they are equal");
  const Eigen::Index n = embedding.pointCount();
  ControlWeights result;
  result.k = k;
  result.indices.setConstant(n, k, -1);
  result.weights.setZero(n, k);
  result.total.setZero(n);
  result.dropped.setZero(n);

  int np[3];
  for (int a = 0; a < 3; ++a) np[a] = lattice.axis(a).degree() + 1;
  const int window = np[0] * np[1] * np[2];
  const auto& blocks = embedding.blocks();
  const auto& tiles = embedding.tileBlocks();
  const auto& order = embedding.order();
  const std::int64_t tileCount = static_cast<std::int64_t>(tiles.size()) - 1;
#pragma omp parallel if (n >= 16384)
  {
    std::vector<double> bu(static_cast<std::size_t>(np[0])), bv(static_cast<std::size_t>(np[1])),
        bw(static_cast<std::size_t>(np[2]));
    std::vector<double> w(static_cast<std::size_t>(window));
    std::vector<std::int32_t> index(static_cast<std::size_t>(window));
    std::vector<Eigen::Index> flat(static_cast<std::size_t>(window));
    std::vector<int> rank(static_cast<std::size_t>(window));
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t t = 0; t < tileCount; ++t) {
      for (std::uint32_t bi = tiles[t]; bi < tiles[t + 1]; ++bi) {
        const Embedding::Block& block = blocks[bi];
        if (block.kind == Embedding::BlockKind::Frozen) continue;  // no weights, total 0
        const std::array<int, 3> cell = embedding.cellOf(block);
        // The cell's window of control indices, in the order Deformer's gatherWindow walks it.
        detail::windowControlIndices(lattice, cell, flat.data());
        for (int r = 0; r < window; ++r) index[std::size_t(r)] = static_cast<std::int32_t>(flat[std::size_t(r)]);
        // A periodic axis with fewer control points than its window wraps onto the same point
        // twice: first[r] is the first window position with index[r] (the weights add up there).
        std::vector<int> first(static_cast<std::size_t>(window));
        bool wraps = false;
        for (int r = 0; r < window; ++r) {
          first[std::size_t(r)] = int(std::find(index.begin(), index.begin() + r + 1, index[std::size_t(r)]) - index.begin());
          wraps = wraps || first[std::size_t(r)] != r;
        }
        for (std::uint32_t q = block.begin; q < block.end; ++q) {
          const Eigen::Index p = order.empty() ? q : order[q];
          const double s = block.kind == Embedding::BlockKind::Blended
                               ? embedding.blendWeight()[block.blendOffset + q - block.begin]
                               : 1.0;
          detail::windowWeights(lattice, cell, embedding.sortedU()[q], embedding.sortedV()[q], embedding.sortedW()[q], s,
                                bu.data(), bv.data(), bw.data(), w.data());
          if (wraps) {
            for (int r = 0; r < window; ++r) {
              if (first[std::size_t(r)] == r) continue;
              w[std::size_t(first[std::size_t(r)])] += w[std::size_t(r)];
              w[std::size_t(r)] = 0.0;
            }
          }
          std::iota(rank.begin(), rank.end(), 0);
          const int kept = std::min(k, window);
          // Largest first; ties by window position, so the result does not depend on the sort.
          std::partial_sort(rank.begin(), rank.begin() + kept, rank.end(), [&w](int x, int y) {
            return w[std::size_t(x)] > w[std::size_t(y)] || (w[std::size_t(x)] == w[std::size_t(y)] && x < y);
          });
          double dropped = 0.0;
          for (int r = kept; r < window; ++r) dropped += std::abs(w[std::size_t(rank[std::size_t(r)])]);
          int slot = 0;
          for (int r = 0; r < kept; ++r) {
            const int at = rank[std::size_t(r)];
            if (w[std::size_t(at)] == 0.0) {
              continue;  // a zero weight is no joint (a point on a knot: fewer non-zero basis functions)
            }
            result.indices(p, slot) = index[std::size_t(at)];
            result.weights(p, slot) = w[std::size_t(at)];
            ++slot;
          }
          result.total[p] = s;
          result.dropped[p] = dropped;
        }
      }
    }
  }
  return result;
}

namespace {

// 0 for the points of a block outside the control point's support (or left unchanged).
void zeroBlock(const Embedding::Block& block, const Embedding::IndexVector& order, Eigen::VectorXd& result) {
  for (std::uint32_t q = block.begin; q < block.end; ++q) result[order.empty() ? q : order[q]] = 0.0;
}

// controlPointWeights on a rational lattice: s R_f = s w_f B_f / sum w B, from the whole window
// of each point whose cell holds the control point (detail::windowWeights).
void rationalControlPointWeights(const Lattice& lattice, const Embedding& embedding, Eigen::Index flat,
                                 Eigen::VectorXd& result) {
  const Eigen::Index n = embedding.pointCount();
  const int np[3] = {lattice.axis(0).degree() + 1, lattice.axis(1).degree() + 1, lattice.axis(2).degree() + 1};
  const std::size_t size = static_cast<std::size_t>(np[0]) * np[1] * np[2];
  const auto& blocks = embedding.blocks();
  const auto& order = embedding.order();
#pragma omp parallel if (n >= 16384)
  {
    std::vector<double> bu(static_cast<std::size_t>(np[0])), bv(static_cast<std::size_t>(np[1])),
        bw(static_cast<std::size_t>(np[2])), window(size);
    std::vector<Eigen::Index> indices(size);
#pragma omp for schedule(dynamic, 64)
    for (std::int64_t bi = 0; bi < static_cast<std::int64_t>(blocks.size()); ++bi) {
      const Embedding::Block& block = blocks[static_cast<std::size_t>(bi)];
      bool inWindow = block.kind != Embedding::BlockKind::Frozen;
      const std::array<int, 3> cell = embedding.cellOf(block);
      if (inWindow) {
        detail::windowControlIndices(lattice, cell, indices.data());
        inWindow = std::find(indices.begin(), indices.end(), flat) != indices.end();
      }
      if (!inWindow) {
        zeroBlock(block, order, result);
        continue;
      }
      for (std::uint32_t q = block.begin; q < block.end; ++q) {
        const double s = block.kind == Embedding::BlockKind::Blended
                             ? embedding.blendWeight()[block.blendOffset + q - block.begin]
                             : 1.0;
        detail::windowWeights(lattice, cell, embedding.sortedU()[q], embedding.sortedV()[q], embedding.sortedW()[q], s,
                              bu.data(), bv.data(), bw.data(), window.data());
        double sum = 0.0;
        for (std::size_t i = 0; i < size; ++i)
          if (indices[i] == flat) sum += window[i];
        result[order.empty() ? q : order[q]] = sum;
      }
    }
  }
}

}  // namespace

namespace {

// One block of controlPointWeights in the power form: per point, Horner's rule on each axis'
// polynomial of the control point (summed over the window positions that name it) at the local
// parameter, the product of the three, times the blend weight. K is a template parameter so that
// the loops unroll; `order` and `blend` are null for the identity order and an Evaluated block.
struct PowerBlock {
  const double* const* params;
  const double* origin;
  const double* scale;
  const double (*sum)[detail::kMaxPowerDegree + 1];
  const std::uint32_t* order;
  const double* blend;  // the block's blend weights, from its first point

  template <int K>
  void run(std::uint32_t begin, std::uint32_t end, double* result) const {
    for (std::uint32_t q = begin; q < end; ++q) {
      double product = 1.0;
      for (int a = 0; a < 3; ++a) {
        const double x = (params[a][q] - origin[a]) * scale[a];
        double h = sum[a][K];
        for (int k = K - 1; k >= 0; --k) h = h * x + sum[a][k];
        product *= h;
      }
      const double s = blend ? blend[q - begin] : 1.0;
      result[order ? order[q] : q] = s * product;
    }
  }
};

}  // namespace

Eigen::VectorXd controlPointWeights(const Lattice& lattice, const Embedding& embedding, Eigen::Index flat) {
  Eigen::VectorXd result;
  controlPointWeights(lattice, embedding, flat, result);
  return result;
}

void controlPointWeights(const Lattice& lattice, const Embedding& embedding, Eigen::Index flat, Eigen::VectorXd& result) {
  embedding.checkLattice(lattice);
  const Eigen::Vector3i g = lattice.gridIndex(flat);  // throws when out of range
  const Eigen::Index n = embedding.pointCount();
  if (result.size() != n) result.resize(n);  // every point is written below (0 outside the support)
  if (lattice.isRational()) {
    rationalControlPointWeights(lattice, embedding, flat, result);
    return;
  }
  int np[3], degrees[3];
  for (int a = 0; a < 3; ++a) {
    degrees[a] = lattice.axis(a).degree();
    np[a] = degrees[a] + 1;
  }
  // Degree <= 3: the basis functions in the power form of each cell, as the deformer's kernels
  // evaluate them (detail::axisPolynomials; K is the largest degree, the others padded with 0).
  const int K = detail::powerDegree(degrees);
  detail::AxisPolynomials poly[3];
  if (K >= 0)
    for (int a = 0; a < 3; ++a) poly[a] = detail::axisPolynomials(lattice.axis(a), K);
  const auto& blocks = embedding.blocks();
  const auto& tiles = embedding.tileBlocks();
  const auto& order = embedding.order();
  const std::int64_t tileCount = static_cast<std::int64_t>(tiles.size()) - 1;
#pragma omp parallel if (n >= 16384)
  {
    std::vector<double> bu(static_cast<std::size_t>(np[0])), bv(static_cast<std::size_t>(np[1])),
        bw(static_cast<std::size_t>(np[2]));
    // Per axis, the window positions of the cell that hold the control point's index on that
    // axis (two or more where a periodic axis wraps), and the sum of their polynomials.
    std::vector<int> at[3];
    double sum[3][detail::kMaxPowerDegree + 1];
    double origin[3], scale[3];
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t t = 0; t < tileCount; ++t) {
      for (std::uint32_t bi = tiles[t]; bi < tiles[t + 1]; ++bi) {
        const Embedding::Block& block = blocks[bi];
        if (block.kind == Embedding::BlockKind::Frozen) {
          zeroBlock(block, order, result);
          continue;
        }
        const std::array<int, 3> blockCell = embedding.cellOf(block);
        bool inWindow = true;
        for (int a = 0; a < 3; ++a) {
          at[a].clear();
          for (int r = 0; r < np[a]; ++r)
            if (lattice.axis(a).controlIndex(blockCell[a], r) == g[a]) at[a].push_back(r);
          inWindow = inWindow && !at[a].empty();
          if (K < 0) continue;
          const double* cell = poly[a].cell(blockCell[a]);
          origin[a] = cell[0];
          scale[a] = cell[1];
          for (int k = 0; k <= K; ++k) {
            sum[a][k] = 0.0;
            for (int r : at[a]) sum[a][k] += cell[2 + r * (K + 1) + k];
          }
        }
        if (!inWindow) {
          zeroBlock(block, order, result);
          continue;
        }
        const double* params[3] = {embedding.sortedU().data(), embedding.sortedV().data(), embedding.sortedW().data()};
        if (K >= 0) {
          const double* blend = block.kind == Embedding::BlockKind::Blended
                                    ? embedding.blendWeight().data() + block.blendOffset
                                    : nullptr;
          const PowerBlock power{params, origin, scale, sum, order.empty() ? nullptr : order.data(), blend};
          switch (K) {
            case 0: power.run<0>(block.begin, block.end, result.data()); break;
            case 1: power.run<1>(block.begin, block.end, result.data()); break;
            case 2: power.run<2>(block.begin, block.end, result.data()); break;
            default: power.run<3>(block.begin, block.end, result.data()); break;
          }
          continue;
        }
        for (std::uint32_t q = block.begin; q < block.end; ++q) {
          const Eigen::Index p = order.empty() ? q : order[q];
          const double s = block.kind == Embedding::BlockKind::Blended
                               ? embedding.blendWeight()[block.blendOffset + q - block.begin]
                               : 1.0;
          lattice.axis(0).basis(blockCell[0], params[0][q], bu.data());
          lattice.axis(1).basis(blockCell[1], params[1][q], bv.data());
          lattice.axis(2).basis(blockCell[2], params[2][q], bw.data());
          double su = 0.0, sv = 0.0, sw = 0.0;
          for (int r : at[0]) su += bu[std::size_t(r)];
          for (int r : at[1]) sv += bv[std::size_t(r)];
          for (int r : at[2]) sw += bw[std::size_t(r)];
          result[p] = s * (su * sv * sw);
        }
      }
    }
  }
}

}  // namespace ffdkit::ffd
