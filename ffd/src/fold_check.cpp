#include "ffdkit/ffd/fold_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/LU>

#include "vector_clones.h"

namespace ffdkit::ffd {
namespace {

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

double bernstein(int degree, int k, double x) {
  return binomial(degree, k) * std::pow(x, k) * std::pow(1.0 - x, degree - k);
}

// Per cell of one axis, the Bernstein coefficients of the basis functions non-zero there:
// E(r, k) = coefficient of B_k^p(x) (x = the cell's local coordinate in [0, 1]) in the r-th
// function (AxisSpline::controlIndex(cell, r)). A Bernstein axis is its own Bezier form; a
// B-spline piece is found by collocation at p+1 interior points (exact up to rounding: both
// sides are polynomials of degree p).
std::vector<Eigen::MatrixXd> bezierExtraction(const AxisSpline& axis) {
  const int p = axis.degree();
  std::vector<Eigen::MatrixXd> out(static_cast<std::size_t>(axis.cellCount()));
  Eigen::MatrixXd collocation(p + 1, p + 1);
  for (int j = 0; j <= p; ++j)
    for (int k = 0; k <= p; ++k) collocation(j, k) = bernstein(p, k, (j + 0.5) / (p + 1));
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(collocation);
  std::vector<double> values(static_cast<std::size_t>(p + 1));
  for (int c = 0; c < axis.cellCount(); ++c) {
    if (axis.basis().kind == AxisBasis::Kind::Bernstein) {
      out[std::size_t(c)] = Eigen::MatrixXd::Identity(p + 1, p + 1);
      continue;
    }
    Eigen::MatrixXd N(p + 1, p + 1);  // N(j, r): function r at sample j
    for (int j = 0; j <= p; ++j) {
      const double t = axis.cellMin(c) + (j + 0.5) / (p + 1) * (axis.cellMax(c) - axis.cellMin(c));
      axis.basis(c, t, values.data());
      for (int r = 0; r <= p; ++r) N(j, r) = values[std::size_t(r)];
    }
    out[std::size_t(c)] = lu.solve(N).transpose();
  }
  return out;
}

// A trivariate array of values indexed i + n0 (j + n1 k), n = degree + 1 per axis.
struct Dims {
  int n[3];
  int size() const { return n[0] * n[1] * n[2]; }
  int at(int i, int j, int k) const { return i + n[0] * (j + n[1] * k); }
};

// Splits a Bernstein patch (coefficients c, dims d) at the midpoint of `axis` by de Casteljau.
void split(const std::vector<double>& c, const Dims& d, int axis, std::vector<double>& left, std::vector<double>& right) {
  left.assign(c.size(), 0.0);
  right.assign(c.size(), 0.0);
  const int len = d.n[axis];
  const int stride = axis == 0 ? 1 : axis == 1 ? d.n[0] : d.n[0] * d.n[1];
  double line[64];
  for (int k = 0; k < d.n[2]; ++k)
    for (int j = 0; j < d.n[1]; ++j)
      for (int i = 0; i < d.n[0]; ++i) {
        const int idx[3] = {i, j, k};
        if (idx[axis] != 0) continue;
        const int base = d.at(i, j, k);
        for (int r = 0; r < len; ++r) line[r] = c[std::size_t(base + r * stride)];
        for (int level = 0; level < len; ++level) {
          left[std::size_t(base + level * stride)] = line[0];
          right[std::size_t(base + (len - 1 - level) * stride)] = line[len - 1 - level];
          for (int r = 0; r < len - 1 - level; ++r) line[r] = 0.5 * (line[r] + line[r + 1]);
        }
      }
}

struct Verdict {
  CellFolding folding;
  Eigen::Vector3d witness;  // cell-local coordinates
};

// sign * patch on the box [lo, lo + width]^3 of the cell's local coordinates.
Verdict classify(const std::vector<double>& c, const Dims& d, const Eigen::Vector3d& lo, double width, int depth,
                 int maxDepth) {
  if (*std::min_element(c.begin(), c.end()) > 0.0) return {CellFolding::Positive, {}};
  for (int corner = 0; corner < 8; ++corner) {
    const int i = (corner & 1) ? d.n[0] - 1 : 0, j = (corner & 2) ? d.n[1] - 1 : 0, k = (corner & 4) ? d.n[2] - 1 : 0;
    if (c[std::size_t(d.at(i, j, k))] <= 0.0)
      return {CellFolding::Folds, lo + width * Eigen::Vector3d(corner & 1 ? 1 : 0, corner & 2 ? 1 : 0, corner & 4 ? 1 : 0)};
  }
  if (depth >= maxDepth) return {CellFolding::Unknown, {}};
  std::vector<double> parts[8], l, r;
  parts[0] = c;
  for (int axis = 0, count = 1; axis < 3; ++axis, count *= 2)
    for (int q = count - 1; q >= 0; --q) {
      split(parts[q], d, axis, l, r);
      parts[2 * q] = std::move(l);
      parts[2 * q + 1] = std::move(r);
    }
  // parts[q]: bit 2 = u half, bit 1 = v half, bit 0 = w half (the first axis split is the most
  // significant bit of the final index).
  bool unknown = false;
  for (int q = 0; q < 8; ++q) {
    const Eigen::Vector3d childLo = lo + 0.5 * width * Eigen::Vector3d((q >> 2) & 1, (q >> 1) & 1, q & 1);
    const Verdict v = classify(parts[q], d, childLo, 0.5 * width, depth + 1, maxDepth);
    if (v.folding == CellFolding::Folds) return v;
    unknown = unknown || v.folding == CellFolding::Unknown;
  }
  return {unknown ? CellFolding::Unknown : CellFolding::Positive, {}};
}

// binomial(n, k) for n <= 9 as constants (the fixed-degree products below).
constexpr double kBinomial[10][10] = {
    {1}, {1, 1}, {1, 2, 1}, {1, 3, 3, 1}, {1, 4, 6, 4, 1}, {1, 5, 10, 10, 5, 1}, {1, 6, 15, 20, 15, 6, 1},
    {1, 7, 21, 35, 35, 21, 7, 1}, {1, 8, 28, 56, 70, 56, 28, 8, 1}, {1, 9, 36, 84, 126, 126, 84, 36, 9, 1}};

// det J's Bernstein coefficients from a cell's Bezier net b ((P+1)^3 points, i fastest) when all
// three axes have degree P (1..3): the same two products as the general path below, with every
// size a compile-time constant (arrays on the stack, inner loops unrolled), about 50,000
// multiply-adds for a cubic cell. `out` gets (3P)^3 coefficients, index i + 3P (j + 3P k).
template <int P>
FFDKIT_VECTOR_CLONES void equalDegreeProducts(const Eigen::Vector3d* b, const double width[3], double* out) {
  constexpr int N = P + 1, M = P;          // a net's and a derivative's points per axis
  constexpr int C0 = 2 * P + 1, C1 = 2 * P;  // X_v x X_w: (2P+1) x 2P x 2P
  constexpr int Q = 3 * P;                 // det J: Q^3
  const auto at = [](int i, int j, int k) { return i + N * (j + N * k); };
  // Scaled derivative nets (coefficient times the binomials of its degrees), [coordinate][k][j][i].
  double du[3][N][N][M], dv[3][N][M][N], dw[3][M][N][N];
  const double su = P / width[0], sv = P / width[1], sw = P / width[2];
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        for (int c = 0; c < 3; ++c) {
          if (i < M)
            du[c][k][j][i] = su * kBinomial[M - 1][i] * kBinomial[N - 1][j] * kBinomial[N - 1][k] *
                             (b[at(i + 1, j, k)][c] - b[at(i, j, k)][c]);
          if (j < M)
            dv[c][k][j][i] = sv * kBinomial[N - 1][i] * kBinomial[M - 1][j] * kBinomial[N - 1][k] *
                             (b[at(i, j + 1, k)][c] - b[at(i, j, k)][c]);
          if (k < M)
            dw[c][k][j][i] = sw * kBinomial[N - 1][i] * kBinomial[N - 1][j] * kBinomial[M - 1][k] *
                             (b[at(i, j, k + 1)][c] - b[at(i, j, k)][c]);
        }
  double cross[3][C1][C1][C0] = {};
  for (int kv = 0; kv < N; ++kv)
    for (int jv = 0; jv < M; ++jv)
      for (int kw = 0; kw < M; ++kw)
        for (int jw = 0; jw < N; ++jw)
          for (int iv = 0; iv < N; ++iv) {
            const double vx = dv[0][kv][jv][iv], vy = dv[1][kv][jv][iv], vz = dv[2][kv][jv][iv];
            for (int iw = 0; iw < N; ++iw) {
              const double wx = dw[0][kw][jw][iw], wy = dw[1][kw][jw][iw], wz = dw[2][kw][jw][iw];
              cross[0][kv + kw][jv + jw][iv + iw] += vy * wz - vz * wy;
              cross[1][kv + kw][jv + jw][iv + iw] += vz * wx - vx * wz;
              cross[2][kv + kw][jv + jw][iv + iw] += vx * wy - vy * wx;
            }
          }
  double det[Q][Q][Q] = {};
  for (int ku = 0; ku < N; ++ku)
    for (int ju = 0; ju < N; ++ju)
      for (int kc = 0; kc < C1; ++kc)
        for (int jc = 0; jc < C1; ++jc)
          for (int iu = 0; iu < M; ++iu) {
            const double ux = du[0][ku][ju][iu], uy = du[1][ku][ju][iu], uz = du[2][ku][ju][iu];
            double* __restrict o = det[ku + kc][ju + jc] + iu;
            const double* __restrict cx = cross[0][kc][jc];
            const double* __restrict cy = cross[1][kc][jc];
            const double* __restrict cz = cross[2][kc][jc];
            for (int ic = 0; ic < C0; ++ic) o[ic] += ux * cx[ic] + uy * cy[ic] + uz * cz[ic];
          }
  for (int k = 0; k < Q; ++k)
    for (int j = 0; j < Q; ++j)
      for (int i = 0; i < Q; ++i)
        out[i + Q * (j + Q * k)] = det[k][j][i] / (kBinomial[Q - 1][i] * kBinomial[Q - 1][j] * kBinomial[Q - 1][k]);
}

// The patch of one cell given the per-axis extraction matrices.
JacobianDeterminantPatch patchOf(const Lattice& lattice, const std::array<int, 3>& cell,
                                 const std::vector<Eigen::MatrixXd>* extraction) {
  int p[3];
  double width[3];
  JacobianDeterminantPatch patch;
  for (int a = 0; a < 3; ++a) {
    p[a] = lattice.axis(a).degree();
    patch.parameterMin[a] = lattice.axis(a).cellMin(cell[a]);
    patch.parameterMax[a] = lattice.axis(a).cellMax(cell[a]);
    width[a] = patch.parameterMax[a] - patch.parameterMin[a];
  }
  const Eigen::MatrixXd& Eu = extraction[0][std::size_t(cell[0])];
  const Eigen::MatrixXd& Ev = extraction[1][std::size_t(cell[1])];
  const Eigen::MatrixXd& Ew = extraction[2][std::size_t(cell[2])];
  // The cell's Bezier net b (3 coordinates), one axis at a time.
  const Dims net{{p[0] + 1, p[1] + 1, p[2] + 1}};
  std::vector<Eigen::Vector3d> window(std::size_t(net.size())), t1(window.size()), t2(window.size()), b(window.size());
  for (int k = 0; k <= p[2]; ++k)
    for (int j = 0; j <= p[1]; ++j)
      for (int i = 0; i <= p[0]; ++i)
        window[std::size_t(net.at(i, j, k))] =
            lattice.controlPoints()
                .row(lattice.index(lattice.axis(0).controlIndex(cell[0], i), lattice.axis(1).controlIndex(cell[1], j),
                                   lattice.axis(2).controlIndex(cell[2], k)))
                .transpose();
  for (int k = 0; k <= p[2]; ++k)
    for (int j = 0; j <= p[1]; ++j)
      for (int i = 0; i <= p[0]; ++i) {
        Eigen::Vector3d s = Eigen::Vector3d::Zero();
        for (int r = 0; r <= p[0]; ++r) s += Eu(r, i) * window[std::size_t(net.at(r, j, k))];
        t1[std::size_t(net.at(i, j, k))] = s;
      }
  for (int k = 0; k <= p[2]; ++k)
    for (int j = 0; j <= p[1]; ++j)
      for (int i = 0; i <= p[0]; ++i) {
        Eigen::Vector3d s = Eigen::Vector3d::Zero();
        for (int r = 0; r <= p[1]; ++r) s += Ev(r, j) * t1[std::size_t(net.at(i, r, k))];
        t2[std::size_t(net.at(i, j, k))] = s;
      }
  for (int k = 0; k <= p[2]; ++k)
    for (int j = 0; j <= p[1]; ++j)
      for (int i = 0; i <= p[0]; ++i) {
        Eigen::Vector3d s = Eigen::Vector3d::Zero();
        for (int r = 0; r <= p[2]; ++r) s += Ew(r, k) * t2[std::size_t(net.at(i, j, r))];
        b[std::size_t(net.at(i, j, k))] = s;
      }
  if (p[0] == p[1] && p[1] == p[2] && p[0] >= 1 && p[0] <= 3) {
    const int q = 3 * p[0];
    patch.coefficients.resize(q * q * q);
    if (p[0] == 1) equalDegreeProducts<1>(b.data(), width, patch.coefficients.data());
    if (p[0] == 2) equalDegreeProducts<2>(b.data(), width, patch.coefficients.data());
    if (p[0] == 3) equalDegreeProducts<3>(b.data(), width, patch.coefficients.data());
    patch.degrees = {q - 1, q - 1, q - 1};
    return patch;
  }
  // Derivative nets in scaled Bernstein form (coefficient times C(d0,i) C(d1,j) C(d2,k)), so
  // that a product is a plain convolution: sum f~_a g~_b lands on f~g~_(a+b).
  Dims dd[3];
  std::vector<Eigen::Vector3d> D[3];
  double binomials[3][3][12];  // binomials[a][axis][i] = C(dd[a].n[axis] - 1, i)
  for (int a = 0; a < 3; ++a) {
    dd[a] = net;
    dd[a].n[a] -= 1;
    for (int axis = 0; axis < 3; ++axis)
      for (int i = 0; i < dd[a].n[axis]; ++i) binomials[a][axis][i] = binomial(dd[a].n[axis] - 1, i);
    D[a].resize(std::size_t(dd[a].size()));
    for (int k = 0; k < dd[a].n[2]; ++k)
      for (int j = 0; j < dd[a].n[1]; ++j)
        for (int i = 0; i < dd[a].n[0]; ++i) {
          int next[3] = {i, j, k};
          next[a] += 1;
          const double scaledBinomials = binomials[a][0][i] * binomials[a][1][j] * binomials[a][2][k];
          D[a][std::size_t(dd[a].at(i, j, k))] =
              (p[a] / width[a] * scaledBinomials) *
              (b[std::size_t(net.at(next[0], next[1], next[2]))] - b[std::size_t(net.at(i, j, k))]);
        }
  }
  const Dims out{{3 * p[0], 3 * p[1], 3 * p[2]}};
  // Products of nets as 3D convolutions, the u index innermost and contiguous on both sides (one
  // array per coordinate), so that the compiler vectorises the inner loop.
  const auto split3 = [](const std::vector<Eigen::Vector3d>& v, std::vector<double> c[3]) {
    for (int k = 0; k < 3; ++k) {
      c[k].resize(v.size());
      for (std::size_t i = 0; i < v.size(); ++i) c[k][i] = v[i][k];
    }
  };
  std::vector<double> Du[3], Dv[3], Dw[3];
  split3(D[0], Du);
  split3(D[1], Dv);
  split3(D[2], Dw);
  // X_v x X_w: degrees (2p, 2q-1, 2r-1).
  const Dims cd{{dd[1].n[0] + dd[2].n[0] - 1, dd[1].n[1] + dd[2].n[1] - 1, dd[1].n[2] + dd[2].n[2] - 1}};
  std::vector<double> C[3];
  for (int k = 0; k < 3; ++k) C[k].assign(std::size_t(cd.size()), 0.0);
  const int vn0 = dd[1].n[0], wn0 = dd[2].n[0];
  for (int kv = 0; kv < dd[1].n[2]; ++kv)
    for (int jv = 0; jv < dd[1].n[1]; ++jv)
      for (int kw = 0; kw < dd[2].n[2]; ++kw)
        for (int jw = 0; jw < dd[2].n[1]; ++jw) {
          const int rowOut = cd.at(0, jv + jw, kv + kw);
          const int rowV = dd[1].at(0, jv, kv), rowW = dd[2].at(0, jw, kw);
          for (int iv = 0; iv < vn0; ++iv) {
            const double vx = Dv[0][std::size_t(rowV + iv)], vy = Dv[1][std::size_t(rowV + iv)],
                         vz = Dv[2][std::size_t(rowV + iv)];
            double* __restrict cx = C[0].data() + rowOut + iv;
            double* __restrict cy = C[1].data() + rowOut + iv;
            double* __restrict cz = C[2].data() + rowOut + iv;
            const double* __restrict wx = Dw[0].data() + rowW;
            const double* __restrict wy = Dw[1].data() + rowW;
            const double* __restrict wz = Dw[2].data() + rowW;
            for (int iw = 0; iw < wn0; ++iw) {
              cx[iw] += vy * wz[iw] - vz * wy[iw];
              cy[iw] += vz * wx[iw] - vx * wz[iw];
              cz[iw] += vx * wy[iw] - vy * wx[iw];
            }
          }
        }
  // X_u . (X_v x X_w): degrees (3p-1, 3q-1, 3r-1).
  patch.coefficients = Eigen::VectorXd::Zero(out.size());
  double* __restrict det = patch.coefficients.data();
  const int un0 = dd[0].n[0], cn0 = cd.n[0];
  for (int ku = 0; ku < dd[0].n[2]; ++ku)
    for (int ju = 0; ju < dd[0].n[1]; ++ju)
      for (int kc = 0; kc < cd.n[2]; ++kc)
        for (int jc = 0; jc < cd.n[1]; ++jc) {
          const int rowOut = out.at(0, ju + jc, ku + kc);
          const int rowU = dd[0].at(0, ju, ku), rowC = cd.at(0, jc, kc);
          for (int iu = 0; iu < un0; ++iu) {
            const double ux = Du[0][std::size_t(rowU + iu)], uy = Du[1][std::size_t(rowU + iu)],
                         uz = Du[2][std::size_t(rowU + iu)];
            const double* __restrict cx = C[0].data() + rowC;
            const double* __restrict cy = C[1].data() + rowC;
            const double* __restrict cz = C[2].data() + rowC;
            double* __restrict o = det + rowOut + iu;
            for (int ic = 0; ic < cn0; ++ic) o[ic] += ux * cx[ic] + uy * cy[ic] + uz * cz[ic];
          }
        }
  // Back from the scaled form: divide by C(d0, i) C(d1, j) C(d2, k) (reciprocals per axis).
  double inverse[3][32];
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < out.n[a]; ++i) inverse[a][i] = 1.0 / binomial(out.n[a] - 1, i);
  for (int k = 0; k < out.n[2]; ++k)
    for (int j = 0; j < out.n[1]; ++j) {
      const double jk = inverse[1][j] * inverse[2][k];
      for (int i = 0; i < out.n[0]; ++i) patch.coefficients[out.at(i, j, k)] *= inverse[0][i] * jk;
    }
  patch.degrees = {out.n[0] - 1, out.n[1] - 1, out.n[2] - 1};
  return patch;
}

}  // namespace

