#include "volume_polynomial.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_map>

#include "point_window.h"
#include "vector_clones.h"


namespace ffdkit::ffd::detail {
namespace {

constexpr int kBatch = 8;  // vertices per rank-one batch of K

constexpr std::int64_t pairCount(std::int64_t u) { return u * (u - 1) / 2; }
constexpr std::int64_t tripleCount(std::int64_t u) { return u * (u - 1) * (u - 2) / 6; }
constexpr std::int64_t pairIndex(std::int64_t j, std::int64_t k) { return k * (k - 1) / 2 + j; }        // j < k
constexpr std::int64_t tripleBase(std::int64_t j, std::int64_t k) { return tripleCount(k) + pairCount(j); }  // + i, i < j < k

// One cell's window of control points as active indices: the distinct ones ascending (slots),
// and the slot of each window position (a periodic axis may wrap two positions onto one point).
struct Window {
  std::array<int, 3> cell{};
  std::vector<int> slots;
  std::vector<int> slotOf;
};

// Per index set, the sums of one thread: K, q (three arrays, one per coordinate), R.
struct Accumulator {
  std::vector<double> cubic, quadratic[3], linear[3];
  void resize(std::int64_t u) {
    cubic.assign(std::size_t(tripleCount(u)), 0.0);
    for (int c = 0; c < 3; ++c) {
      quadratic[c].assign(std::size_t(pairCount(u)), 0.0);
      linear[c].assign(std::size_t(u), 0.0);
    }
  }
};

// A[jk] = sum_x d_x[j] e_x[k] over j < k: the ring's wedge sum_pairs d_b ^ d_c written per distinct
// neighbour x, e_x = sum_{pairs (x, c)} d_c - sum_{pairs (b, x)} d_b (one multiply-add per entry
// and neighbour). d and e are count x stride (stride >= u rounded up to 8, zero-padded), so that
// eight entries of a row of A sum over the neighbours in registers and are written once.
FFDKIT_VECTOR_CLONES
void wedgeSum(double* __restrict A, const double* __restrict d, const double* __restrict e, int count, int u,
              int stride) {
  for (int k = 1; k < u; ++k) {
    double* __restrict Ak = A + pairIndex(0, k);
    for (int j0 = 0; j0 < k; j0 += 8) {
      double acc[8] = {0, 0, 0, 0, 0, 0, 0, 0};
      for (int x = 0; x < count; ++x) {
        const double ek = e[std::size_t(x) * std::size_t(stride) + std::size_t(k)];
        const double* __restrict dx = d + std::size_t(x) * std::size_t(stride) + std::size_t(j0);
        for (int t = 0; t < 8; ++t) acc[t] += dx[t] * ek;
      }
      const int end = std::min(8, k - j0);
      for (int t = 0; t < end; ++t) Ak[j0 + t] = acc[t];
    }
  }
}

// Q[c][jk] += sum_b Y[b][c] A[b][jk] and R[c][i] += sum_b G[b][c] W[b][i] for a batch.
FFDKIT_VECTOR_CLONES
void addQuadraticAndLinear(double* const Q[3], double* const R[3], const double* __restrict A, const double* __restrict W,
                           const double (*Y)[3], const double (*G)[3], int u) {
  const std::size_t P = std::size_t(pairCount(u));
  for (int c = 0; c < 3; ++c) {
    double* __restrict q = Q[c];
    for (std::size_t pj = 0; pj < P; ++pj) {
      double s = q[pj];
      for (int b = 0; b < kBatch; ++b) s += Y[b][c] * A[std::size_t(b) * P + pj];
      q[pj] = s;
    }
    double* __restrict r = R[c];
    for (int i = 0; i < u; ++i) {
      double s = r[i];
      for (int b = 0; b < kBatch; ++b) s += G[b][c] * W[std::size_t(b) * std::size_t(u) + std::size_t(i)];
      r[i] = s;
    }
  }
}

// K[i<j<k] += sum_b W[b][i] A[b][jk] for a batch of kBatch vertices (rows of zeros pad a short batch):
// K streams through the cache once per batch.
FFDKIT_VECTOR_CLONES
void addCubic(double* __restrict K, const double* __restrict A, const double* __restrict W, int u) {
  const std::size_t P = std::size_t(pairCount(u));
  for (int k = 2; k < u; ++k)
    for (int j = 1; j < k; ++j) {
      const std::size_t pj = std::size_t(pairIndex(j, k));
      double a[kBatch];
      bool any = false;
      for (int b = 0; b < kBatch; ++b) {
        a[b] = A[std::size_t(b) * P + pj];
        any = any || a[b] != 0.0;
      }
      if (!any) continue;
      double* __restrict Kjk = K + tripleBase(j, k);
      for (int i = 0; i < j; ++i) {
        double s = Kjk[i];
        for (int b = 0; b < kBatch; ++b) s += a[b] * W[std::size_t(b) * std::size_t(u) + std::size_t(i)];
        Kjk[i] = s;
      }
    }
}

}  // namespace

std::optional<VolumePolynomial> VolumePolynomial::build(const Lattice& lattice, const Embedding& embedding,
                                                        const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                                        const Eigen::Vector3d& origin, const ClosedSurface& surface) {
  const Eigen::Index n = embedding.pointCount();
  const auto& blocks = embedding.blocks();
  const auto& tiles = embedding.tileBlocks();
  const auto& order = embedding.order();
  int np[3];
  for (int a = 0; a < 3; ++a) np[a] = lattice.axis(a).degree() + 1;
  const int windowSize = np[0] * np[1] * np[2];

  // Where each point sits: its sorted position and block; the windows of the cells in use.
  std::vector<std::uint32_t> sortedOf(static_cast<std::size_t>(n)), blockOf(static_cast<std::size_t>(n));
  std::vector<Window> windows;
  std::unordered_map<std::uint32_t, int> windowOfCell;
  std::vector<int> windowOfBlock(blocks.size(), -1);
  std::vector<char> used(std::size_t(lattice.pointCount()), 0);
  for (std::size_t bi = 0; bi < blocks.size(); ++bi) {
    const Embedding::Block& block = blocks[bi];
    for (std::uint32_t q = block.begin; q < block.end; ++q) {
      const std::size_t p = order.empty() ? q : order[q];
      sortedOf[p] = q;
      blockOf[p] = std::uint32_t(bi);
    }
    if (block.kind == Embedding::BlockKind::Frozen || block.begin == block.end) continue;
    auto [it, fresh] = windowOfCell.try_emplace(block.cell, int(windows.size()));
    windowOfBlock[bi] = it->second;
    if (!fresh) continue;
    Window w;
    w.cell = embedding.cellOf(block);
    std::vector<Eigen::Index> flat(static_cast<std::size_t>(windowSize));
    detail::windowControlIndices(lattice, w.cell, flat.data());
    w.slotOf.resize(std::size_t(windowSize));
    for (int r = 0; r < windowSize; ++r) {
      w.slotOf[std::size_t(r)] = int(flat[std::size_t(r)]);  // the control index for now
      used[std::size_t(flat[std::size_t(r)])] = 1;
    }
    windows.push_back(std::move(w));
  }
  VolumePolynomial result;
  std::vector<int> activeOf(used.size(), -1);
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) {
      activeOf[i] = int(result.active_.size());
      result.active_.push_back(Eigen::Index(i));
    }
  const std::int64_t a = std::int64_t(result.active_.size());
  if (a > kMaxActiveControls) return std::nullopt;
  for (Window& w : windows) {
    for (int& s : w.slotOf) s = activeOf[std::size_t(s)];
    w.slots = w.slotOf;
    std::sort(w.slots.begin(), w.slots.end());
    w.slots.erase(std::unique(w.slots.begin(), w.slots.end()), w.slots.end());
    for (int& s : w.slotOf) s = int(std::lower_bound(w.slots.begin(), w.slots.end(), s) - w.slots.begin());
  }

