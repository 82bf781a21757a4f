#include "deform_kernels.h"

#include <algorithm>

#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"
#include "vector_clones.h"

namespace ffdkit::ffd::detail {

KernelInput kernelInput(const Lattice& lattice, const Embedding& embedding, const std::vector<int> (&spans)[3],
                        const AxisPolynomials* const (&poly)[3], Eigen::MatrixX3d& out) {
  KernelInput in{};
  for (int a = 0; a < 3; ++a) {
    in.axis[a].knots = lattice.axis(a).knots().data();
    in.axis[a].degree = lattice.axis(a).degree();
    in.axis[a].cellSpan = spans[a].data();
    in.axis[a].poly = poly[a];
  }
  in.u = embedding.sortedU().data();
  in.v = embedding.sortedV().data();
  in.w = embedding.sortedW().data();
  in.order = embedding.order().empty() ? nullptr : embedding.order().data();
  in.ox = out.col(0).data();
  in.oy = out.col(1).data();
  in.oz = out.col(2).data();
  return in;
}

namespace {

constexpr int kLanes = 8;
constexpr int kMaxBasis = 33;

// Eight lanes of doubles: one AVX-512 register, two AVX2 registers, or four SSE2 registers,
// depending on the clone. GCC vector extensions keep the lane structure explicit.
typedef double Lane __attribute__((vector_size(kLanes * sizeof(double))));
typedef std::int64_t LaneMask __attribute__((vector_size(kLanes * sizeof(std::int64_t))));

// A broadcast (Lane{} + x would add +0.0 to x first: not foldable, since -0.0 + 0.0 = +0.0).
FFDKIT_INLINE Lane splat(double x) {
  Lane r;
  for (int l = 0; l < kLanes; ++l) r[l] = x;
  return r;
}

// The degree+1 basis values of eight parameters on one span (Cox-de Boor, The NURBS Book A2.2),
// vectorised across lanes: the knots are the same for every lane of a cell. P >= 0 fixes the
// degree at compile time (full unrolling); P < 0 reads it from the axis.
template <int P>
FFDKIT_INLINE void basisLanes(const AxisView& axis, int cell, Lane t, Lane* N) {
  const int p = P >= 0 ? P : axis.degree;
  const int s = axis.cellSpan[cell];
  const double* U = axis.knots;
  Lane left[kMaxBasis];
  Lane right[kMaxBasis];
  N[0] = splat(1.0);
  for (int j = 1; j <= p; ++j) {
    left[j] = t - U[s + 1 - j];
    right[j] = U[s + j] - t;
    Lane saved = splat(0.0);
    for (int r = 0; r < j; ++r) {
      const Lane temp = N[r] * (1.0 / (U[s + r + 1] - U[s + 1 - j + r]));
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
}

FFDKIT_INLINE Lane loadLanes(const double* src, std::uint32_t q, int count) {
  Lane x;
  if (count == kLanes) {
    __builtin_memcpy(&x, src + q, sizeof(Lane));
  } else {
    for (int l = 0; l < kLanes; ++l) x[l] = src[q + std::min(l, count - 1)];
  }
  return x;
}

// x = (t - origin) * scale, the cell's local parameter (AxisPolynomials).
FFDKIT_INLINE Lane localLanes(const double* src, std::uint32_t q, int count, const double* cellPoly) {
  return (loadLanes(src, q, count) - cellPoly[0]) * cellPoly[1];
}

// sum_k M[k] x^k by Horner's rule (V: eight double lanes, or sixteen float lanes with float M).
template <int K, class V, class S>
FFDKIT_INLINE V horner(const S* M, V x) {
  V r = x * M[K] + M[K - 1];
  for (int k = K - 2; k >= 0; --k) r = r * x + M[k];
  return r;
}

FFDKIT_INLINE void storeLanes(const KernelInput& in, std::uint32_t q0, int count, bool blended, Lane dx, Lane dy, Lane dz,
                              Store mode) {
  if (blended) {
    Lane s = splat(1.0);
    for (int l = 0; l < kLanes; ++l) s[l] = in.blend[q0 + std::min(l, count - 1) - in.blendBegin];
    dx *= s;
    dy *= s;
    dz *= s;
  }
  if (mode == Store::Displacement) {
    // The tile's scratch, original order (a few hundred kB at most: stays in cache).
    for (int l = 0; l < count; ++l) {
      const std::uint32_t p = in.order[q0 + l] - in.outOffset;
      in.ox[p] = dx[l];
      in.oy[p] = dy[l];
      in.oz[p] = dz[l];
      in.evaluated[p] = 1;
    }
    return;
  }
  const bool accumulate = mode == Store::Accumulate;
  if (!in.order && count == kLanes) {
    // Identity order: contiguous vector loads and stores.
    Lane x, y, z;
    if (accumulate) {
      __builtin_memcpy(&x, in.ox + q0, sizeof(Lane));
      __builtin_memcpy(&y, in.oy + q0, sizeof(Lane));
      __builtin_memcpy(&z, in.oz + q0, sizeof(Lane));
    } else {
      __builtin_memcpy(&x, in.qx + q0, sizeof(Lane));
      __builtin_memcpy(&y, in.qy + q0, sizeof(Lane));
      __builtin_memcpy(&z, in.qz + q0, sizeof(Lane));
    }
    x += dx;
    y += dy;
    z += dz;
    __builtin_memcpy(in.ox + q0, &x, sizeof(Lane));
    __builtin_memcpy(in.oy + q0, &y, sizeof(Lane));
    __builtin_memcpy(in.oz + q0, &z, sizeof(Lane));
    return;
  }
  for (int l = 0; l < count; ++l) {
    const std::uint32_t q = q0 + l;
    const std::size_t p = in.order ? in.order[q] : q;
    if (accumulate) {
      in.ox[p] += dx[l];
      in.oy[p] += dy[l];
      in.oz[p] += dz[l];
    } else {
      in.ox[p] = in.qx[p] + dx[l];
      in.oy[p] = in.qy[p] + dy[l];
      in.oz[p] = in.qz[p] + dz[l];
    }
  }
}

template <int P>
FFDKIT_INLINE void denseBlockT(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end,
                               bool blended, const double* Wx, const double* Wy, const double* Wz, Store mode) {
  const int nu = (P >= 0 ? P : in.axis[0].degree) + 1;
  const int nv = (P >= 0 ? P : in.axis[1].degree) + 1;
  const int nw = (P >= 0 ? P : in.axis[2].degree) + 1;
  Lane bu[kMaxBasis], bv[kMaxBasis], bw[kMaxBasis];
  for (std::uint32_t q0 = begin; q0 < end; q0 += kLanes) {
    const int count = static_cast<int>(std::min<std::uint32_t>(kLanes, end - q0));
    basisLanes<P>(in.axis[0], cell[0], loadLanes(in.u, q0, count), bu);
    basisLanes<P>(in.axis[1], cell[1], loadLanes(in.v, q0, count), bv);
    basisLanes<P>(in.axis[2], cell[2], loadLanes(in.w, q0, count), bw);
    Lane dx = splat(0.0), dy = splat(0.0), dz = splat(0.0);
    int wi = 0;
    for (int c = 0; c < nw; ++c) {
      for (int b = 0; b < nv; ++b) {
        Lane sx = splat(0.0), sy = splat(0.0), sz = splat(0.0);
        for (int a = 0; a < nu; ++a, ++wi) {
          sx += bu[a] * Wx[wi];
          sy += bu[a] * Wy[wi];
          sz += bu[a] * Wz[wi];
        }
        const Lane nn = bv[b] * bw[c];
        dx += nn * sx;
        dy += nn * sy;
        dz += nn * sz;
      }
    }
    storeLanes(in, q0, count, blended, dx, dy, dz, mode);
  }
}

// Horner's rule over the tensor-product power form: rows in x, their sums in y, then z
// (3 (K+1)^3 - 3 multiply-adds for the three coordinates; the (K+1)^2 rows of a coordinate
// are independent chains of K multiply-adds, which keeps both FMA pipes busy).
template <int K, class V, class S>
FFDKIT_INLINE V hornerTensor(const S* C, V x, V y, V z) {
  constexpr int n = K + 1;
  V sumW = x;  // overwritten at c == K
  for (int c = K; c >= 0; --c) {
    V sumV = horner<K>(C + (c * n + K) * n, x);
    for (int b = K - 1; b >= 0; --b) sumV = sumV * y + horner<K>(C + (c * n + b) * n, x);
    sumW = c == K ? sumV : sumW * z + sumV;
  }
  return sumW;
}

template <int K>
FFDKIT_INLINE void powerBlockT(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end,
                               bool blended, const double* C, Store mode) {
  constexpr int set = (K + 1) * (K + 1) * (K + 1);
  const double* pu = in.axis[0].poly->cell(cell[0]);
  const double* pv = in.axis[1].poly->cell(cell[1]);
  const double* pw = in.axis[2].poly->cell(cell[2]);
  for (std::uint32_t q0 = begin; q0 < end; q0 += kLanes) {
    const int count = static_cast<int>(std::min<std::uint32_t>(kLanes, end - q0));
    const Lane x = localLanes(in.u, q0, count, pu);
    const Lane y = localLanes(in.v, q0, count, pv);
    const Lane z = localLanes(in.w, q0, count, pw);
    const Lane dx = hornerTensor<K>(C, x, y, z);
    const Lane dy = hornerTensor<K>(C + set, x, y, z);
    const Lane dz = hornerTensor<K>(C + 2 * set, x, y, z);
    storeLanes(in, q0, count, blended, dx, dy, dz, mode);
  }
}

// Sixteen float lanes (one AVX-512 register) for Precision::Single, and the halves that map to
// the eight double lanes of the stores.
constexpr int kSingleLanes = 2 * kLanes;
typedef float SingleLane __attribute__((vector_size(kSingleLanes * sizeof(float))));
typedef float HalfLane __attribute__((vector_size(kLanes * sizeof(float))));

// Sixteen local parameters: x computed in double exactly as the double kernel does, then rounded
// to float (the only rounding of the parameters).
FFDKIT_INLINE SingleLane localSingle(const double* src, std::uint32_t q, int count, const double* cellPoly) {
  const HalfLane lo = __builtin_convertvector(localLanes(src, q, std::min(count, kLanes), cellPoly), HalfLane);
  const HalfLane hi = count > kLanes
                          ? __builtin_convertvector(localLanes(src, q + kLanes, count - kLanes, cellPoly), HalfLane)
                          : lo;
  return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
}

FFDKIT_INLINE Lane lowHalf(SingleLane d) {
  return __builtin_convertvector(__builtin_shufflevector(d, d, 0, 1, 2, 3, 4, 5, 6, 7), Lane);
}
FFDKIT_INLINE Lane highHalf(SingleLane d) {
  return __builtin_convertvector(__builtin_shufflevector(d, d, 8, 9, 10, 11, 12, 13, 14, 15), Lane);
}

// powerBlockT in single precision: the cell's coefficients (C, rounded by the caller) and the
// local parameters rounded to float, Horner's rule on sixteen float lanes (half the multiply-add
// instructions of eight double lanes), the displacement widened to double and stored as the
// double kernel stores it.
template <int K>
FFDKIT_INLINE void powerBlockSingleT(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end,
                                     bool blended, const float* C, Store mode) {
  constexpr int set = (K + 1) * (K + 1) * (K + 1);
  const double* pu = in.axis[0].poly->cell(cell[0]);
  const double* pv = in.axis[1].poly->cell(cell[1]);
  const double* pw = in.axis[2].poly->cell(cell[2]);
  for (std::uint32_t q0 = begin; q0 < end; q0 += kSingleLanes) {
    const int count = static_cast<int>(std::min<std::uint32_t>(kSingleLanes, end - q0));
    const SingleLane x = localSingle(in.u, q0, count, pu);
    const SingleLane y = localSingle(in.v, q0, count, pv);
    const SingleLane z = localSingle(in.w, q0, count, pw);
    // Hidden from the optimiser per step: else GCC hoists the 3 (K+1)^3 broadcasts out of the
    // loop and spills them, and each multiply-add waits on a 64-byte reload instead of taking its
    // coefficient as a 4-byte broadcast operand.
    const float* c = C;
    asm("" : "+r"(c));
    const SingleLane dx = hornerTensor<K>(c, x, y, z);
    const SingleLane dy = hornerTensor<K>(c + set, x, y, z);
    const SingleLane dz = hornerTensor<K>(c + 2 * set, x, y, z);
    storeLanes(in, q0, std::min(count, kLanes), blended, lowHalf(dx), lowHalf(dy), lowHalf(dz), mode);
    if (count > kLanes)
      storeLanes(in, q0 + kLanes, count - kLanes, blended, highHalf(dx), highHalf(dy), highHalf(dz), mode);
  }
}

// (dx, dy, dz) / D for the lanes' stored denominators D = sum B w (a rational lattice's numerator
// change over its unchanged denominator): one reciprocal, three products.
FFDKIT_INLINE void divideLanes(const double* denominators, std::uint32_t q0, int count, Lane& dx, Lane& dy, Lane& dz) {
  const Lane inv = 1.0 / loadLanes(denominators, q0, count);
  dx *= inv;
  dy *= inv;
  dz *= inv;
}

// The homogeneous form of a rational lattice: the tensor-product Horner of powerBlockT on the four
// components (N, D) of the current lattice and on those of the base, then N / D - Nb / Db.
template <int K, bool BaseRational>
FFDKIT_INLINE void rationalPowerBlockT(const KernelInput& in, const int cell[3], std::uint32_t begin,
                                       std::uint32_t end, bool blended, const double* C, double* denominators,
                                       Store mode) {
  constexpr int set = (K + 1) * (K + 1) * (K + 1);
  const double* pu = in.axis[0].poly->cell(cell[0]);
  const double* pv = in.axis[1].poly->cell(cell[1]);
  const double* pw = in.axis[2].poly->cell(cell[2]);
  for (std::uint32_t q0 = begin; q0 < end; q0 += kLanes) {
    const int count = static_cast<int>(std::min<std::uint32_t>(kLanes, end - q0));
    const Lane x = localLanes(in.u, q0, count, pu);
    const Lane y = localLanes(in.v, q0, count, pv);
    const Lane z = localLanes(in.w, q0, count, pw);
    const Lane D = hornerTensor<K>(C + 3 * set, x, y, z);
    const Lane inv = 1.0 / D;
    Lane dx = hornerTensor<K>(C, x, y, z) * inv;
    Lane dy = hornerTensor<K>(C + set, x, y, z) * inv;
    Lane dz = hornerTensor<K>(C + 2 * set, x, y, z) * inv;
    if constexpr (BaseRational) {
      const Lane invBase = 1.0 / hornerTensor<K>(C + 7 * set, x, y, z);
      dx -= hornerTensor<K>(C + 4 * set, x, y, z) * invBase;
      dy -= hornerTensor<K>(C + 5 * set, x, y, z) * invBase;
      dz -= hornerTensor<K>(C + 6 * set, x, y, z) * invBase;
    } else {
      dx -= hornerTensor<K>(C + 4 * set, x, y, z);
      dy -= hornerTensor<K>(C + 5 * set, x, y, z);
      dz -= hornerTensor<K>(C + 6 * set, x, y, z);
    }
    if (denominators) {
      if (count == kLanes) {
        __builtin_memcpy(denominators + q0, &D, sizeof(Lane));
      } else {
        for (int l = 0; l < count; ++l) denominators[q0 + l] = D[l];
      }
    }
    storeLanes(in, q0, count, blended, dx, dy, dz, mode);
  }
}

// The first `count` lanes of a block's weights into keep[q0 ..].
FFDKIT_INLINE void storeWeights(double* keep, std::uint32_t q0, int count, Lane weight) {
  if (count == kLanes) {
    __builtin_memcpy(keep + q0, &weight, sizeof(Lane));
  } else {
    for (int l = 0; l < count; ++l) keep[q0 + l] = weight[l];
  }
}

// Keep: termCount is 1 and the lanes' weight is written to keep[q] (sparseBlockKeepingWeights).
template <int K, bool Keep = false>
FFDKIT_INLINE void sparsePowerT(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end,
                                bool blended, const SparseTerm* terms, int termCount, Store mode,
                                const double* denominators, double* keep = nullptr) {
  constexpr int n = K + 1;
  const double* pu = in.axis[0].poly->cell(cell[0]);
  const double* pv = in.axis[1].poly->cell(cell[1]);
  const double* pw = in.axis[2].poly->cell(cell[2]);
  for (std::uint32_t q0 = begin; q0 < end; q0 += kLanes) {
    const int count = static_cast<int>(std::min<std::uint32_t>(kLanes, end - q0));
    const Lane x = localLanes(in.u, q0, count, pu);
    const Lane y = localLanes(in.v, q0, count, pv);
    const Lane z = localLanes(in.w, q0, count, pw);
    Lane dx = splat(0.0), dy = splat(0.0), dz = splat(0.0);
    for (int i = 0; i < termCount; ++i) {
      const SparseTerm& term = terms[i];
      // Only the basis functions a term needs: one polynomial per axis.
      const Lane weight = horner<K>(pu + 2 + term.a * n, x) * horner<K>(pv + 2 + term.b * n, y) *
                          horner<K>(pw + 2 + term.c * n, z);
      if constexpr (Keep) storeWeights(keep, q0, count, weight);
      dx += weight * term.dx;
      dy += weight * term.dy;
      dz += weight * term.dz;
    }
    if (denominators) divideLanes(denominators, q0, count, dx, dy, dz);
    storeLanes(in, q0, count, blended, dx, dy, dz, mode);
  }
}

template <bool Keep = false>
FFDKIT_INLINE void sparseCoxDeBoor(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end,
                                   bool blended, const SparseTerm* terms, int termCount, Store mode,
                                   const double* denominators, double* keep = nullptr) {
  Lane bu[kMaxBasis], bv[kMaxBasis], bw[kMaxBasis];
  for (std::uint32_t q0 = begin; q0 < end; q0 += kLanes) {
    const int count = static_cast<int>(std::min<std::uint32_t>(kLanes, end - q0));
    basisLanes<-1>(in.axis[0], cell[0], loadLanes(in.u, q0, count), bu);
    basisLanes<-1>(in.axis[1], cell[1], loadLanes(in.v, q0, count), bv);
    basisLanes<-1>(in.axis[2], cell[2], loadLanes(in.w, q0, count), bw);
    Lane dx = splat(0.0), dy = splat(0.0), dz = splat(0.0);
    for (int i = 0; i < termCount; ++i) {
      const SparseTerm& term = terms[i];
      const Lane weight = bu[term.a] * bv[term.b] * bw[term.c];
      if constexpr (Keep) storeWeights(keep, q0, count, weight);
      dx += weight * term.dx;
      dy += weight * term.dy;
      dz += weight * term.dz;
    }
    if (denominators) divideLanes(denominators, q0, count, dx, dy, dz);
    storeLanes(in, q0, count, blended, dx, dy, dz, mode);
  }
}

// (a0 + a1 x) * P(x) for a polynomial P of degree < degree (coefficients k = 0..degree).
void mulLinear(long double a0, long double a1, const long double* P, int degree, long double* out) {
  for (int k = degree; k >= 0; --k) out[k] = a0 * P[k] + (k > 0 ? a1 * P[k - 1] : 0.0L);
}

}  // namespace

FFDKIT_VECTOR_CLONES
void mergeTile(const KernelInput& in, std::uint32_t begin, std::uint32_t end, const double* sx, const double* sy,
               const double* sz, const std::uint8_t* evaluated, Store mode) {
  const bool accumulate = mode == Store::Accumulate;
  const double* bx = accumulate ? in.ox : in.qx;
  const double* by = accumulate ? in.oy : in.qy;
  const double* bz = accumulate ? in.oz : in.qz;
  constexpr std::uint64_t kAll = 0x0101010101010101ull;
  std::uint32_t p = begin;
  // The rows' six streams (base and output columns) restart at every tile, 32 kB each, too short
  // for the hardware prefetcher to run far ahead: ask for their lines eight lines ahead, when the
  // kernels wrote a row there (2-7 % off an exact update of 1M points in random order on 8x8x8 on
  // one thread; in a mesh's spatial order whole runs of rows are skipped, and asking for them
  // regardless cost 10 %).
  constexpr std::uint32_t kAhead = 8 * kLanes;
  for (; p + kLanes <= end; p += kLanes) {
    std::uint64_t ahead = 0;
    if (p + kAhead + kLanes <= end) __builtin_memcpy(&ahead, evaluated + (p + kAhead - begin), sizeof(ahead));
    if (ahead != 0) {
      __builtin_prefetch(bx + p + kAhead);
      __builtin_prefetch(by + p + kAhead);
      __builtin_prefetch(bz + p + kAhead);
      if (!accumulate) {  // else the base is the output
        __builtin_prefetch(in.ox + p + kAhead, 1);
        __builtin_prefetch(in.oy + p + kAhead, 1);
        __builtin_prefetch(in.oz + p + kAhead, 1);
      }
    }
    std::uint64_t flags;
    __builtin_memcpy(&flags, evaluated + (p - begin), sizeof(flags));
    if (flags == 0) continue;
    if (flags == kAll) {
      Lane x, y, z, dx, dy, dz;
      __builtin_memcpy(&x, bx + p, sizeof(Lane));
      __builtin_memcpy(&y, by + p, sizeof(Lane));
      __builtin_memcpy(&z, bz + p, sizeof(Lane));
      __builtin_memcpy(&dx, sx + (p - begin), sizeof(Lane));
      __builtin_memcpy(&dy, sy + (p - begin), sizeof(Lane));
      __builtin_memcpy(&dz, sz + (p - begin), sizeof(Lane));
      x += dx;
      y += dy;
      z += dz;
      __builtin_memcpy(in.ox + p, &x, sizeof(Lane));
      __builtin_memcpy(in.oy + p, &y, sizeof(Lane));
      __builtin_memcpy(in.oz + p, &z, sizeof(Lane));
      continue;
    }
    // Mixed: a branch-free select (a branch per row mispredicts half the time).
    LaneMask m;
    for (int l = 0; l < kLanes; ++l) m[l] = -static_cast<std::int64_t>(evaluated[p - begin + l]);
    Lane x, y, z, ox, oy, oz, dx, dy, dz;
    __builtin_memcpy(&x, bx + p, sizeof(Lane));
    __builtin_memcpy(&y, by + p, sizeof(Lane));
    __builtin_memcpy(&z, bz + p, sizeof(Lane));
    __builtin_memcpy(&ox, in.ox + p, sizeof(Lane));
    __builtin_memcpy(&oy, in.oy + p, sizeof(Lane));
    __builtin_memcpy(&oz, in.oz + p, sizeof(Lane));
    __builtin_memcpy(&dx, sx + (p - begin), sizeof(Lane));
    __builtin_memcpy(&dy, sy + (p - begin), sizeof(Lane));
    __builtin_memcpy(&dz, sz + (p - begin), sizeof(Lane));
    ox = m ? x + dx : ox;
    oy = m ? y + dy : oy;
    oz = m ? z + dz : oz;
    __builtin_memcpy(in.ox + p, &ox, sizeof(Lane));
    __builtin_memcpy(in.oy + p, &oy, sizeof(Lane));
    __builtin_memcpy(in.oz + p, &oz, sizeof(Lane));
  }
  for (; p < end; ++p) {
    if (!evaluated[p - begin]) continue;
    in.ox[p] = bx[p] + sx[p - begin];
    in.oy[p] = by[p] + sy[p - begin];
    in.oz[p] = bz[p] + sz[p - begin];
  }
}

int powerDegree(const int degrees[3]) {
  const int K = std::max({degrees[0], degrees[1], degrees[2]});
  return K <= kMaxPowerDegree ? K : -1;
}

AxisPolynomials axisPolynomials(const AxisSpline& axis, int K) {
  AxisPolynomials out;
  out.degree = K;
  const int n = K + 1;
  const int p = axis.degree();
  out.data.assign(static_cast<std::size_t>(axis.cellCount()) * out.stride(), 0.0);
  const double* U = axis.knots().data();
  for (int cell = 0; cell < axis.cellCount(); ++cell) {
    const int s = axis.cellSpan(cell);
    double* dst = out.data.data() + static_cast<std::size_t>(cell) * out.stride();
    // Centred: x in [-1/2, 1/2] keeps the power form about ten times more accurate than x in
    // [0, 1] for cubics (its coefficients' terms stay small against the value).
    dst[0] = 0.5 * (U[s] + U[s + 1]);
    dst[1] = 1.0 / (U[s + 1] - U[s]);
    const long double ts = dst[0];
    const long double h = static_cast<long double>(U[s + 1]) - U[s];
    // The Cox-de Boor triangle of basisLanes with t = ts + h x: left_j = t - U[s+1-j] and
    // right_j = U[s+j] - t are linear in x, every N a polynomial in x.
    long double N[kMaxPowerDegree + 1][kMaxPowerDegree + 1] = {};
    N[0][0] = 1.0L;
    for (int j = 1; j <= p; ++j) {
      long double saved[kMaxPowerDegree + 1] = {};
      for (int r = 0; r < j; ++r) {
        const long double inv = 1.0L / (static_cast<long double>(U[s + r + 1]) - U[s + 1 - j + r]);
        long double temp[kMaxPowerDegree + 1] = {};
        for (int k = 0; k < j; ++k) temp[k] = N[r][k] * inv;
        long double rightTerm[kMaxPowerDegree + 1];
        mulLinear(U[s + r + 1] - ts, -h, temp, j, rightTerm);  // right_(r+1) * temp
        for (int k = 0; k <= j; ++k) N[r][k] = saved[k] + rightTerm[k];
        mulLinear(ts - U[s + 1 - (j - r)], h, temp, j, saved);  // left_(j-r) * temp
      }
      for (int k = 0; k <= j; ++k) N[j][k] = saved[k];
    }
    for (int r = 0; r <= p; ++r)
      for (int k = 0; k <= p; ++k) dst[2 + r * n + k] = static_cast<double>(N[r][k]);
  }
  return out;
}

namespace {

// cellCoefficients for a fixed padded degree: the loops over the power index are a compile-time
// (K+1) wide, so each step is a few vector multiply-adds.
template <int K>
void cellCoefficientsT(const double* Mu, const double* Mv, const double* Mw, const double* W, int nu, int nv, int nw,
                       double* out) {
  constexpr int n = K + 1;
  const int windowSize = nu * nv * nw;
  for (int coord = 0; coord < 3; ++coord) {
    const double* Wk = W + coord * windowSize;
    double A[n][n][n] = {};  // [c][b][ka]: contracted along u
    for (int c = 0; c < nw; ++c)
      for (int b = 0; b < nv; ++b)
        for (int a = 0; a < nu; ++a) {
          const double x = Wk[(c * nv + b) * nu + a];
          for (int ka = 0; ka < n; ++ka) A[c][b][ka] += Mu[a * n + ka] * x;
        }
    double B[n][n][n] = {};  // [c][kb][ka]: then along v
    for (int c = 0; c < nw; ++c)
      for (int b = 0; b < nv; ++b)
        for (int kb = 0; kb < n; ++kb)
          for (int ka = 0; ka < n; ++ka) B[c][kb][ka] += Mv[b * n + kb] * A[c][b][ka];
    double C[n][n][n] = {};  // [kc][kb][ka]: then along w
    for (int c = 0; c < nw; ++c)
      for (int kc = 0; kc < n; ++kc)
        for (int kb = 0; kb < n; ++kb)
          for (int ka = 0; ka < n; ++ka) C[kc][kb][ka] += Mw[c * n + kc] * B[c][kb][ka];
    std::copy(&C[0][0][0], &C[0][0][0] + n * n * n, out + coord * n * n * n);
  }
}

}  // namespace

void cellCoefficients(const AxisPolynomials axes[3], const int cell[3], const double* W, const int windowCounts[3],
                      double* out) {
  const double* Mu = axes[0].cell(cell[0]) + 2;
  const double* Mv = axes[1].cell(cell[1]) + 2;
  const double* Mw = axes[2].cell(cell[2]) + 2;
  const int nu = windowCounts[0], nv = windowCounts[1], nw = windowCounts[2];
  switch (axes[0].degree) {
    case 1: return cellCoefficientsT<1>(Mu, Mv, Mw, W, nu, nv, nw, out);
    case 2: return cellCoefficientsT<2>(Mu, Mv, Mw, W, nu, nv, nw, out);
    default: return cellCoefficientsT<3>(Mu, Mv, Mw, W, nu, nv, nw, out);
  }
}

FFDKIT_VECTOR_CLONES
void denseBlock(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                const double* Wx, const double* Wy, const double* Wz, Store mode) {
  const int p = in.axis[0].degree;
  if (p == in.axis[1].degree && p == in.axis[2].degree) {
    switch (p) {
      case 1: return denseBlockT<1>(in, cell, begin, end, blended, Wx, Wy, Wz, mode);
      case 2: return denseBlockT<2>(in, cell, begin, end, blended, Wx, Wy, Wz, mode);
      case 3: return denseBlockT<3>(in, cell, begin, end, blended, Wx, Wy, Wz, mode);
      default: break;
    }
  }
  denseBlockT<-1>(in, cell, begin, end, blended, Wx, Wy, Wz, mode);
}

FFDKIT_VECTOR_CLONES
void powerBlock(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                const double* C, Store mode) {
  switch (in.axis[0].poly->degree) {
    case 1: return powerBlockT<1>(in, cell, begin, end, blended, C, mode);
    case 2: return powerBlockT<2>(in, cell, begin, end, blended, C, mode);
    default: return powerBlockT<3>(in, cell, begin, end, blended, C, mode);
  }
}

FFDKIT_VECTOR_CLONES
void powerBlockSingle(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                      const float* C, Store mode) {
  switch (in.axis[0].poly->degree) {
    case 1: return powerBlockSingleT<1>(in, cell, begin, end, blended, C, mode);
    case 2: return powerBlockSingleT<2>(in, cell, begin, end, blended, C, mode);
    default: return powerBlockSingleT<3>(in, cell, begin, end, blended, C, mode);
  }
}

FFDKIT_VECTOR_CLONES
void sparseBlock(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                 const SparseTerm* terms, int termCount, Store mode, const double* denominators) {
  if (!in.axis[0].poly) return sparseCoxDeBoor<false>(in, cell, begin, end, blended, terms, termCount, mode, denominators);
  switch (in.axis[0].poly->degree) {
    case 1: return sparsePowerT<1>(in, cell, begin, end, blended, terms, termCount, mode, denominators);
    case 2: return sparsePowerT<2>(in, cell, begin, end, blended, terms, termCount, mode, denominators);
    default: return sparsePowerT<3>(in, cell, begin, end, blended, terms, termCount, mode, denominators);
  }
}

FFDKIT_VECTOR_CLONES
void sparseBlockKeepingWeights(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end,
                               bool blended, const SparseTerm& term, Store mode, double* weights) {
  if (!in.axis[0].poly)
    return sparseCoxDeBoor<true>(in, cell, begin, end, blended, &term, 1, mode, nullptr, weights);
  switch (in.axis[0].poly->degree) {
    case 1: return sparsePowerT<1, true>(in, cell, begin, end, blended, &term, 1, mode, nullptr, weights);
    case 2: return sparsePowerT<2, true>(in, cell, begin, end, blended, &term, 1, mode, nullptr, weights);
    default: return sparsePowerT<3, true>(in, cell, begin, end, blended, &term, 1, mode, nullptr, weights);
  }
}

FFDKIT_VECTOR_CLONES
void weightedBlock(const KernelInput& in, std::uint32_t begin, std::uint32_t end, bool blended, const double* weights,
                   const SparseTerm& term, Store mode) {
  for (std::uint32_t q0 = begin; q0 < end; q0 += kLanes) {
    const int count = static_cast<int>(std::min<std::uint32_t>(kLanes, end - q0));
    const Lane weight = loadLanes(weights, q0, count);
    // As sparseBlock's sum over its one term, from zero (0 + w dP, not w dP: the same zeros' signs).
    Lane dx = splat(0.0), dy = splat(0.0), dz = splat(0.0);
    dx += weight * term.dx;
    dy += weight * term.dy;
    dz += weight * term.dz;
    storeLanes(in, q0, count, blended, dx, dy, dz, mode);
  }
}

FFDKIT_VECTOR_CLONES
void rationalPowerBlock(const KernelInput& in, const int cell[3], std::uint32_t begin, std::uint32_t end, bool blended,
                        const double* C, bool baseRational, double* denominators, Store mode) {
  const int K = in.axis[0].poly->degree;
  if (baseRational) {
    if (K == 1) return rationalPowerBlockT<1, true>(in, cell, begin, end, blended, C, denominators, mode);
    if (K == 2) return rationalPowerBlockT<2, true>(in, cell, begin, end, blended, C, denominators, mode);
    return rationalPowerBlockT<3, true>(in, cell, begin, end, blended, C, denominators, mode);
  }
  if (K == 1) return rationalPowerBlockT<1, false>(in, cell, begin, end, blended, C, denominators, mode);
  if (K == 2) return rationalPowerBlockT<2, false>(in, cell, begin, end, blended, C, denominators, mode);
  return rationalPowerBlockT<3, false>(in, cell, begin, end, blended, C, denominators, mode);
}

}  // namespace ffdkit::ffd::detail
