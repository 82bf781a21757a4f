#include "fold_lanes.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

#include "fold_convolve.h"
#include "vector_clones.h"

namespace ffdkit::ffd::detail {
namespace {

constexpr int L = kFoldLanes;
typedef double Lanes __attribute__((vector_size(L * sizeof(double))));

// Unaligned loads and stores of one lane vector (the buffers are plain doubles, lane fastest).
FFDKIT_INLINE Lanes load(const double* p) {
  Lanes v;
  std::memcpy(&v, p, sizeof(v));
  return v;
}
FFDKIT_INLINE void store(double* p, const Lanes& v) { std::memcpy(p, &v, sizeof(v)); }

// binomial(n, k) for n <= 8 and their reciprocals (the scaled Bernstein forms below).
constexpr double kBinomial[9][9] = {{1},
                                    {1, 1},
                                    {1, 2, 1},
                                    {1, 3, 3, 1},
                                    {1, 4, 6, 4, 1},
                                    {1, 5, 10, 10, 5, 1},
                                    {1, 6, 15, 20, 15, 6, 1},
                                    {1, 7, 21, 35, 35, 21, 7, 1},
                                    {1, 8, 28, 56, 70, 56, 28, 8, 1}};

// The cells' Bezier nets from their control windows: per lane the window (lane fastest), then
// the extraction matrices applied one axis at a time (a Bernstein axis's is the identity, exact).
// net: [N^3][C][L] (C components per point: 3 for P, 4 for (w P, w)), E: [3][N][N][L]
// (E[a][r][i]: coefficient of B_i in the r-th function).
template <int P, int C>
FFDKIT_VECTOR_CLONES void bezierNets(double* __restrict net, const double* __restrict E) {
  constexpr int N = P + 1;
  Lanes a[N][N][N][C], t[N][N][N][C], e[3][N][N];  // a[k][j][i][c], e[axis][r][i]
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        for (int c = 0; c < C; ++c) a[k][j][i][c] = load(net + L * (c + C * (i + N * (j + N * k))));
  for (int axis = 0; axis < 3; ++axis)
    for (int r = 0; r < N; ++r)
      for (int i = 0; i < N; ++i) e[axis][r][i] = load(E + L * (i + N * (r + N * axis)));
  // Along u: t[k][j][i] = sum_r e[0][r][i] a[k][j][r]; along v into a; along w into net.
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        for (int c = 0; c < C; ++c) {
          Lanes sum = e[0][0][i] * a[k][j][0][c];
          for (int r = 1; r < N; ++r) sum += e[0][r][i] * a[k][j][r][c];
          t[k][j][i][c] = sum;
        }
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        for (int c = 0; c < C; ++c) {
          Lanes sum = e[1][0][j] * t[k][0][i][c];
          for (int r = 1; r < N; ++r) sum += e[1][r][j] * t[k][r][i][c];
          a[k][j][i][c] = sum;
        }
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        for (int c = 0; c < C; ++c) {
          Lanes sum = e[2][0][k] * a[0][j][i][c];
          for (int r = 1; r < N; ++r) sum += e[2][r][k] * a[r][j][i][c];
          store(net + L * (c + C * (i + N * (j + N * k))), sum);
        }
}

// det J's Bernstein coefficients of the L cells whose Bezier nets are `net` ([N^3][3][L], i
// fastest), `scale` = p / cell width per axis ([3][L]): the derivative nets in scaled Bernstein
// form (coefficient times the binomials of its degrees, so that a product is a convolution), then
// C = X_v x X_w and X_u . C, each output row (the innermost index) accumulated in registers over
// the rows of the factors that reach it. `out` gets (3P)^3 coefficients x L, lane fastest, index
// i + 3P (j + 3P k); lowest / highest their smallest and largest per lane.
template <int P>
FFDKIT_VECTOR_CLONES void determinantLanes(const double* __restrict net, const double* __restrict scale,
                                           double* __restrict out, double* lowest, double* highest) {
  constexpr int N = P + 1, M = P;            // a net's and a derivative's points per axis
  constexpr int C0 = 2 * P + 1, C1 = 2 * P;  // X_v x X_w: (2P+1) x 2P x 2P
  constexpr int Q = 3 * P;                   // det J: Q^3
  const auto b = [net](int i, int j, int k, int c) { return load(net + L * (c + 3 * (i + N * (j + N * k)))); };
  Lanes du[3][N][N][M], dv[3][N][M][N], dw[3][M][N][N];
  const Lanes su = load(scale), sv = load(scale + L), sw = load(scale + 2 * L);
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        for (int c = 0; c < 3; ++c) {
          if (i < M)
            du[c][k][j][i] = (kBinomial[M - 1][i] * kBinomial[N - 1][j] * kBinomial[N - 1][k]) * su *
                             (b(i + 1, j, k, c) - b(i, j, k, c));
          if (j < M)
            dv[c][k][j][i] = (kBinomial[N - 1][i] * kBinomial[M - 1][j] * kBinomial[N - 1][k]) * sv *
                             (b(i, j + 1, k, c) - b(i, j, k, c));
          if (k < M)
            dw[c][k][j][i] = (kBinomial[N - 1][i] * kBinomial[N - 1][j] * kBinomial[M - 1][k]) * sw *
                             (b(i, j, k + 1, c) - b(i, j, k, c));
        }
  // C = X_v x X_w: row (kc, jc) gathers the rows (kv, jv) of X_v and (kc - kv, jc - jv) of X_w.
  Lanes cross[C1][C1][3][C0];
  for (int kc = 0; kc < C1; ++kc)
    for (int jc = 0; jc < C1; ++jc) {
      Lanes acc[3][C0] = {};
      for (int kv = std::max(0, kc - (M - 1)); kv <= std::min(N - 1, kc); ++kv)
        for (int jv = std::max(0, jc - (N - 1)); jv <= std::min(M - 1, jc); ++jv) {
          const int kw = kc - kv, jw = jc - jv;
#pragma GCC unroll 4
          for (int iv = 0; iv < N; ++iv) {
            const Lanes vx = dv[0][kv][jv][iv], vy = dv[1][kv][jv][iv], vz = dv[2][kv][jv][iv];
#pragma GCC unroll 4
            for (int iw = 0; iw < N; ++iw) {
              const Lanes wx = dw[0][kw][jw][iw], wy = dw[1][kw][jw][iw], wz = dw[2][kw][jw][iw];
              // One fused multiply-add per product (not a product, a fused difference and an add).
              acc[0][iv + iw] = acc[0][iv + iw] + vy * wz;
              acc[0][iv + iw] = acc[0][iv + iw] - vz * wy;
              acc[1][iv + iw] = acc[1][iv + iw] + vz * wx;
              acc[1][iv + iw] = acc[1][iv + iw] - vx * wz;
              acc[2][iv + iw] = acc[2][iv + iw] + vx * wy;
              acc[2][iv + iw] = acc[2][iv + iw] - vy * wx;
            }
          }
        }
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < C0; ++i) cross[kc][jc][c][i] = acc[c][i];
    }
  // det J = X_u . C: row (K, J) gathers the rows (ku, ju) of X_u and (K - ku, J - ju) of C; back
  // from the scaled form by the reciprocal binomials of degree Q - 1.
  double inverse[Q];
  for (int i = 0; i < Q; ++i) inverse[i] = 1.0 / kBinomial[Q - 1][i];
  Lanes lo = Lanes{} + std::numeric_limits<double>::infinity(), hi = -lo;
  for (int K = 0; K < Q; ++K)
    for (int J = 0; J < Q; ++J) {
      Lanes acc[Q] = {};
      for (int ku = std::max(0, K - (C1 - 1)); ku <= std::min(N - 1, K); ++ku)
        for (int ju = std::max(0, J - (C1 - 1)); ju <= std::min(N - 1, J); ++ju) {
          const int kc = K - ku, jc = J - ju;
          Lanes ux[M], uy[M], uz[M];
          for (int iu = 0; iu < M; ++iu) {
            ux[iu] = du[0][ku][ju][iu];
            uy[iu] = du[1][ku][ju][iu];
            uz[iu] = du[2][ku][ju][iu];
          }
#pragma GCC unroll 8
          for (int ic = 0; ic < C0; ++ic) {
            const Lanes cx = cross[kc][jc][0][ic], cy = cross[kc][jc][1][ic], cz = cross[kc][jc][2][ic];
#pragma GCC unroll 4
            for (int iu = 0; iu < M; ++iu) {
              acc[iu + ic] = acc[iu + ic] + ux[iu] * cx;
              acc[iu + ic] = acc[iu + ic] + uy[iu] * cy;
              acc[iu + ic] = acc[iu + ic] + uz[iu] * cz;
            }
          }
        }
      const double jk = inverse[J] * inverse[K];
      for (int I = 0; I < Q; ++I) {
        const Lanes value = acc[I] * (inverse[I] * jk);
        store(out + L * (I + Q * (J + Q * K)), value);
        lo = value < lo ? value : lo;
        hi = value > hi ? value : hi;
      }
    }
  store(lowest, lo);
  store(highest, hi);
}

// G = det[H_u, H_v, H_w, H] of the L cells whose homogeneous Bezier nets are `net` ([N^3][4][L],
// (w P, w)), `scale` = p / cell width ([3][L]): the columns in scaled Bernstein form, then
// detail::rationalDeterminant with one lane per cell (minor2, minor3 and out: scratch of its
// sizes, 64-byte aligned). `out` then holds G's (4P)^3 coefficients (unscaled), lowest / highest
// their smallest and largest per lane.
template <int P>
FFDKIT_VECTOR_CLONES void rationalLanes(const double* __restrict net, const double* __restrict scale, Lanes* columnStore,
                                        Lanes* minor2, Lanes* minor3, Lanes* out, double* lowest, double* highest) {
  constexpr int N = P + 1, Q = 4 * P;
  const Lanes s[3] = {load(scale), load(scale + L), load(scale + 2 * L)};
  const auto b = [net](int i, int j, int k, int c) { return load(net + L * (c + 4 * (i + N * (j + N * k)))); };
  const Lanes* columns[4][4];
  for (int a = 0; a < 4; ++a) {
    int d[3] = {N, N, N};
    if (a < 3) d[a] -= 1;
    for (int c = 0; c < 4; ++c) {
      Lanes* column = columnStore + N * N * N * (c + 4 * a);
      columns[a][c] = column;
      for (int k = 0; k < d[2]; ++k)
        for (int j = 0; j < d[1]; ++j)
          for (int i = 0; i < d[0]; ++i) {
            const double binomials = kBinomial[d[0] - 1][i] * kBinomial[d[1] - 1][j] * kBinomial[d[2] - 1][k];
            Lanes value = b(i, j, k, c);
            if (a < 3) {
              int next[3] = {i, j, k};
              next[a] += 1;
              value = s[a] * (b(next[0], next[1], next[2], c) - value);
            }
            column[i + d[0] * (j + d[1] * k)] = binomials * value;
          }
    }
  }
  rationalDeterminant<Lanes, P>(columns, minor2, minor3, out);
  double inverse[Q];
  for (int i = 0; i < Q; ++i) {
    double binomial = 1.0;
    for (int r = 1; r <= i; ++r) binomial = binomial * (Q - 1 - i + r) / r;
    inverse[i] = 1.0 / binomial;
  }
  Lanes lo = Lanes{} + std::numeric_limits<double>::infinity(), hi = -lo;
  for (int k = 0; k < Q; ++k)
    for (int j = 0; j < Q; ++j) {
      const double jk = inverse[j] * inverse[k];
      for (int i = 0; i < Q; ++i) {
        Lanes& value = out[i + Q * (j + Q * k)];
        value = value * (inverse[i] * jk);
        lo = value < lo ? value : lo;
        hi = value > hi ? value : hi;
      }
    }
  store(lowest, lo);
  store(highest, hi);
}

}  // namespace

