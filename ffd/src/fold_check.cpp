#include "ffdkit/ffd/fold_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/LU>

#include "fold_convolve.h"
#include "fold_lanes.h"
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

// The fold-over bound's degree limit (kFoldCheckMaxDegree; the fixed-size rows below hold it).
void checkDegree(const Lattice& lattice, int axis, const char* what) {
  if (lattice.axis(axis).degree() > kFoldCheckMaxDegree)
    throw LatticeError(std::string(what) + ": axis " + std::to_string(axis) + " has degree " +
                       std::to_string(lattice.axis(axis).degree()) + "; the fold-over bound handles degrees up to " +
                       std::to_string(kFoldCheckMaxDegree));
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
    checkDegree(lattice, a, "jacobianDeterminantPatch");
    extraction[a] = bezierExtraction(lattice.axis(a));
  }
  return patchOf(lattice, cell, extraction);
}

namespace {

// A cell's verdict from det J's coefficients times the orientation (`signedCoefficients`, degree
// `degree` per axis) whose lowest is not > 0: a corner <= 0 folds, else subdivision decides.
void classifyCell(const Lattice& lattice, const FoldCheckOptions& options, const std::array<int, 3>& cell,
                  const std::vector<double>& signedCoefficients, const std::array<int, 3>& degrees, std::size_t flat,
                  FoldCheckResult& result) {
  const Dims d{{degrees[0] + 1, degrees[1] + 1, degrees[2] + 1}};
  const Verdict v = classify(signedCoefficients, d, Eigen::Vector3d::Zero(), 1.0, 0, options.maxDepth);
  result.cells[flat] = v.folding;
  if (v.folding != CellFolding::Folds) return;
  for (int a = 0; a < 3; ++a) {
    const double lo = lattice.axis(a).cellMin(cell[a]), hi = lattice.axis(a).cellMax(cell[a]);
    result.witness[flat][a] = lo + (hi - lo) * v.witness[a];
  }
}

// One cell of a polynomial map by the general product of nets (any degrees): det J's Bernstein
// coefficients certify Positive at once, or subdivision decides.
void checkPolynomialCell(const Lattice& lattice, const FoldCheckOptions& options,
                         const std::vector<Eigen::MatrixXd>* extraction, const std::array<int, 3>& cell,
                         std::size_t flat, FoldCheckResult& result) {
  const JacobianDeterminantPatch patch = patchOf(lattice, cell, extraction);
  const double lowest = result.orientation > 0 ? patch.coefficients.minCoeff() : -patch.coefficients.maxCoeff();
  result.lowerBound[flat] = lowest;
  if (lowest > 0.0) {  // certified at once (most cells of a usable lattice)
    result.cells[flat] = CellFolding::Positive;
    return;
  }
  std::vector<double> signedCoefficients(patch.coefficients.data(), patch.coefficients.data() + patch.coefficients.size());
  for (double& c : signedCoefficients) c *= result.orientation;
  classifyCell(lattice, options, cell, signedCoefficients, patch.degrees, flat, result);
}

std::array<int, 3> cellOf(const FoldCheckResult& result, std::int64_t flat) {
  const int cu = result.cellCounts[0], cv = result.cellCounts[1];
  return {int(flat % cu), int(flat / cu % cv), int(flat / cu / cv)};
}

// Fewer cells than this (a lattice of one to three cells, e.g. 4x4x4 cubic) run one cell at a
// time: a batch of them would compute mostly unused lanes.
constexpr std::int64_t kFewestForLanes = detail::kFoldLanes / 2;

// The cells `flats` kFoldLanes at a time through `Lanes` (detail::DeterminantLanes for det J,
// detail::RationalLanes for the rational G): a cell whose signed coefficients are all positive is
// Positive at once, the others are classified from their coefficients (subdivision, corners).
// lowerBound(lanes, lane, lowest) turns the lowest signed coefficient into the cell's lowerBound.
template <class Lanes, class LowerBound>
void checkCellsInLanes(const Lattice& lattice, const FoldCheckOptions& options,
                       const std::vector<Eigen::MatrixXd>* extraction, const std::vector<std::int64_t>& flats,
                       FoldCheckResult& result, LowerBound lowerBound) {
  constexpr int L = detail::kFoldLanes;
  const std::int64_t count = std::int64_t(flats.size());
  const std::int64_t batches = (count + L - 1) / L;
#pragma omp parallel if (batches >= 2)
  {
    Lanes lanes(lattice, extraction);
    const int d = lanes.degree();
    std::vector<double> signedCoefficients;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t batch = 0; batch < batches; ++batch) {
      std::array<int, 3> cells[L];
      const int n = int(std::min<std::int64_t>(L, count - batch * L));
      for (int l = 0; l < n; ++l) cells[l] = cellOf(result, flats[std::size_t(batch * L + l)]);
      lanes.compute(cells, n);
      for (int l = 0; l < n; ++l) {
        const std::size_t flat = std::size_t(flats[std::size_t(batch * L + l)]);
        const double lowest = result.orientation > 0 ? lanes.lowest(l) : -lanes.highest(l);
        result.lowerBound[flat] = lowerBound(lanes, l, lowest);
        if (lowest > 0.0) {
          result.cells[flat] = CellFolding::Positive;
          continue;
        }
        lanes.coefficients(l, result.orientation, signedCoefficients);
        classifyCell(lattice, options, cells[l], signedCoefficients, {d, d, d}, flat, result);
      }
    }
  }
}