double JacobianDeterminantPatch::value(const Eigen::Vector3d& uvw) const {
  double basis[3][32];
  for (int a = 0; a < 3; ++a) {
    const double x = (uvw[a] - parameterMin[a]) / (parameterMax[a] - parameterMin[a]);
    for (int k = 0; k <= degrees[a]; ++k) basis[a][k] = bernstein(degrees[a], k, x);
  }
  double sum = 0.0;
  Eigen::Index at = 0;
  for (int k = 0; k <= degrees[2]; ++k)
    for (int j = 0; j <= degrees[1]; ++j)
      for (int i = 0; i <= degrees[0]; ++i) sum += coefficients[at++] * basis[0][i] * basis[1][j] * basis[2][k];
  return sum;
}

JacobianDeterminantPatch jacobianDeterminantPatch(const Lattice& lattice, const std::array<int, 3>& cell) {
  std::vector<Eigen::MatrixXd> extraction[3];
  for (int a = 0; a < 3; ++a) {
    if (cell[a] < 0 || cell[a] >= lattice.axis(a).cellCount())
      throw LatticeError("jacobianDeterminantPatch: cell (" + std::to_string(cell[0]) + ", " + std::to_string(cell[1]) +
                         ", " + std::to_string(cell[2]) + ") out of range, the lattice has (" +
                         std::to_string(lattice.axis(0).cellCount()) + ", " + std::to_string(lattice.axis(1).cellCount()) +
                         ", " + std::to_string(lattice.axis(2).cellCount()) + ") cells");
    if (lattice.axis(a).degree() > 10)
      throw LatticeError("jacobianDeterminantPatch: degree " + std::to_string(lattice.axis(a).degree()) +
                         " on axis " + std::to_string(a) + " above 10");
    extraction[a] = bezierExtraction(lattice.axis(a));
  }
  return patchOf(lattice, cell, extraction);
}