bool foldLanesSupport(const Lattice& lattice) {
  const int p = lattice.axis(0).degree();
  return p >= 1 && p <= 3 && lattice.axis(1).degree() == p && lattice.axis(2).degree() == p;
}

DeterminantLanes::DeterminantLanes(const Lattice& lattice, const std::vector<Eigen::MatrixXd>* extraction)
    : lattice_(lattice), extraction_(extraction), degree_(3 * lattice.axis(0).degree() - 1) {
  coefficients_.resize(std::size_t((degree_ + 1) * (degree_ + 1) * (degree_ + 1) * L));
}

namespace {

// The windows of cells[0 .. count) into lanes (spare lanes repeat the last cell): net [N^3][C][L]
// (C = 3: the control points; C = 4: (w P, w)), the extraction matrices E [3][N][N][L], p / cell
// width per axis [3][L], and with C = 4 each window's smallest and largest weight.
void gatherWindows(const Lattice& lattice, const std::vector<Eigen::MatrixXd>* extraction,
                   const std::array<int, 3>* cells, int count, int C, double* net, double* E, double* scale,
                   double* minWeight = nullptr, double* maxWeight = nullptr) {
  const int p = lattice.axis(0).degree(), n = p + 1;
  const Eigen::MatrixX3d& points = lattice.controlPoints();
  for (int lane = 0; lane < L; ++lane) {
    const std::array<int, 3>& cell = cells[std::min(lane, count - 1)];
    for (int a = 0; a < 3; ++a) {
      const AxisSpline& axis = lattice.axis(a);
      scale[L * a + lane] = p / (axis.cellMax(cell[a]) - axis.cellMin(cell[a]));
      const Eigen::MatrixXd& e = extraction[a][std::size_t(cell[a])];
      for (int r = 0; r < n; ++r)
        for (int i = 0; i < n; ++i) E[L * (i + n * (r + n * a)) + lane] = e(r, i);
    }
    double lightest = std::numeric_limits<double>::infinity(), heaviest = 0.0;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const Eigen::Index f = lattice.index(lattice.axis(0).controlIndex(cell[0], i),
                                               lattice.axis(1).controlIndex(cell[1], j),
                                               lattice.axis(2).controlIndex(cell[2], k));
          double* at = net + L * C * (i + n * (j + n * k)) + lane;
          if (C == 3) {
            for (int c = 0; c < 3; ++c) at[L * c] = points(f, c);
          } else {
            const double w = lattice.weight(f);
            for (int c = 0; c < 3; ++c) at[L * c] = w * points(f, c);
            at[L * 3] = w;
            lightest = std::min(lightest, w);
            heaviest = std::max(heaviest, w);
          }
        }
    if (minWeight) minWeight[lane] = lightest;
    if (maxWeight) maxWeight[lane] = heaviest;
  }
}

}  // namespace