// The cells `flats` of a polynomial map (or of a rational one's windows with equal weights). Axes
// of one degree 1..3 (not options.referenceExpansion, at least kFewestForLanes cells): kFoldLanes
// cells at a time (detail::DeterminantLanes; a cell's coefficients do not depend on the cells
// beside it in its batch, so the verdicts are the same whatever the thread count); otherwise one
// cell at a time.
void checkPolynomialCells(const Lattice& lattice, const FoldCheckOptions& options,
                          const std::vector<Eigen::MatrixXd>* extraction, const std::vector<std::int64_t>& flats,
                          FoldCheckResult& result) {
  const std::int64_t count = std::int64_t(flats.size());
  if (options.referenceExpansion || !detail::foldLanesSupport(lattice) || count < kFewestForLanes) {
#pragma omp parallel for schedule(dynamic, 1) if (count >= 8)
    for (std::int64_t c = 0; c < count; ++c)
      checkPolynomialCell(lattice, options, extraction, cellOf(result, flats[std::size_t(c)]),
                          std::size_t(flats[std::size_t(c)]), result);
    return;
  }
  checkCellsInLanes<detail::DeterminantLanes>(
      lattice, options, extraction, flats, result,
      [](const detail::DeterminantLanes&, int, double lowest) { return lowest; });
}

// ---- rational lattices ---------------------------------------------------------------------------
// With H = (N, D) = (sum B w P, sum B w) the homogeneous map (Lamousin & Waggenspack 1994) and
// X = N / D, H_a = D_a (X, 1) + D (X_a, 0); subtracting D_a / D times the column H from each
// derivative column leaves det[H_u, H_v, H_w, H] = det[D (X_u, 0), D (X_v, 0), D (X_w, 0), D (X, 1)]
// = D^4 det J. All weights are > 0 and the basis is a partition of unity, so D lies between the
// smallest and the largest weight of the cell's window: det J has the sign of the polynomial
// G = det[H_u, H_v, H_w, H], of degree (4p-1, 4q-1, 4r-1), bounded by its Bernstein coefficients
// as det J is on the polynomial path (docs/ffd-engine.md, "Fold-over bound").

// A trivariate polynomial in scaled Bernstein form (coefficient times C(d0,i) C(d1,j) C(d2,k)),
// where a product is a convolution of the coefficient arrays.
struct ScaledPolynomial {
  Dims d{{1, 1, 1}};
  std::vector<double> c;
};

ScaledPolynomial product(const ScaledPolynomial& a, const ScaledPolynomial& b) {
  ScaledPolynomial out;
  for (int axis = 0; axis < 3; ++axis) out.d.n[axis] = a.d.n[axis] + b.d.n[axis] - 1;
  out.c.assign(std::size_t(out.d.size()), 0.0);
  const int an0 = a.d.n[0], bn0 = b.d.n[0];
  for (int ka = 0; ka < a.d.n[2]; ++ka)
    for (int ja = 0; ja < a.d.n[1]; ++ja)
      for (int kb = 0; kb < b.d.n[2]; ++kb)
        for (int jb = 0; jb < b.d.n[1]; ++jb) {
          double* __restrict o = out.c.data() + out.d.at(0, ja + jb, ka + kb);
          const double* __restrict x = a.c.data() + a.d.at(0, ja, ka);
          const double* __restrict y = b.c.data() + b.d.at(0, jb, kb);
          for (int ia = 0; ia < an0; ++ia)
            for (int ib = 0; ib < bn0; ++ib) o[ia + ib] += x[ia] * y[ib];
        }
  return out;
}

