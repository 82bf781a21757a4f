// Internal to ffd/: the product of trivariate polynomials in scaled Bernstein form, shared by the
// fold-over bound's one-cell path (fold_check.cpp, T = double) and its batched path
// (fold_lanes.cpp, T = one SIMD lane per cell).
#pragma once

#include "vector_clones.h"

namespace ffdkit::ffd::detail {

// out (dims A + B - 1 per axis, index i + O0 (j + O1 k)) += sum_m sign_m a_m (dims A) * b_m
// (dims B): M products of scaled Bernstein forms (coefficient times C(d0,i) C(d1,j) C(d2,k), so
// that a product is a convolution of the coefficient arrays) summed at once (M multiply-adds per
// load and store of out), with compile-time sizes so that the inner loop is unrolled and vectorised.
template <typename T, int M, int A0, int A1, int A2, int B0, int B1, int B2>
FFDKIT_INLINE void convolveSum(const T* const (&a)[M], const T* const (&b)[M], const double (&sign)[M],
                               T* __restrict out) {
  constexpr int O0 = A0 + B0 - 1, O1 = A1 + B1 - 1;
  for (int ka = 0; ka < A2; ++ka)
    for (int ja = 0; ja < A1; ++ja)
      for (int kb = 0; kb < B2; ++kb)
        for (int jb = 0; jb < B1; ++jb) {
          T* __restrict o = out + O0 * ((ja + jb) + O1 * (ka + kb));
          const T* y[M];
          for (int m = 0; m < M; ++m) y[m] = b[m] + B0 * (jb + B1 * kb);
          for (int ia = 0; ia < A0; ++ia) {
            T x[M];
            for (int m = 0; m < M; ++m) x[m] = sign[m] * a[m][ia + A0 * (ja + A1 * ka)];
            for (int ib = 0; ib < B0; ++ib) {
              T sum = o[ia + ib];
              for (int m = 0; m < M; ++m) sum += x[m] * y[m][ib];
              o[ia + ib] = sum;
            }
          }
        }
}

// det[H_u, H_v, H_w, H] when all three axes have degree P (1..3), by the Laplace expansion along
// H_u over the 3 x 3 minors of [H_v, H_w, H], themselves expanded along H_v over the 2 x 2 minors
// of [H_w, H]; every size a compile-time constant. columns[a][component]: the scaled nets of H_u,
// H_v, H_w (P on their own axis, P + 1 on the others) and H ((P+1)^3). minor2 (6 x (2P+1)^2 2P)
// and minor3 (4 x (3P+1) (3P)^2) are scratch; `out` gets G's (4P)^3 scaled coefficients, index
// i + 4P (j + 4P k).
constexpr int rationalMinor2Size(int P) { return (2 * P + 1) * (2 * P + 1) * (2 * P); }
constexpr int rationalMinor3Size(int P) { return (3 * P + 1) * (3 * P) * (3 * P); }

template <typename T, int P>
FFDKIT_INLINE void rationalDeterminant(const T* const (&columns)[4][4], T* minor2, T* minor3, T* out) {
  constexpr int N = P + 1, S2 = rationalMinor2Size(P), S3 = rationalMinor3Size(P);
  // The pairs of rows r < s of [H_w, H], 6 of them.
  const auto pair = [](int r, int s) { return r == 0 ? s - 1 : r == 1 ? s + 1 : 5; };
  for (int i = 0; i < 6 * S2; ++i) minor2[i] = T{};
  for (int i = 0; i < 4 * S3; ++i) minor3[i] = T{};
  for (int i = 0; i < 64 * P * P * P; ++i) out[i] = T{};
  for (int r = 0; r < 4; ++r)
    for (int s = r + 1; s < 4; ++s)
      convolveSum<T, 2, N, N, P, N, N, N>({columns[2][r], columns[2][s]}, {columns[3][s], columns[3][r]}, {1.0, -1.0},
                                          minor2 + S2 * pair(r, s));
  for (int i = 0; i < 4; ++i) {
    int rows[3], n = 0;
    for (int r = 0; r < 4; ++r)
      if (r != i) rows[n++] = r;
    convolveSum<T, 3, N, P, N, 2 * P + 1, 2 * P + 1, 2 * P>(
        {columns[1][rows[0]], columns[1][rows[1]], columns[1][rows[2]]},
        {minor2 + S2 * pair(rows[1], rows[2]), minor2 + S2 * pair(rows[0], rows[2]), minor2 + S2 * pair(rows[0], rows[1])},
        {1.0, -1.0, 1.0}, minor3 + S3 * i);
  }
  convolveSum<T, 4, P, N, N, 3 * P + 1, 3 * P, 3 * P>(
      {columns[0][0], columns[0][1], columns[0][2], columns[0][3]},
      {minor3, minor3 + S3, minor3 + 2 * S3, minor3 + 3 * S3}, {1.0, -1.0, 1.0, -1.0}, out);
}

}  // namespace ffdkit::ffd::detail