void DeterminantLanes::compute(const std::array<int, 3>* cells, int count) {
  const int p = lattice_.axis(0).degree();
  alignas(64) double net[64 * 3 * L], E[3 * 4 * 4 * L], scale[3 * L];
  gatherWindows(lattice_, extraction_, cells, count, 3, net, E, scale);
  if (p == 1) {
    bezierNets<1, 3>(net, E);
    determinantLanes<1>(net, scale, coefficients_.data(), lowest_, highest_);
  } else if (p == 2) {
    bezierNets<2, 3>(net, E);
    determinantLanes<2>(net, scale, coefficients_.data(), lowest_, highest_);
  } else {
    bezierNets<3, 3>(net, E);
    determinantLanes<3>(net, scale, coefficients_.data(), lowest_, highest_);
  }
}

void DeterminantLanes::coefficients(int lane, double sign, std::vector<double>& out) const {
  out.resize(coefficients_.size() / L);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = sign * coefficients_[L * i + std::size_t(lane)];
}

}  // namespace ffdkit::ffd::detail

namespace ffdkit::ffd::detail {

RationalLanes::RationalLanes(const Lattice& lattice, const std::vector<Eigen::MatrixXd>* extraction)
    : lattice_(lattice), extraction_(extraction), degree_(4 * lattice.axis(0).degree() - 1) {
  const int p = lattice.axis(0).degree();
  // Columns (16 nets of at most (p+1)^3), the 2 x 2 and 3 x 3 minors and G, one lane vector each.
  const std::size_t vectors = std::size_t(16 * (p + 1) * (p + 1) * (p + 1) + 6 * rationalMinor2Size(p) +
                                          4 * rationalMinor3Size(p) + 64 * p * p * p);
  storage_.resize(L * vectors + L);  // + L: room to align to 64 bytes
}

double* RationalLanes::aligned() {
  const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(storage_.data());
  return storage_.data() + (((64 - at % 64) % 64) / sizeof(double));
}

const double* RationalLanes::coefficientData() const {
  const int p = lattice_.axis(0).degree();
  const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(storage_.data());
  const double* base = storage_.data() + (((64 - at % 64) % 64) / sizeof(double));
  return base + L * std::size_t(16 * (p + 1) * (p + 1) * (p + 1) + 6 * rationalMinor2Size(p) + 4 * rationalMinor3Size(p));
}

void RationalLanes::compute(const std::array<int, 3>* cells, int count) {
  const int p = lattice_.axis(0).degree();
  alignas(64) double net[64 * 4 * L], E[3 * 4 * 4 * L], scale[3 * L];
  gatherWindows(lattice_, extraction_, cells, count, 4, net, E, scale, minWeight_, maxWeight_);
  Lanes* columns = reinterpret_cast<Lanes*>(aligned());
  Lanes* minor2 = columns + 16 * (p + 1) * (p + 1) * (p + 1);
  Lanes* minor3 = minor2 + 6 * rationalMinor2Size(p);
  Lanes* out = minor3 + 4 * rationalMinor3Size(p);
  if (p == 1) {
    bezierNets<1, 4>(net, E);
    rationalLanes<1>(net, scale, columns, minor2, minor3, out, lowest_, highest_);
  } else if (p == 2) {
    bezierNets<2, 4>(net, E);
    rationalLanes<2>(net, scale, columns, minor2, minor3, out, lowest_, highest_);
  } else {
    bezierNets<3, 4>(net, E);
    rationalLanes<3>(net, scale, columns, minor2, minor3, out, lowest_, highest_);
  }
}

void RationalLanes::coefficients(int lane, double sign, std::vector<double>& out) const {
  const std::size_t n = std::size_t((degree_ + 1) * (degree_ + 1) * (degree_ + 1));
  const double* G = coefficientData();
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = sign * G[L * i + std::size_t(lane)];
}

}  // namespace ffdkit::ffd::detail
