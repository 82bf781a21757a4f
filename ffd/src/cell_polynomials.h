// Internal to ffd/: an axis's basis functions, cell by cell, as cubic polynomials (degree <= 3).
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/axis_basis.h"

#include "vector_clones.h"

namespace ffdkit::ffd::detail {

// Four doubles, one per basis function non-zero on a cell (padded with zeros): one AVX register.
// aligned(32) explicitly: without it the baseline (SSE2) compilation caps the type's alignment at
// 16, so std::vector would hand 16-byte aligned storage to the AVX clones' aligned loads.
typedef double Lane4 __attribute__((vector_size(4 * sizeof(double)), aligned(32)));

// On each cell a B-spline (or Bernstein) basis function of degree p <= 3 is one polynomial
// (The NURBS Book, sec. 2.2), so its values and derivatives there are a few multiply-adds in the
// cell's local coordinate x = (t - cellMin) / width, across the p+1 functions at once: Horner
// N(x) = a0 + x (a1 + x (a2 + x a3)). Newton embedding evaluates the basis about ten times per
// point, and the Cox-de Boor recursion (AxisSpline::basis) cost most of its time. The extension
// of a polynomial beyond its cell is what AxisSpline::basis computes there too (extrapolation).
class CellPolynomials {
 public:
  static constexpr int kMaxDegree = 3;
  static bool supports(const AxisSpline& axis) { return axis.degree() <= kMaxDegree; }

  CellPolynomials() = default;
  // The coefficients come from AxisSpline::basis: the values and derivatives at both ends of the
  // cell (cubic Hermite data) fix a cubic exactly, with small integer weights, so the result
  // agrees with Cox-de Boor to a few ulp. On a periodic axis the last cell's right end wraps to 0,
  // so it is taken one ulp inside (a change below rounding).
  explicit CellPolynomials(const AxisSpline& axis) {
    const int p = axis.degree();
    cells_.resize(static_cast<std::size_t>(axis.cellCount()));
    for (int c = 0; c < axis.cellCount(); ++c) {
      Cell& cell = cells_[static_cast<std::size_t>(c)];
      const double width = axis.cellMax(c) - axis.cellMin(c);
      cell.origin = axis.cellMin(c);
      cell.scale = 1.0 / width;
      double end = axis.cellMax(c);
      if (axis.wrap(end) != end) end = std::nextafter(end, cell.origin);
      double n0[kMaxDegree + 1], d0[kMaxDegree + 1], n1[kMaxDegree + 1], d1[kMaxDegree + 1];
      axis.basis(c, cell.origin, n0, d0);
      axis.basis(c, end, n1, d1);
      for (int k = 0; k <= kMaxDegree; ++k) {
        cell.a[k] = Lane4{0, 0, 0, 0};
        cell.d[k] = Lane4{0, 0, 0, 0};
      }
      for (int r = 0; r <= p; ++r) {
        // Hermite on [0, 1] in the power basis; slopes in the local coordinate.
        const double s0 = d0[r] * width, s1 = d1[r] * width;
        const double coef[4] = {n0[r], s0, 3.0 * (n1[r] - n0[r]) - 2.0 * s0 - s1, 2.0 * (n0[r] - n1[r]) + s0 + s1};
        for (int k = 0; k <= p; ++k) cell.a[k][r] = coef[k];  // powers above p are zero (to rounding)
        for (int k = 1; k <= p; ++k) cell.d[k - 1][r] = k * coef[k] * cell.scale;
      }
    }
  }

  // Power coefficients of the cell's functions (lane r for the r-th function, index k for x^k)
  // and the reciprocal of its width.
  const Lane4* coefficients(int cell) const { return cells_[static_cast<std::size_t>(cell)].a; }
  double scale(int cell) const { return cells_[static_cast<std::size_t>(cell)].scale; }
  double origin(int cell) const { return cells_[static_cast<std::size_t>(cell)].origin; }
  // The cell's local coordinate of t: in [0, 1] for t in the cell.
  FFDKIT_INLINE double local(int cell, double t) const {
    const Cell& k = cells_[static_cast<std::size_t>(cell)];
    return (t - k.origin) * k.scale;
  }

  // Values N and derivatives D = dN/dt of the basis functions non-zero on `cell` at t (already
  // wrapped on a periodic axis), lane r for the r-th function (AxisSpline::controlIndex(cell, r)).
  FFDKIT_INLINE void evaluate(int cell, double t, Lane4& N, Lane4& D) const {
    const Cell& k = cells_[static_cast<std::size_t>(cell)];
    const double x = (t - k.origin) * k.scale;
    N = k.a[0] + x * (k.a[1] + x * (k.a[2] + x * k.a[3]));
    D = k.d[0] + x * (k.d[1] + x * k.d[2]);
  }

 private:
  struct Cell {
    Lane4 a[kMaxDegree + 1];  // power coefficients of the values, lane per function
    Lane4 d[kMaxDegree + 1];  // of the derivatives d/dt (d[3] unused)
    double origin = 0.0, scale = 1.0;
  };
  std::vector<Cell> cells_;
};

}  // namespace ffdkit::ffd::detail
