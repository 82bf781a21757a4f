// Internal to ffd/: the window of control points of a lattice cell, and one point's weights on it.
#pragma once

#include <array>

#include "ffdkit/ffd/lattice.h"

namespace ffdkit::ffd::detail {

// The order every walk of a window uses: u fastest, then v, then w, (degree_u+1)(degree_v+1)(degree_w+1)
// positions; position a + np_u (b + np_v c) is the a-th, b-th, c-th basis function non-zero on the cell.

/// The flat control indices (Lattice::index) of `cell`'s window, one per position (a periodic axis
/// with fewer control points than its window repeats an index).
inline void windowControlIndices(const Lattice& lattice, const std::array<int, 3>& cell, Eigen::Index* out) {
  const int n0 = lattice.axis(0).degree() + 1, n1 = lattice.axis(1).degree() + 1, n2 = lattice.axis(2).degree() + 1;
  int at = 0;
  for (int c = 0; c < n2; ++c)
    for (int b = 0; b < n1; ++b)
      for (int a = 0; a < n0; ++a, ++at)
        out[at] = lattice.index(lattice.axis(0).controlIndex(cell[0], a), lattice.axis(1).controlIndex(cell[1], b),
                                lattice.axis(2).controlIndex(cell[2], c));
}

/// A point's weights on `cell`'s window, s B_a(u) B_b(v) B_c(w) per position (Kuriyama 1996,
/// eq. (6.1), times the outside policy's blend weight s). bu, bv, bw: scratch of degree+1 values each.
/// A rational lattice gives s R_abc = s w_abc B_abc / sum w B (Lamousin & Waggenspack 1994): for
/// fixed weights X = sum R P is linear in the control points with these coefficients.
inline void windowWeights(const Lattice& lattice, const std::array<int, 3>& cell, double u, double v, double w,
                          double s, double* bu, double* bv, double* bw, double* out) {
  const int n0 = lattice.axis(0).degree() + 1, n1 = lattice.axis(1).degree() + 1, n2 = lattice.axis(2).degree() + 1;
  lattice.axis(0).basis(cell[0], u, bu);
  lattice.axis(1).basis(cell[1], v, bv);
  lattice.axis(2).basis(cell[2], w, bw);
  if (lattice.isRational()) {
    double sum = 0.0;
    int at = 0;
    for (int c = 0; c < n2; ++c)
      for (int b = 0; b < n1; ++b)
        for (int a = 0; a < n0; ++a, ++at) {
          const Eigen::Index f = lattice.index(lattice.axis(0).controlIndex(cell[0], a), lattice.axis(1).controlIndex(cell[1], b),
                                               lattice.axis(2).controlIndex(cell[2], c));
          out[at] = lattice.weight(f) * bu[a] * bv[b] * bw[c];
          sum += out[at];
        }
    for (int i = 0; i < at; ++i) out[i] = s * (out[i] / sum);
    return;
  }
  int at = 0;
  for (int c = 0; c < n2; ++c)
    for (int b = 0; b < n1; ++b) {
      const double vw = s * bv[b] * bw[c];
      for (int a = 0; a < n0; ++a, ++at) out[at] = bu[a] * vw;
    }
}

}  // namespace ffdkit::ffd::detail