  const auto& offsets = surface.pairOffsets();
  const auto& pairs = surface.pairs();
  const Eigen::RowVector3d o = origin.transpose();
  const std::int64_t tileCount = std::int64_t(tiles.size()) - 1;
  Accumulator total;
  total.resize(a);
  double constant = 0.0;

#pragma omp parallel reduction(+ : constant) if (n >= 16384)
  {
    // The point's weights on its window's slots (zero-filled); the window, or -1 when frozen.
    std::vector<double> bu(static_cast<std::size_t>(np[0])), bv(static_cast<std::size_t>(np[1])), bw(static_cast<std::size_t>(np[2]));
    std::vector<double> positions(static_cast<std::size_t>(windowSize));
    const auto weightsOf = [&](Eigen::Index p, double* out) -> int {
      const std::uint32_t bi = blockOf[std::size_t(p)];
      const int wi = windowOfBlock[bi];
      if (wi < 0) return -1;
      const Embedding::Block& block = blocks[bi];
      const Window& w = windows[std::size_t(wi)];
      const std::uint32_t q = sortedOf[std::size_t(p)];
      const double s = block.kind == Embedding::BlockKind::Blended
                           ? embedding.blendWeight()[block.blendOffset + q - block.begin]
                           : 1.0;
      windowWeights(lattice, w.cell, embedding.sortedU()[q], embedding.sortedV()[q], embedding.sortedW()[q], s, bu.data(),
                    bv.data(), bw.data(), positions.data());
      std::fill(out, out + w.slots.size(), 0.0);
      for (int r = 0; r < windowSize; ++r) out[w.slotOf[std::size_t(r)]] += positions[std::size_t(r)];
      return wi;
    };

    std::vector<Accumulator> perWindow(windows.size());
    Accumulator mixed;  // vertices whose neighbours lie in other cells: over all `a` active controls
    // The batch: its window, its vertices' weights (kBatch x u), wedges (kBatch x pairs), y and g.
    int batchWindow = -1, batchCount = 0;
    std::vector<double> batchW, batchA;
    std::array<double[3], kBatch> batchY, batchG;
    const auto flush = [&]() {
      if (batchCount == 0) return;
      const Window& w = windows[std::size_t(batchWindow)];
      const int u = int(w.slots.size());
      Accumulator& acc = perWindow[std::size_t(batchWindow)];
      if (acc.linear[0].empty()) acc.resize(u);
      for (int b = batchCount; b < kBatch; ++b) {  // pad
        std::fill(batchW.begin() + std::ptrdiff_t(b) * u, batchW.begin() + std::ptrdiff_t(b + 1) * u, 0.0);
        std::fill(batchA.begin() + std::ptrdiff_t(b) * pairCount(u), batchA.begin() + std::ptrdiff_t(b + 1) * pairCount(u), 0.0);
      }
      if (u >= 3) addCubic(acc.cubic.data(), batchA.data(), batchW.data(), u);
      for (int b = batchCount; b < kBatch; ++b)
        for (int c = 0; c < 3; ++c) batchY[std::size_t(b)][c] = batchG[std::size_t(b)][c] = 0.0;
      double* Q[3] = {acc.quadratic[0].data(), acc.quadratic[1].data(), acc.quadratic[2].data()};
      double* R[3] = {acc.linear[0].data(), acc.linear[1].data(), acc.linear[2].data()};
      addQuadraticAndLinear(Q, R, batchA.data(), batchW.data(), batchY.data(), batchG.data(), u);
      batchCount = 0;
    };

    std::vector<Eigen::Index> ring;
    std::vector<int> ringWindow;
    std::vector<double> d, e, A, wv, scratch;
    std::vector<int> set, position;  // the vertex's index set (active, ascending); slot -> set position

#pragma omp for schedule(dynamic, 1)
    for (std::int64_t t = 0; t < tileCount; ++t) {
      for (std::uint32_t bi = tiles[std::size_t(t)]; bi < tiles[std::size_t(t) + 1]; ++bi) {
        const Embedding::Block& block = blocks[bi];
        for (std::uint32_t q = block.begin; q < block.end; ++q) {
          const Eigen::Index v = order.empty() ? Eigen::Index(q) : Eigen::Index(order[q]);
          const Eigen::RowVector3d yv = points.row(v) - o;
          // The rest gradient at v and v's share of V0.
          Eigen::Vector3d g = Eigen::Vector3d::Zero();
          ring.clear();
          for (int e2 = offsets[v]; e2 < offsets[v + 1]; ++e2) {
            const Eigen::Vector3d yb = (points.row(pairs(e2, 0)) - o - yv).transpose();
            const Eigen::Vector3d yc = (points.row(pairs(e2, 1)) - o - yv).transpose();
            g += yb.cross(yc);
            ring.push_back(pairs(e2, 0));
            ring.push_back(pairs(e2, 1));
          }
          g /= 6.0;
          constant += yv.dot(g.transpose()) / 3.0;
          std::sort(ring.begin(), ring.end());
          ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
          // The index set: v's window when every non-frozen point of the star shares it.
          const int own = windowOfBlock[blockOf[std::size_t(v)]];
          int common = own;
          bool single = true, anyMoving = own >= 0;
          ringWindow.resize(ring.size());
          for (std::size_t x = 0; x < ring.size(); ++x) {
            const int wx = windowOfBlock[blockOf[std::size_t(ring[x])]];
            ringWindow[x] = wx;
            if (wx < 0) continue;
            anyMoving = true;
            if (common < 0) common = wx;
            single = single && wx == common;
          }
          if (!anyMoving) continue;  // nothing of the star moves: V0 only
          // Dense weights over the set: v's (wv), each neighbour's minus v's (d).
          int u = 0;
          if (single) {
            u = int(windows[std::size_t(common)].slots.size());
          } else {
            set.clear();
            if (own >= 0) set.insert(set.end(), windows[std::size_t(own)].slots.begin(), windows[std::size_t(own)].slots.end());
            for (int wx : ringWindow)
              if (wx >= 0) set.insert(set.end(), windows[std::size_t(wx)].slots.begin(), windows[std::size_t(wx)].slots.end());
            std::sort(set.begin(), set.end());
            set.erase(std::unique(set.begin(), set.end()), set.end());
            u = int(set.size());
          }
          scratch.resize(std::size_t(windowSize));
          const auto denseWeights = [&](Eigen::Index p, int wp, double* out) {
            std::fill(out, out + u, 0.0);
            if (wp < 0) return;
            const Window& w = windows[std::size_t(wp)];
            weightsOf(p, scratch.data());
            for (std::size_t s = 0; s < w.slots.size(); ++s) {
              const int at = single ? int(s) : int(std::lower_bound(set.begin(), set.end(), w.slots[s]) - set.begin());
              out[at] += scratch[s];
            }
          };
          wv.resize(std::size_t(u));
          denseWeights(v, own, wv.data());
          const std::size_t m = ring.size();
          // d(x, i) = w_x[i] - w_v[i] and e(x, i), m x stride (rows padded with zeros to 8).
          const int stride = (u + 7) / 8 * 8;
          d.assign(m * std::size_t(stride), 0.0);
          e.assign(m * std::size_t(stride), 0.0);
          for (std::size_t x = 0; x < m; ++x) {
            double* dx = d.data() + x * std::size_t(stride);
            denseWeights(ring[x], ringWindow[x], dx);
            for (int i = 0; i < u; ++i) dx[i] -= wv[std::size_t(i)];
          }
          for (int e2 = offsets[v]; e2 < offsets[v + 1]; ++e2) {
            const std::size_t b = std::size_t(std::lower_bound(ring.begin(), ring.end(), pairs(e2, 0)) - ring.begin());
            const std::size_t c = std::size_t(std::lower_bound(ring.begin(), ring.end(), pairs(e2, 1)) - ring.begin());
            double* eb = e.data() + b * std::size_t(stride);
            double* ec = e.data() + c * std::size_t(stride);
            const double* db = d.data() + b * std::size_t(stride);
            const double* dc = d.data() + c * std::size_t(stride);
            for (int i = 0; i < u; ++i) {
              eb[i] += dc[i] / 6.0;
              ec[i] -= db[i] / 6.0;
            }
          }
          const std::size_t P = std::size_t(pairCount(u));
          if (single) {
            if (batchCount > 0 && batchWindow != common) flush();
            batchWindow = common;
            batchW.resize(std::size_t(kBatch) * std::size_t(u));
            batchA.resize(std::size_t(kBatch) * P);
            wedgeSum(batchA.data() + std::size_t(batchCount) * P, d.data(), e.data(), int(m), u, stride);
            std::copy(wv.begin(), wv.end(), batchW.begin() + std::ptrdiff_t(batchCount) * u);
            for (int c = 0; c < 3; ++c) {
              batchY[std::size_t(batchCount)][c] = yv[c];
              batchG[std::size_t(batchCount)][c] = g[c];
            }
            if (++batchCount == kBatch) flush();
            continue;
          }
          // Mixed cells (rare: stars across a cell boundary): straight into the all-active sums.
          if (mixed.linear[0].empty()) mixed.resize(a);
          A.resize(P);
          wedgeSum(A.data(), d.data(), e.data(), int(m), u, stride);
          for (int k = 0; k < u; ++k)
            for (int j = 0; j < k; ++j) {
              const double ajk = A[std::size_t(pairIndex(j, k))];
              if (ajk == 0.0) continue;
              const std::int64_t J = set[std::size_t(j)], Kk = set[std::size_t(k)];
              for (int c = 0; c < 3; ++c) mixed.quadratic[c][std::size_t(pairIndex(J, Kk))] += yv[c] * ajk;
              double* Kjk = mixed.cubic.data() + tripleBase(J, Kk);
              for (int i = 0; i < j; ++i) Kjk[set[std::size_t(i)]] += wv[std::size_t(i)] * ajk;
            }
          for (int i = 0; i < u; ++i)
            for (int c = 0; c < 3; ++c) mixed.linear[c][std::size_t(set[std::size_t(i)])] += wv[std::size_t(i)] * g[c];
        }
      }
    }
    flush();
    // Into the totals: each window's sums through its slots, then the mixed ones.
#pragma omp critical
    {
      for (std::size_t wi = 0; wi < windows.size(); ++wi) {
        const Accumulator& acc = perWindow[wi];
        if (acc.linear[0].empty()) continue;
        const std::vector<int>& S = windows[wi].slots;
        const int u = int(S.size());
        for (int k = 0; k < u; ++k)
          for (int j = 0; j < k; ++j) {
            for (int c = 0; c < 3; ++c)
              total.quadratic[c][std::size_t(pairIndex(S[std::size_t(j)], S[std::size_t(k)]))] +=
                  acc.quadratic[c][std::size_t(pairIndex(j, k))];
            if (acc.cubic.empty()) continue;
            const double* src = acc.cubic.data() + tripleBase(j, k);
            double* dst = total.cubic.data() + tripleBase(S[std::size_t(j)], S[std::size_t(k)]);
            for (int i = 0; i < j; ++i) dst[S[std::size_t(i)]] += src[i];
          }
        for (int i = 0; i < u; ++i)
          for (int c = 0; c < 3; ++c) total.linear[c][std::size_t(S[std::size_t(i)])] += acc.linear[c][std::size_t(i)];
      }
      if (!mixed.linear[0].empty()) {
        for (std::size_t x = 0; x < total.cubic.size(); ++x) total.cubic[x] += mixed.cubic[x];
        for (int c = 0; c < 3; ++c) {
          for (std::size_t x = 0; x < total.quadratic[c].size(); ++x) total.quadratic[c][x] += mixed.quadratic[c][x];
          for (std::size_t x = 0; x < total.linear[c].size(); ++x) total.linear[c][x] += mixed.linear[c][x];
        }
      }
    }
  }
  result.constant_ = constant;
  result.linear_.resize(a, 3);
  result.quadratic_.resize(pairCount(a), 3);
  for (int c = 0; c < 3; ++c) {
    for (std::int64_t i = 0; i < a; ++i) result.linear_(i, c) = total.linear[c][std::size_t(i)];
    for (std::int64_t p = 0; p < pairCount(a); ++p) result.quadratic_(p, c) = total.quadratic[c][std::size_t(p)];
  }
  result.cubic_ = std::move(total.cubic);
  return result;
}