namespace {

// A rational lattice's det J is a ratio (the polynomial bound above does not apply): each cell is
// sampled on a 5 x 5 x 5 grid of its closed box; a sample with sign * det J <= 0 proves Folds,
// otherwise the cell stays Unknown (never certified). lowerBound: the smallest sample, which
// bounds nothing (NaN).
void checkRationalFolding(const Lattice& lattice, FoldCheckResult& result) {
  const int cu = result.cellCounts[0], cv = result.cellCounts[1], cw = result.cellCounts[2];
  const std::int64_t cellCount = std::int64_t(cu) * cv * cw;
  constexpr int kSamples = 5;
#pragma omp parallel for schedule(dynamic, 1) if (cellCount >= 8)
  for (std::int64_t flat = 0; flat < cellCount; ++flat) {
    const int cell[3] = {int(flat % cu), int(flat / cu % cv), int(flat / cu / cv)};
    result.lowerBound[std::size_t(flat)] = std::numeric_limits<double>::quiet_NaN();
    for (int k = 0; k < kSamples && result.cells[std::size_t(flat)] != CellFolding::Folds; ++k)
      for (int j = 0; j < kSamples; ++j)
        for (int i = 0; i < kSamples; ++i) {
          const int at[3] = {i, j, k};
          Eigen::Vector3d uvw;
          for (int a = 0; a < 3; ++a) {
            const AxisSpline& axis = lattice.axis(a);
            uvw[a] = axis.cellMin(cell[a]) + (axis.cellMax(cell[a]) - axis.cellMin(cell[a])) * at[a] / (kSamples - 1);
          }
          if (result.orientation * lattice.jacobian(uvw).determinant() <= 0.0) {
            result.cells[std::size_t(flat)] = CellFolding::Folds;
            result.witness[std::size_t(flat)] = uvw;
          }
        }
  }
  for (CellFolding c : result.cells) {
    result.foldsCount += c == CellFolding::Folds;
    result.unknownCount += c == CellFolding::Unknown;
  }
}

}  // namespace

