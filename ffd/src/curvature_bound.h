// Internal to ffd/: a bound on the second derivatives of the rest map, for Newton's early exit.
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "ffdkit/ffd/lattice.h"

#include "cell_polynomials.h"

namespace ffdkit::ffd::detail {

// H(a, b) >= |d^2 Xbar / du_a du_b| (Euclidean norm of the 3-vector) at every parameter point in
// the closure of any cell, for a rest map of degree <= 3 per axis. On a cell, Xbar is a tensor
// polynomial of degree 3 in the local coordinates (x, y, z) in [0, 1]^3; written in the cubic
// Bernstein basis with control points b_ijk, its second derivatives are Bernstein sums of the
// control points' differences with non-negative weights summing to one (Farin, Curves and
// Surfaces for CAGD, sec. 15.3), so |d^2/dx^2| <= 6 max |b_{i+2,j,k} - 2 b_{i+1,j,k} + b_ijk| and
// |d^2/dx dy| <= 9 max |b_{i+1,j+1,k} - b_{i+1,j,k} - b_{i,j+1,k} + b_ijk|; d/du = scale_u d/dx.
// (Bounds from the power coefficients instead were ~1000 x too large: they lose the cancellation.)
// poly: the cell polynomials of the lattice's three axes (each of degree <= 3).
inline Eigen::Matrix3d restCurvatureBound(const Lattice& lattice, const CellPolynomials poly[3]) {
  const AxisSpline* axes[3] = {&lattice.axis(0), &lattice.axis(1), &lattice.axis(2)};
  const int cells[3] = {axes[0]->cellCount(), axes[1]->cellCount(), axes[2]->cellCount()};
  // Power to cubic Bernstein coefficients: x^a = sum_{i >= a} (C(i, a) / C(3, a)) B_i(x).
  static constexpr double kToBernstein[4][4] = {
      {1, 0, 0, 0}, {1, 1.0 / 3, 0, 0}, {1, 2.0 / 3, 1.0 / 3, 0}, {1, 1, 1, 1}};
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (int cw = 0; cw < cells[2]; ++cw)
    for (int cv = 0; cv < cells[1]; ++cv)
      for (int cu = 0; cu < cells[0]; ++cu) {
        const int cell[3] = {cu, cv, cw};
        Lane4 P[64];  // the cell's rest points, zero-padded to 4 x 4 x 4, u fastest
        for (int t = 0; t < 4; ++t)
          for (int s = 0; s < 4; ++s)
            for (int r = 0; r < 4; ++r) {
              Lane4& point = P[r + 4 * (s + 4 * t)];
              point = Lane4{0, 0, 0, 0};
              if (r > axes[0]->degree() || s > axes[1]->degree() || t > axes[2]->degree()) continue;
              const Eigen::Index f = lattice.index(axes[0]->controlIndex(cu, r), axes[1]->controlIndex(cv, s),
                                                   axes[2]->controlIndex(cw, t));
              for (int c = 0; c < 3; ++c) point[c] = lattice.restPoints()(f, c);
            }
        // B[axis][i]: lane r = Bernstein coefficient i of the cell's r-th basis function.
        Lane4 B[3][4];
        for (int axis = 0; axis < 3; ++axis) {
          const Lane4* A = poly[axis].coefficients(cell[axis]);
          for (int i = 0; i < 4; ++i) {
            B[axis][i] = Lane4{0, 0, 0, 0};
            for (int a = 0; a < 4; ++a) B[axis][i] += kToBernstein[i][a] * A[a];
          }
        }
        // b[i][j][k] = sum_rst B_u[i][r] B_v[j][s] B_w[k][t] P_rst, one axis at a time.
        Lane4 T1[4][4][4], T2[4][4][4], b[4][4][4];
        for (int i = 0; i < 4; ++i)
          for (int t = 0; t < 4; ++t)
            for (int s = 0; s < 4; ++s) {
              Lane4 sum = {0, 0, 0, 0};
              for (int r = 0; r < 4; ++r) sum += B[0][i][r] * P[r + 4 * (s + 4 * t)];
              T1[i][t][s] = sum;
            }
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j)
            for (int t = 0; t < 4; ++t) {
              Lane4 sum = {0, 0, 0, 0};
              for (int s = 0; s < 4; ++s) sum += B[1][j][s] * T1[i][t][s];
              T2[i][j][t] = sum;
            }
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) {
              Lane4 sum = {0, 0, 0, 0};
              for (int t = 0; t < 4; ++t) sum += B[2][k][t] * T2[i][j][t];
              b[i][j][k] = sum;
            }
        const auto norm = [](Lane4 v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); };
        const auto at = [&b](int axis, int step, int i, int j, int k) -> const Lane4& {
          int idx[3] = {i, j, k};
          idx[axis] += step;
          return b[idx[0]][idx[1]][idx[2]];
        };
        const double s[3] = {poly[0].scale(cu), poly[1].scale(cv), poly[2].scale(cw)};
        for (int r = 0; r < 3; ++r)
          for (int q = r; q < 3; ++q) {
            double worst = 0.0;
            for (int i = 0; i < 4; ++i)
              for (int j = 0; j < 4; ++j)
                for (int k = 0; k < 4; ++k) {
                  int idx[3] = {i, j, k};
                  if (r == q) {
                    if (idx[r] > 1) continue;
                    worst = std::max(worst, 6.0 * norm(at(r, 2, i, j, k) - 2.0 * at(r, 1, i, j, k) + b[i][j][k]));
                  } else {
                    if (idx[r] > 2 || idx[q] > 2) continue;
                    idx[r] += 1;
                    const Lane4& both = at(q, 1, idx[0], idx[1], idx[2]);
                    worst = std::max(worst, 9.0 * norm(both - at(r, 1, i, j, k) - at(q, 1, i, j, k) + b[i][j][k]));
                  }
                }
            H(r, q) = H(q, r) = std::max(H(r, q), worst * s[r] * s[q]);
          }
      }
  return H;
}

}  // namespace ffdkit::ffd::detail