double VolumePolynomial::evaluate(const Eigen::Ref<const Eigen::MatrixX3d>& displacement, Eigen::MatrixX3d& gradient) const {
  const std::int64_t a = std::int64_t(active_.size());
  Rows3 D(a, 3), G = linear_;
  for (std::int64_t i = 0; i < a; ++i) D.row(i) = displacement.row(active_[std::size_t(i)]);
  double value = constant_;
  for (std::int64_t i = 0; i < a; ++i) value += linear_.row(i).dot(D.row(i));
  for (std::int64_t k = 1; k < a; ++k) {
    const Eigen::Vector3d Dk = D.row(k).transpose();
    for (std::int64_t j = 0; j < k; ++j) {
      const Eigen::Vector3d Dj = D.row(j).transpose();
      const Eigen::Vector3d z = Dj.cross(Dk);
      // Quadratic: q . (D_j x D_k); d/dD_j = D_k x q, d/dD_k = q x D_j.
      const Eigen::Vector3d qjk = quadratic_.row(pairIndex(j, k)).transpose();
      value += qjk.dot(z);
      G.row(j) += Dk.cross(qjk).transpose();
      G.row(k) += qjk.cross(Dj).transpose();
      if (j == 0) continue;
      // Cubic: sum_{i<j} K_ijk D_i . z; d/dD_i = K z, d/dD_j = -S x D_k, d/dD_k = S x D_j with S = sum K_ijk D_i.
      const double* Kjk = cubic_.data() + tripleBase(j, k);
      double s0 = 0.0, s1 = 0.0, s2 = 0.0;
      for (std::int64_t i = 0; i < j; ++i) {
        const double kijk = Kjk[i];
        s0 += kijk * D(i, 0);
        s1 += kijk * D(i, 1);
        s2 += kijk * D(i, 2);
        G(i, 0) += kijk * z[0];
        G(i, 1) += kijk * z[1];
        G(i, 2) += kijk * z[2];
      }
      const Eigen::Vector3d S(s0, s1, s2);
      value += S.dot(z);
      G.row(j) -= S.cross(Dk).transpose();
      G.row(k) += S.cross(Dj).transpose();
    }
  }
  gradient.setZero(displacement.rows(), 3);
  for (std::int64_t i = 0; i < a; ++i) gradient.row(active_[std::size_t(i)]) = G.row(i);
  return value;
}

}  // namespace ffdkit::ffd::detail