FoldCheckResult checkFolding(const Lattice& lattice, const FoldCheckOptions& options) {
  if (options.maxDepth < 0 || options.maxDepth > 10)
    throw LatticeError("checkFolding: maxDepth must be in [0, 10], got " + std::to_string(options.maxDepth));
  std::vector<Eigen::MatrixXd> extraction[3];
  FoldCheckResult result;
  for (int a = 0; a < 3; ++a) {
    if (lattice.axis(a).degree() > 10)
      throw LatticeError("checkFolding: degree " + std::to_string(lattice.axis(a).degree()) + " on axis " +
                         std::to_string(a) + " above 10");
    extraction[a] = bezierExtraction(lattice.axis(a));
    result.cellCounts[std::size_t(a)] = lattice.axis(a).cellCount();
  }
  const Eigen::Vector3d centre = 0.5 * (lattice.parameterMin() + lattice.parameterMax());
  result.orientation = lattice.restJacobian(centre).determinant() < 0.0 ? -1 : 1;
  const int cu = result.cellCounts[0], cv = result.cellCounts[1], cw = result.cellCounts[2];
  const std::int64_t cellCount = std::int64_t(cu) * cv * cw;
  result.cells.assign(std::size_t(cellCount), CellFolding::Unknown);
  result.lowerBound.assign(std::size_t(cellCount), 0.0);
  result.witness.assign(std::size_t(cellCount), Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  if (lattice.isRational()) {
    checkRationalFolding(lattice, result);
    return result;
  }
#pragma omp parallel for schedule(dynamic, 1) if (cellCount >= 8)
  for (std::int64_t flat = 0; flat < cellCount; ++flat) {
    const std::array<int, 3> cell = {int(flat % cu), int(flat / cu % cv), int(flat / cu / cv)};
    const JacobianDeterminantPatch patch = patchOf(lattice, cell, extraction);
    const double lowest = result.orientation > 0 ? patch.coefficients.minCoeff() : -patch.coefficients.maxCoeff();
    result.lowerBound[std::size_t(flat)] = lowest;
    if (lowest > 0.0) {  // certified at once (most cells of a usable lattice)
      result.cells[std::size_t(flat)] = CellFolding::Positive;
      continue;
    }
    std::vector<double> signedCoefficients(patch.coefficients.data(), patch.coefficients.data() + patch.coefficients.size());
    for (double& c : signedCoefficients) c *= result.orientation;
    const Dims d{{patch.degrees[0] + 1, patch.degrees[1] + 1, patch.degrees[2] + 1}};
    const Verdict v = classify(signedCoefficients, d, Eigen::Vector3d::Zero(), 1.0, 0, options.maxDepth);
    result.cells[std::size_t(flat)] = v.folding;
    if (v.folding == CellFolding::Folds)
      result.witness[std::size_t(flat)] =
          patch.parameterMin + (patch.parameterMax - patch.parameterMin).cwiseProduct(v.witness);
  }
  for (CellFolding c : result.cells) {
    result.positiveCount += c == CellFolding::Positive;
    result.foldsCount += c == CellFolding::Folds;
    result.unknownCount += c == CellFolding::Unknown;
  }
  return result;
}

}  // namespace ffdkit::ffd