// acc += sign * x (the same degrees; acc empty: acc = sign * x).
void accumulate(ScaledPolynomial& acc, const ScaledPolynomial& x, double sign) {
  if (acc.c.empty()) {
    acc.d = x.d;
    acc.c.assign(x.c.size(), 0.0);
  }
  for (std::size_t i = 0; i < x.c.size(); ++i) acc.c[i] += sign * x.c[i];
}

// det[H_u, H_v, H_w, H] from the scaled nets of its columns (H_u, H_v, H_w, H; per component),
// any degrees: the Laplace expansion along H_u, G = sum_i (-1)^i (H_u)_i M_i, M_i the 3 x 3
// minor of [H_v, H_w, H] without row i, itself expanded along H_v over the 2 x 2 minors of [H_w, H].
void expandDeterminant(const ScaledPolynomial (&column)[4][4], ScaledPolynomial& G) {
  ScaledPolynomial minor2[4][4];
  for (int r = 0; r < 4; ++r)
    for (int s = r + 1; s < 4; ++s) {
      accumulate(minor2[r][s], product(column[2][r], column[3][s]), 1.0);
      accumulate(minor2[r][s], product(column[2][s], column[3][r]), -1.0);
    }
  for (int i = 0; i < 4; ++i) {
    int rows[3], n = 0;
    for (int r = 0; r < 4; ++r)
      if (r != i) rows[n++] = r;
    ScaledPolynomial minor3;
    accumulate(minor3, product(column[1][rows[0]], minor2[rows[1]][rows[2]]), 1.0);
    accumulate(minor3, product(column[1][rows[1]], minor2[rows[0]][rows[2]]), -1.0);
    accumulate(minor3, product(column[1][rows[2]], minor2[rows[0]][rows[1]]), 1.0);
    accumulate(G, product(column[0][i], minor3), i % 2 == 0 ? 1.0 : -1.0);
  }
}

// expandDeterminant when all three axes have degree P (1..3) (detail::rationalDeterminant, every
// size a compile-time constant).
template <int P>
FFDKIT_VECTOR_CLONES void rationalEqualDegree(const double* const (&columns)[4][4], double* out) {
  double minor2[6 * detail::rationalMinor2Size(P)], minor3[4 * detail::rationalMinor3Size(P)];
  detail::rationalDeterminant<double, P>(columns, minor2, minor3, out);
}

// G = det[H_u, H_v, H_w, H] on one cell in Bernstein form, and the range of the window's weights.
struct RationalPatch {
  Dims d{{1, 1, 1}};
  std::vector<double> coefficients;  // index i + n0 (j + n1 k)
  double minWeight = 1.0, maxWeight = 1.0;
  Eigen::Vector3d parameterMin, parameterMax;
};

