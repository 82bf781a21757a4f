// Internal to ffd/: the SIMD block kernels behind Deformer (deformer.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/axis_basis.h"

namespace ffdkit::ffd {
class Lattice;
class Embedding;
}  // namespace ffdkit::ffd

namespace ffdkit::ffd::detail {

/// Lattices whose axes all have degree <= this are evaluated in the power form of each cell
/// (powerBlock, sparseBlock); higher degrees use Cox-de Boor per point (denseBlock), where the
/// power form would be ill-conditioned (Bernstein of degree 10 has coefficients up to C(10,5)).
constexpr int kMaxPowerDegree = 3;

/// The degree the power-form kernels run at for these axis degrees: the largest (lower-degree
/// axes are padded with zero coefficients, which Horner's rule adds exactly), or -1 when one
/// axis is above kMaxPowerDegree.
int powerDegree(const int degrees[3]);

/// Per cell of one axis, the basis functions that are non-zero on it as polynomials in the cell's
/// local parameter x = (t - origin) * scale in [-1/2, 1/2] (origin, scale: the cell's midpoint and
/// the reciprocal of its length):  N_(span-p+r)(t) = sum_k M[r][k] x^k,  r, k in [0, K].
/// Derived from the Cox-de Boor triangle (The NURBS Book A2.2) run on polynomials (in long
/// double), rows and columns above the axis degree are zero. Layout per cell:
/// {origin, scale, M[0][0..K], ..., M[K][0..K]}.
struct AxisPolynomials {
  int degree = -1;  ///< K, the padded degree
  std::vector<double> data;
  int stride() const { return 2 + (degree + 1) * (degree + 1); }
  const double* cell(int c) const { return data.data() + static_cast<std::size_t>(c) * stride(); }
};
AxisPolynomials axisPolynomials(const AxisSpline& axis, int K);

/// The power form of the displacement field on one cell: coefficient sets
/// C[k][(kc (K+1) + kb) (K+1) + ka], k = x, y, z, such that
///   sum_abc N_a(u) N_b(v) N_c(w) W_abc = sum_(ka,kb,kc) C[ka,kb,kc] x^ka y^kb z^kc.
/// W: the cell's window of world displacements, three blocks (x, y, z) of nu * nv * nw values,
/// a fastest (as gathered by deformer.cpp). out: 3 (K+1)^3 values. The contraction runs axis by
/// axis in a fixed order, so the same window always gives the same bits.
void cellCoefficients(const AxisPolynomials axes[3], const int cell[3], const double* W, const int windowCounts[3],
                      double* out);
inline int coefficientSetSize(int K) { return 3 * (K + 1) * (K + 1) * (K + 1); }

/// What a kernel writes for each point: out = Q + s d (Replace), out += s d (Accumulate), or
/// s d itself into a tile's scratch, at row order[q] - outOffset, flagging evaluated[row]
/// (Displacement; mergeTile then adds it to the tile's rows in original order).
enum class Store : std::uint8_t { Replace, Accumulate, Displacement };

/// Everything a block kernel needs, flattened into plain arrays.
struct AxisView {
  const double* knots;     // Cox-de Boor path
  int degree;
  const int* cellSpan;
  const AxisPolynomials* poly;  // power path (null: Cox-de Boor)
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
  double* ox;  // output columns (Displacement: the scratch columns)
  double* oy;
  double* oz;
  std::uint32_t outOffset;   // Displacement: the original row of scratch row 0
  std::uint8_t* evaluated;  // Displacement: per scratch row, 1 once written
};

/// The input every kernel call of a pass shares, made in one place for the polynomial and the
/// rational deformers: each axis' knots and degree, its cell spans (spans[a][cell]) and power-form
/// polynomials (poly[a]; null: Cox-de Boor), the embedding's sorted parameters and point order,
/// and `out`'s columns as the output. The caller adds what its pass needs (input columns, a
/// block's blend weights, a tile's scratch).
KernelInput kernelInput(const Lattice& lattice, const Embedding& embedding, const std::vector<int> (&spans)[3],
                        const AxisPolynomials* const (&poly)[3], Eigen::MatrixX3d& out);

/// Cox-de Boor block (any degree): d = sum_abc Bu_a Bv_b Bw_c W_abc over the cell window W
/// (world displacements, or their change), written as `mode` says.
void denseBlock(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                const double* Wx, const double* Wy, const double* Wz, Store mode);

/// Power-form block (degree K = in.axis[*].poly->degree <= kMaxPowerDegree): the same d by
/// Horner's rule in x, then y, then z from the cell's coefficient sets C (cellCoefficients):
/// 3 (K+1)^3 - 3 multiply-adds per point and no basis values.
void powerBlock(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                const double* C, Store mode);

/// powerBlock in single precision (Precision::Single): C is the cell's coefficient set rounded
/// to float; the local parameters are rounded too, Horner's rule runs on sixteen float lanes, and
/// the displacement is widened to double before it is stored (so out = Q + s d adds in double).
void powerBlockSingle(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                      const float* C, Store mode);

struct SparseTerm {
  int a, b, c;
  double dx, dy, dz;
};

/// Sparse block: s * sum over changed control points of Bu_a Bv_b Bw_c dP (basis values from the
/// power form when in.axis[0].poly is set, else Cox-de Boor), added to out (Accumulate) or
/// written to the scratch (Displacement). With `denominators` (a rational lattice whose changed
/// control points kept their weights, dP = w F.linear dP): the sum is divided by
/// denominators[q], the point's unchanged D = sum B w, so that d is the change of N / D.
void sparseBlock(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                 const SparseTerm* terms, int termCount, Store mode, const double* denominators = nullptr);

/// sparseBlock for one term (one moved control point) that also keeps each point's weight, the
/// product Bu_a Bv_b Bw_c of its three basis functions (without the blend weight), in
/// weights[q] (sorted order): what weightedBlock needs to repeat the step for a new change of the
/// same control point without the basis.
void sparseBlockKeepingWeights(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end,
                               bool blended, const SparseTerm& term, Store mode, double* weights);

/// sparseBlock for one term from the weights sparseBlockKeepingWeights kept for its control point
/// (weights[q], sorted order): d = s (0 + weight dP) per point, the same arithmetic on the same
/// weight, so the same bits, reading 8 bytes per point instead of the three parameters.
void weightedBlock(const KernelInput& in, std::uint32_t begin, std::uint32_t end, bool blended, const double* weights,
                   const SparseTerm& term, Store mode);

/// The coefficient sets of one rational block (rationalPowerBlock): the current homogeneous sums
/// N = sum B w F.linear P (x, y, z) and D = sum B w, then a base's Nb (x, y, z) and Db, then one
/// unused set (cellCoefficients fills sets three at a time).
inline int rationalSetCount() { return 9; }

/// Rational power-form block (Lamousin & Waggenspack 1994, evaluated in homogeneous form: the
/// polynomial kernel on (w P, w), then a division; Piegl & Tiller 1997, sec. 4.2): per point, Horner's
/// rule gives the current (N, D) and the base's (Nb, Db) from the coefficient sets C
/// (rationalSetCount() sets of (K+1)^3), and d = N / D - Nb / Db (d = N / D - Nb when
/// baseRational is false: a polynomial rest map, whose Db is 1), one reciprocal per ratio. The base
/// is the rest map (Store::Replace: out = Q + s d) or the last state of an incremental step
/// (Store::Accumulate: out += s d). D is written to denominators[q] (sorted order) when not null.
void rationalPowerBlock(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                        const double* C, bool baseRational, double* denominators, Store mode);

/// The second half of a tile in random point order: its rows [begin, end) in original order (so
/// that reads and writes stream), out = Q + s (Replace) or out += s (Accumulate) for the rows
/// flagged in `evaluated`, with s = (sx, sy, sz)[p - begin] the displacements the kernels
/// wrote (Store::Displacement). The same arithmetic, so the same bits, as a direct store.
void mergeTile(const KernelInput& in, std::uint32_t begin, std::uint32_t end, const double* sx, const double* sy,
               const double* sz, const std::uint8_t* evaluated, Store mode);

}  // namespace ffdkit::ffd::detail
