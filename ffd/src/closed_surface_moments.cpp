#include "closed_surface_moments.h"

#include <algorithm>

#include "vector_clones.h"

namespace ffdkit::ffd::detail {
namespace {

constexpr Eigen::Index kParallelTriangles = 32768;
constexpr double kSixth = 1.0 / 6.0;
constexpr double kTwentyFourth = 1.0 / 24.0;
constexpr Eigen::Index kChunk = 4096;  // triangles per task

// Columns of a #vertices x 3 column-major matrix, with the origin taken off on reading.
struct Points {
  const double* x;
  const double* y;
  const double* z;
  double ox, oy, oz;
  FFDKIT_INLINE void at(Eigen::Index v, double out[3]) const {
    out[0] = x[v] - ox;
    out[1] = y[v] - oy;
    out[2] = z[v] - oz;
  }
};

Points columns(const Eigen::MatrixX3d& x, const Eigen::Vector3d& origin) {
  const Eigen::Index n = x.rows();
  return {x.data(), x.data() + n, x.data() + 2 * n, origin[0], origin[1], origin[2]};
}

// The sums of triangles [begin, end): out[0] = sum det, out[1 + k] = sum det ((a+b+c)_k / 24 - t_k / 6).
FFDKIT_VECTOR_CLONES
void sumTriangles(const Points& p, const int* triangles, Eigen::Index begin, Eigen::Index end, const double t[3],
                  double out[4]) {
  // Multiplications by constants: a division in the loop would cost more than the rest of it.
  const double t6[3] = {t[0] / 6.0, t[1] / 6.0, t[2] / 6.0};
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  for (Eigen::Index r = begin; r < end; ++r) {
    double a[3], b[3], c[3];
    p.at(triangles[3 * r], a);
    p.at(triangles[3 * r + 1], b);
    p.at(triangles[3 * r + 2], c);
    const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                       a[2] * (b[0] * c[1] - b[1] * c[0]);
    s0 += det;
    s1 += det * ((a[0] + b[0] + c[0]) * kTwentyFourth - t6[0]);
    s2 += det * ((a[1] + b[1] + c[1]) * kTwentyFourth - t6[1]);
    s3 += det * ((a[2] + b[2] + c[2]) * kTwentyFourth - t6[2]);
  }
  out[0] = s0;
  out[1] = s1;
  out[2] = s2;
  out[3] = s3;
}

FFDKIT_VECTOR_CLONES
void volumeGradients(const Points& p, const int* offsets, const int* pairs, const Eigen::Index* vertices, int count,
                     double* out, int stride) {
  for (int i = 0; i < count; ++i) {
    const Eigen::Index v = vertices[i];
    double n0 = 0.0, n1 = 0.0, n2 = 0.0;
    for (int e = offsets[v]; e < offsets[v + 1]; ++e) {
      double b[3], c[3];
      p.at(pairs[2 * e], b);
      p.at(pairs[2 * e + 1], c);
      n0 += b[1] * c[2] - b[2] * c[1];
      n1 += b[2] * c[0] - b[0] * c[2];
      n2 += b[0] * c[1] - b[1] * c[0];
    }
    double* o = out + std::ptrdiff_t(stride) * i;
    o[0] = n0 * kSixth;
    o[1] = n1 * kSixth;
    o[2] = n2 * kSixth;
  }
}

FFDKIT_VECTOR_CLONES
void centroidGradients(const Points& p, const int* offsets, const int* pairs, const double t[3],
                       const Eigen::Index* vertices, int count, double* out, int stride) {
  for (int i = 0; i < count; ++i) {
    const Eigen::Index v = vertices[i];
    double a[3];
    p.at(v, a);
    double n[3] = {0.0, 0.0, 0.0};
    double W[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};  // W[j][k] = sum (b x c)_j S_k
    for (int e = offsets[v]; e < offsets[v + 1]; ++e) {
      double b[3], c[3];
      p.at(pairs[2 * e], b);
      p.at(pairs[2 * e + 1], c);
      const double bc[3] = {b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]};
      const double S[3] = {a[0] + b[0] + c[0], a[1] + b[1] + c[1], a[2] + b[2] + c[2]};
      for (int j = 0; j < 3; ++j) {
        n[j] += bc[j];
        for (int k = 0; k < 3; ++k) W[j][k] += bc[j] * S[k];
      }
    }
    // dr_k/dv = W e_k / 24 - t_k n / 6 + d e_k / 24, by multiplications: the divisions cost more
    // than the ring's sums.
    const double d24 = (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]) * kTwentyFourth;
    double* o = out + std::ptrdiff_t(stride) * i;
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j)
        o[3 * k + j] = W[j][k] * kTwentyFourth - t[k] * (n[j] * kSixth) + (j == k ? d24 : 0.0);
  }
}

}  // namespace

SurfaceSums surfaceSums(const Eigen::MatrixX3d& x, const Eigen::Vector3d& origin, const ClosedSurface& surface,
                        const Eigen::Vector3d& target) {
  const Points p = columns(x, origin);
  const Eigen::Index t = surface.triangles().rows();
  const int* triangles = surface.triangles().data();
  const double centred[3] = {target[0] - origin[0], target[1] - origin[1], target[2] - origin[2]};
  const Eigen::Index chunks = (t + kChunk - 1) / kChunk;
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
#pragma omp parallel for reduction(+ : s0, s1, s2, s3) schedule(static) if (t >= kParallelTriangles)
  for (Eigen::Index k = 0; k < chunks; ++k) {
    double part[4];
    sumTriangles(p, triangles, k * kChunk, std::min(t, (k + 1) * kChunk), centred, part);
    s0 += part[0];
    s1 += part[1];
    s2 += part[2];
    s3 += part[3];
  }
  SurfaceSums sums;
  sums.volume = s0 / 6.0;
  sums.centroidResidual = Eigen::Vector3d(s1, s2, s3);
  return sums;
}

void SurfaceGradients::volume(const ClosedSurface& surface, const Eigen::Index* vertices, int count, double* out,
                              int stride) const {
  volumeGradients(columns(x_, origin_), surface.pairOffsets().data(), surface.pairs().data(), vertices, count, out,
                  stride);
}

void SurfaceGradients::centroid(const ClosedSurface& surface, const Eigen::Index* vertices, int count, double* out,
                                int stride) const {
  const double t[3] = {target_[0], target_[1], target_[2]};
  centroidGradients(columns(x_, origin_), surface.pairOffsets().data(), surface.pairs().data(), t, vertices, count,
                    out, stride);
}

}  // namespace ffdkit::ffd::detail