// general: by expandDeterminant whatever the degrees (FoldCheckOptions::referenceExpansion).
RationalPatch rationalPatchOf(const Lattice& lattice, const std::array<int, 3>& cell,
                              const std::vector<Eigen::MatrixXd>* extraction, bool general) {
  int p[3];
  double width[3];
  RationalPatch patch;
  for (int a = 0; a < 3; ++a) {
    p[a] = lattice.axis(a).degree();
    patch.parameterMin[a] = lattice.axis(a).cellMin(cell[a]);
    patch.parameterMax[a] = lattice.axis(a).cellMax(cell[a]);
    width[a] = patch.parameterMax[a] - patch.parameterMin[a];
  }
  // The cell's Bezier net of H (the extraction is linear, so it maps (w P, w) like P).
  const Dims net{{p[0] + 1, p[1] + 1, p[2] + 1}};
  std::vector<Eigen::Vector4d> b(std::size_t(net.size())), t(b.size());
  patch.minWeight = std::numeric_limits<double>::infinity();
  patch.maxWeight = 0.0;
  for (int k = 0; k <= p[2]; ++k)
    for (int j = 0; j <= p[1]; ++j)
      for (int i = 0; i <= p[0]; ++i) {
        const Eigen::Index f = lattice.index(lattice.axis(0).controlIndex(cell[0], i),
                                             lattice.axis(1).controlIndex(cell[1], j),
                                             lattice.axis(2).controlIndex(cell[2], k));
        const double w = lattice.weight(f);
        patch.minWeight = std::min(patch.minWeight, w);
        patch.maxWeight = std::max(patch.maxWeight, w);
        b[std::size_t(net.at(i, j, k))] << w * lattice.controlPoints().row(f).transpose(), w;
      }
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::MatrixXd& E = extraction[axis][std::size_t(cell[axis])];
    for (int k = 0; k <= p[2]; ++k)
      for (int j = 0; j <= p[1]; ++j)
        for (int i = 0; i <= p[0]; ++i) {
          int at[3] = {i, j, k};
          const int out = at[axis];
          Eigen::Vector4d sum = Eigen::Vector4d::Zero();
          for (int r = 0; r <= p[axis]; ++r) {
            at[axis] = r;
            sum += E(r, out) * b[std::size_t(net.at(at[0], at[1], at[2]))];
          }
          t[std::size_t(net.at(i, j, k))] = sum;
        }
    std::swap(b, t);
  }
  // Columns of the 4 x 4 matrix, per component, in scaled Bernstein form: H_u, H_v, H_w, H.
  ScaledPolynomial column[4][4];
  for (int a = 0; a < 4; ++a) {
    Dims d = net;
    if (a < 3) d.n[a] -= 1;
    for (int component = 0; component < 4; ++component) {
      column[a][component].d = d;
      column[a][component].c.resize(std::size_t(d.size()));
    }
    for (int k = 0; k < d.n[2]; ++k)
      for (int j = 0; j < d.n[1]; ++j)
        for (int i = 0; i < d.n[0]; ++i) {
          const double scale = binomial(d.n[0] - 1, i) * binomial(d.n[1] - 1, j) * binomial(d.n[2] - 1, k);
          Eigen::Vector4d value = b[std::size_t(net.at(i, j, k))];
          if (a < 3) {
            int next[3] = {i, j, k};
            next[a] += 1;
            value = p[a] / width[a] * (b[std::size_t(net.at(next[0], next[1], next[2]))] - value);
          }
          for (int component = 0; component < 4; ++component)
            column[a][component].c[std::size_t(d.at(i, j, k))] = scale * value[component];
        }
  }
  // det[H_u, H_v, H_w, H] by products of the nets.
  ScaledPolynomial G;
  if (!general && p[0] == p[1] && p[1] == p[2] && p[0] >= 1 && p[0] <= 3) {
    const double* columns[4][4];
    for (int a = 0; a < 4; ++a)
      for (int component = 0; component < 4; ++component) columns[a][component] = column[a][component].c.data();
    const int q = 4 * p[0];
    G.d = Dims{{q, q, q}};
    G.c.resize(std::size_t(q * q * q));
    if (p[0] == 1) rationalEqualDegree<1>(columns, G.c.data());
    if (p[0] == 2) rationalEqualDegree<2>(columns, G.c.data());
    if (p[0] == 3) rationalEqualDegree<3>(columns, G.c.data());
  } else {
    expandDeterminant(column, G);
  }
  patch.d = G.d;
  patch.coefficients = std::move(G.c);
  // Back from the scaled form: divide by C(d0, i) C(d1, j) C(d2, k) (reciprocals per axis).
  double inverse[3][44];
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < patch.d.n[a]; ++i) inverse[a][i] = 1.0 / binomial(patch.d.n[a] - 1, i);
  for (int k = 0; k < patch.d.n[2]; ++k)
    for (int j = 0; j < patch.d.n[1]; ++j) {
      const double jk = inverse[1][j] * inverse[2][k];
      double* row = patch.coefficients.data() + patch.d.at(0, j, k);
      for (int i = 0; i < patch.d.n[0]; ++i) row[i] *= inverse[0][i] * jk;
    }
  return patch;
}

// Per cell: G's coefficients certify Positive at once or, subdivided like det J's on the
// polynomial path, find a corner where G (hence det J) is <= 0 or leave the cell Unknown.
// lowerBound: min G / maxWeight^4 when min G > 0, else min G / minWeight^4 (a lower bound of
// sign * det J = sign * G / D^4 either way, D being in [minWeight, maxWeight]).
// The cells `flats` of a rational lattice (unequal window weights) kFoldLanes at a time
// (detail::RationalLanes), as checkRationalFolding's one-cell path does them.
void checkRationalLanes(const Lattice& lattice, const FoldCheckOptions& options,
                        const std::vector<Eigen::MatrixXd>* extraction, const std::vector<std::int64_t>& flats,
                        FoldCheckResult& result) {
  checkCellsInLanes<detail::RationalLanes>(
      lattice, options, extraction, flats, result, [](const detail::RationalLanes& lanes, int l, double lowest) {
        return lowest / std::pow(lowest > 0.0 ? lanes.maxWeight(l) : lanes.minWeight(l), 4);
      });
}

void checkRationalFolding(const Lattice& lattice, const FoldCheckOptions& options,
                          const std::vector<Eigen::MatrixXd>* extraction, FoldCheckResult& result) {
  const std::int64_t cellCount = std::int64_t(result.cells.size());
  // Equal weights in a cell's window (every cell away from an edited weight): the map is
  // polynomial there, and det J's own bound (degree 3p-1 instead of 4p-1) is used.
  std::vector<std::int64_t> equal, unequal;
  for (std::int64_t flat = 0; flat < cellCount; ++flat) {
    const std::array<int, 3> cell = cellOf(result, flat);
    double lightest = std::numeric_limits<double>::infinity(), heaviest = 0.0;
    for (int k = 0; k <= lattice.axis(2).degree(); ++k)
      for (int j = 0; j <= lattice.axis(1).degree(); ++j)
        for (int i = 0; i <= lattice.axis(0).degree(); ++i) {
          const double w = lattice.weight(lattice.index(lattice.axis(0).controlIndex(cell[0], i),
                                                        lattice.axis(1).controlIndex(cell[1], j),
                                                        lattice.axis(2).controlIndex(cell[2], k)));
          lightest = std::min(lightest, w);
          heaviest = std::max(heaviest, w);
        }
    (lightest == heaviest ? equal : unequal).push_back(flat);
  }
  checkPolynomialCells(lattice, options, extraction, equal, result);
  const std::int64_t count = std::int64_t(unequal.size());
  if (!options.referenceExpansion && detail::foldLanesSupport(lattice) && count >= kFewestForLanes) {
    checkRationalLanes(lattice, options, extraction, unequal, result);
    return;
  }
#pragma omp parallel for schedule(dynamic, 1) if (count >= 8)
  for (std::int64_t c = 0; c < count; ++c) {
    const std::size_t flat = std::size_t(unequal[std::size_t(c)]);
    const std::array<int, 3> cell = cellOf(result, std::int64_t(flat));
    RationalPatch patch = rationalPatchOf(lattice, cell, extraction, options.referenceExpansion);
    for (double& x : patch.coefficients) x *= result.orientation;
    const double lowest = *std::min_element(patch.coefficients.begin(), patch.coefficients.end());
    result.lowerBound[flat] = lowest / std::pow(lowest > 0.0 ? patch.maxWeight : patch.minWeight, 4);
    if (lowest > 0.0) {
      result.cells[flat] = CellFolding::Positive;
      continue;
    }
    classifyCell(lattice, options, cell, patch.coefficients,
                 {patch.d.n[0] - 1, patch.d.n[1] - 1, patch.d.n[2] - 1}, flat, result);
  }
}

}  // namespace


FoldCheckResult checkFolding(const Lattice& lattice, const FoldCheckOptions& options) {
  if (options.maxDepth < 0 || options.maxDepth > 10)
    throw LatticeError("checkFolding: maxDepth must be in [0, 10], got " + std::to_string(options.maxDepth));
  std::vector<Eigen::MatrixXd> extraction[3];
  FoldCheckResult result;
  for (int a = 0; a < 3; ++a) {
    checkDegree(lattice, a, "checkFolding");
    extraction[a] = bezierExtraction(lattice.axis(a));
    result.cellCounts[std::size_t(a)] = lattice.axis(a).cellCount();
  }
  const Eigen::Vector3d centre = 0.5 * (lattice.parameterMin() + lattice.parameterMax());
  result.orientation = lattice.restJacobian(centre).determinant() < 0.0 ? -1 : 1;
  const std::int64_t cellCount = std::int64_t(result.cellCounts[0]) * result.cellCounts[1] * result.cellCounts[2];
  result.cells.assign(std::size_t(cellCount), CellFolding::Unknown);
  result.lowerBound.assign(std::size_t(cellCount), 0.0);
  result.witness.assign(std::size_t(cellCount), Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  if (lattice.isRational()) {
    checkRationalFolding(lattice, options, extraction, result);
  } else {
    std::vector<std::int64_t> all(static_cast<std::size_t>(cellCount));
    for (std::int64_t flat = 0; flat < cellCount; ++flat) all[std::size_t(flat)] = flat;
    checkPolynomialCells(lattice, options, extraction, all, result);
  }
  for (CellFolding c : result.cells) {
    result.positiveCount += c == CellFolding::Positive;
    result.foldsCount += c == CellFolding::Folds;
    result.unknownCount += c == CellFolding::Unknown;
  }
  return result;
}

}  // namespace ffdkit::ffd
