#include "gesture_normals.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include <Eigen/Core>
#include <vtkFloatArray.h>
#include <vtkType.h>

namespace ffdkit::app {

using scene_view_shapes::VertexFaces;

namespace {

// (x, y, z) normalised into o[0..2], +z for a zero sum (one division per vertex).
inline void writeNormal(float* o, float x, float y, float z) {
  const float inverse = 1.0f / std::sqrt(x * x + y * y + z * z);  // inf for a zero sum
  const bool some = inverse < std::numeric_limits<float>::infinity();
  o[0] = some ? x * inverse : 0.0f;
  o[1] = some ? y * inverse : 0.0f;
  o[2] = some ? z * inverse : 1.0f;
}

// `drawn` as n float32 points and `normals` as n normals, ready to be written.
void sizeArrays(Eigen::Index n, vtkPoints* drawn, vtkFloatArray* normals) {
  if (drawn->GetDataType() != VTK_FLOAT) drawn->SetDataTypeToFloat();
  drawn->SetNumberOfPoints(n);
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
}

// The followed normals of a step: N + d x W normalised, from the sums N and the motion W (columns)
// with D - D(t0) = d = (dx, dy, dz), written interleaved to out (FollowPass).
struct FollowedNormals {
  const float *nx, *ny, *nz, *wx, *wy, *wz;
  float* out;
  float dx, dy, dz;

  // Vertex i. The arithmetic every vector form below repeats lane by lane, in the same order and
  // without fused multiply-adds, so every vertex gets these bits.
  void scalar(Eigen::Index i) const {
    const float x = nx[i] + (dy * wz[i] - dz * wy[i]);
    const float y = ny[i] + (dz * wx[i] - dx * wz[i]);
    const float z = nz[i] + (dx * wy[i] - dy * wx[i]);
    writeNormal(out + 3 * i, x, y, z);
  }
};

// One followed step over the vertices (GestureNormals::follow): the normals, beta, and the float
// points (interleaved, updated in place) with the step of D since the points shown (sx, sy, sz).
struct FollowPass {
  FollowedNormals normals;
  const float* beta;
  float* xyz;
  float sx, sy, sz;

  // Vertex i: its normal, and x += beta s.
  void scalar(Eigen::Index i) const {
    const float w = beta[i];
    xyz[3 * i] += w * sx;
    xyz[3 * i + 1] += w * sy;
    xyz[3 * i + 2] += w * sz;
    normals.scalar(i);
  }
};

#if defined(__SSE2__)
// How far ahead of the vertex it moves a follow pass asks for the float points it will read and
// write: the processor's own prefetch follows the seven streams the pass only reads, not this
// one it reads and writes back (a quarter of the pass's time at 1M vertices without the hint,
// BM_DragStep). 256 vertices = 3 KB ahead, about a microsecond of the pass.
constexpr Eigen::Index kPointsAhead = 256;

// Four vertices' normals (x, y, z: one coordinate of four vertices each) as three interleaved
// vectors (x0 y0 z0 x1) (y1 z1 x2 y2) (z2 x3 y3 z3), stored at o: with streaming stores when o is
// 16-byte aligned (the normals are only written: no read of their old lines), else plain ones.
inline void storeInterleaved(float* o, __m128 x, __m128 y, __m128 z, bool stream) {
  const __m128 xy01 = _mm_unpacklo_ps(x, y);  // x0 y0 x1 y1
  const __m128 xy23 = _mm_unpackhi_ps(x, y);  // x2 y2 x3 y3
  const __m128 v0 = _mm_shuffle_ps(xy01, _mm_shuffle_ps(z, x, _MM_SHUFFLE(1, 1, 0, 0)), _MM_SHUFFLE(2, 0, 1, 0));
  const __m128 v1 = _mm_shuffle_ps(_mm_shuffle_ps(y, z, _MM_SHUFFLE(1, 1, 1, 1)), xy23, _MM_SHUFFLE(1, 0, 2, 0));
  const __m128 v2 = _mm_shuffle_ps(_mm_shuffle_ps(z, xy23, _MM_SHUFFLE(2, 2, 2, 2)),
                                   _mm_shuffle_ps(xy23, z, _MM_SHUFFLE(3, 3, 3, 2)), _MM_SHUFFLE(2, 1, 2, 0));
  if (stream) {
    _mm_stream_ps(o, v0);
    _mm_stream_ps(o + 4, v1);
    _mm_stream_ps(o + 8, v2);
  } else {
    _mm_storeu_ps(o, v0);
    _mm_storeu_ps(o + 4, v1);
    _mm_storeu_ps(o + 8, v2);
  }
}

// Four sums (x, y, z: one coordinate of four vertices each) normalised as writeNormal does, lane by
// lane, and stored interleaved at o.
inline void storeNormalised(float* o, __m128 x, __m128 y, __m128 z, bool stream) {
  const __m128 infinity = _mm_set1_ps(std::numeric_limits<float>::infinity()), one = _mm_set1_ps(1.0f);
  const __m128 length = _mm_sqrt_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(x, x), _mm_mul_ps(y, y)), _mm_mul_ps(z, z)));
  const __m128 inverse = _mm_div_ps(one, length);
  const __m128 some = _mm_cmplt_ps(inverse, infinity);
  storeInterleaved(o, _mm_and_ps(some, _mm_mul_ps(x, inverse)), _mm_and_ps(some, _mm_mul_ps(y, inverse)),
                   _mm_or_ps(_mm_and_ps(some, _mm_mul_ps(z, inverse)), _mm_andnot_ps(some, one)), stream);
}

// Vertices i..i+3's followed normals (FollowedNormals::scalar, four lanes), with (vdx, vdy, vdz)
// the broadcast d, stored interleaved at f.out + 3 i.
inline void storeNormalQuad(const FollowedNormals& f, Eigen::Index i, __m128 vdx, __m128 vdy, __m128 vdz, bool stream) {
  const __m128 ax = _mm_loadu_ps(f.wx + i), ay = _mm_loadu_ps(f.wy + i), az = _mm_loadu_ps(f.wz + i);
  const __m128 x = _mm_add_ps(_mm_loadu_ps(f.nx + i), _mm_sub_ps(_mm_mul_ps(vdy, az), _mm_mul_ps(vdz, ay)));
  const __m128 y = _mm_add_ps(_mm_loadu_ps(f.ny + i), _mm_sub_ps(_mm_mul_ps(vdz, ax), _mm_mul_ps(vdx, az)));
  const __m128 z = _mm_add_ps(_mm_loadu_ps(f.nz + i), _mm_sub_ps(_mm_mul_ps(vdx, ay), _mm_mul_ps(vdy, ax)));
  storeNormalised(f.out + 3 * i, x, y, z, stream);
}

// Vertices [4 q0, 4 q1), four at a time with SSE.
void followQuads(const FollowPass& pass, Eigen::Index q0, Eigen::Index q1, bool stream) {
  const FollowPass f = pass;  // a local copy: the stores below cannot change its pointers, kept in registers
  const __m128 vdx = _mm_set1_ps(f.normals.dx), vdy = _mm_set1_ps(f.normals.dy), vdz = _mm_set1_ps(f.normals.dz);
  // The step in the pattern of four interleaved points: (x y z x) (y z x y) (z x y z).
  const __m128 s0 = _mm_setr_ps(f.sx, f.sy, f.sz, f.sx), s1 = _mm_setr_ps(f.sy, f.sz, f.sx, f.sy),
               s2 = _mm_setr_ps(f.sz, f.sx, f.sy, f.sz);
  for (Eigen::Index q = q0; q < q1; ++q) {
    const Eigen::Index i = 4 * q;
    storeNormalQuad(f.normals, i, vdx, vdy, vdz, stream);
    const __m128 b = _mm_loadu_ps(f.beta + i);
    float* p = f.xyz + 3 * i;
    _mm_prefetch(reinterpret_cast<const char*>(p + 3 * kPointsAhead), _MM_HINT_T0);  // never faults, also past the end
    _mm_storeu_ps(p, _mm_add_ps(_mm_loadu_ps(p), _mm_mul_ps(_mm_shuffle_ps(b, b, _MM_SHUFFLE(1, 0, 0, 0)), s0)));
    _mm_storeu_ps(p + 4, _mm_add_ps(_mm_loadu_ps(p + 4), _mm_mul_ps(_mm_shuffle_ps(b, b, _MM_SHUFFLE(2, 2, 1, 1)), s1)));
    _mm_storeu_ps(p + 8, _mm_add_ps(_mm_loadu_ps(p + 8), _mm_mul_ps(_mm_shuffle_ps(b, b, _MM_SHUFFLE(3, 3, 3, 2)), s2)));
  }
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define FFDKIT_FOLLOW_AVX2 1
// Eight sums normalised as writeNormal does, lane by lane, and stored interleaved at o.
__attribute__((target("avx2"), always_inline)) inline void storeNormalised(float* o, __m256 x, __m256 y, __m256 z,
                                                                           bool stream) {
  const __m256 infinity = _mm256_set1_ps(std::numeric_limits<float>::infinity()), one = _mm256_set1_ps(1.0f);
  const __m256 length =
      _mm256_sqrt_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(x, x), _mm256_mul_ps(y, y)), _mm256_mul_ps(z, z)));
  const __m256 inverse = _mm256_div_ps(one, length);
  const __m256 some = _mm256_cmp_ps(inverse, infinity, _CMP_LT_OQ);
  const __m256 ox = _mm256_and_ps(some, _mm256_mul_ps(x, inverse));
  const __m256 oy = _mm256_and_ps(some, _mm256_mul_ps(y, inverse));
  const __m256 oz = _mm256_or_ps(_mm256_and_ps(some, _mm256_mul_ps(z, inverse)), _mm256_andnot_ps(some, one));
  storeInterleaved(o, _mm256_castps256_ps128(ox), _mm256_castps256_ps128(oy), _mm256_castps256_ps128(oz), stream);
  storeInterleaved(o + 12, _mm256_extractf128_ps(ox, 1), _mm256_extractf128_ps(oy, 1), _mm256_extractf128_ps(oz, 1),
                   stream);
}

// Vertices i..i+7's followed normals (FollowedNormals::scalar, eight lanes), with (vdx, vdy, vdz)
// the broadcast d, stored interleaved at f.out + 3 i.
__attribute__((target("avx2"), always_inline)) inline void storeNormalOctet(const FollowedNormals& f, Eigen::Index i,
                                                                            __m256 vdx, __m256 vdy, __m256 vdz,
                                                                            bool stream) {
  const __m256 ax = _mm256_loadu_ps(f.wx + i), ay = _mm256_loadu_ps(f.wy + i), az = _mm256_loadu_ps(f.wz + i);
  const __m256 x =
      _mm256_add_ps(_mm256_loadu_ps(f.nx + i), _mm256_sub_ps(_mm256_mul_ps(vdy, az), _mm256_mul_ps(vdz, ay)));
  const __m256 y =
      _mm256_add_ps(_mm256_loadu_ps(f.ny + i), _mm256_sub_ps(_mm256_mul_ps(vdz, ax), _mm256_mul_ps(vdx, az)));
  const __m256 z =
      _mm256_add_ps(_mm256_loadu_ps(f.nz + i), _mm256_sub_ps(_mm256_mul_ps(vdx, ay), _mm256_mul_ps(vdy, ax)));
  storeNormalised(f.out + 3 * i, x, y, z, stream);
}

// Vertices [8 o0, 8 o1), eight at a time with AVX2 (no FMA: the bits of the SSE and scalar forms;
// the square root and the division are a third of the pass, and AVX2 does eight for the price of
// four).
__attribute__((target("avx2"))) void followOctets(const FollowPass& pass, Eigen::Index o0, Eigen::Index o1, bool stream) {
  const FollowPass f = pass;  // a local copy: the stores below cannot change its pointers, kept in registers
  const __m256 vdx = _mm256_set1_ps(f.normals.dx), vdy = _mm256_set1_ps(f.normals.dy), vdz = _mm256_set1_ps(f.normals.dz);
  // The step in the pattern of eight interleaved points, and the lanes of beta each float takes.
  const __m256 s0 = _mm256_setr_ps(f.sx, f.sy, f.sz, f.sx, f.sy, f.sz, f.sx, f.sy);
  const __m256 s1 = _mm256_setr_ps(f.sz, f.sx, f.sy, f.sz, f.sx, f.sy, f.sz, f.sx);
  const __m256 s2 = _mm256_setr_ps(f.sy, f.sz, f.sx, f.sy, f.sz, f.sx, f.sy, f.sz);
  const __m256i b0 = _mm256_setr_epi32(0, 0, 0, 1, 1, 1, 2, 2), b1 = _mm256_setr_epi32(2, 3, 3, 3, 4, 4, 4, 5),
                b2 = _mm256_setr_epi32(5, 5, 6, 6, 6, 7, 7, 7);
  for (Eigen::Index o = o0; o < o1; ++o) {
    const Eigen::Index i = 8 * o;
    storeNormalOctet(f.normals, i, vdx, vdy, vdz, stream);
    const __m256 b = _mm256_loadu_ps(f.beta + i);
    float* p = f.xyz + 3 * i;
    _mm_prefetch(reinterpret_cast<const char*>(p + 3 * kPointsAhead), _MM_HINT_T0);  // never faults, also past the end
    _mm256_storeu_ps(p, _mm256_add_ps(_mm256_loadu_ps(p), _mm256_mul_ps(_mm256_permutevar8x32_ps(b, b0), s0)));
    _mm256_storeu_ps(p + 8, _mm256_add_ps(_mm256_loadu_ps(p + 8), _mm256_mul_ps(_mm256_permutevar8x32_ps(b, b1), s1)));
    _mm256_storeu_ps(p + 16, _mm256_add_ps(_mm256_loadu_ps(p + 16), _mm256_mul_ps(_mm256_permutevar8x32_ps(b, b2), s2)));
  }
}
#endif
#endif

// Every vertex of a followed step, in one pass on both cores: eight vertices at a time where the
// processor has AVX2, four with SSE, the last few one by one (the same bits either way).
void followVertices(const FollowPass& f, Eigen::Index n) {
#if defined(__SSE2__)
#if defined(FFDKIT_FOLLOW_AVX2)
  static const bool avx2 = __builtin_cpu_supports("avx2");
#else
  constexpr bool avx2 = false;
#endif
  const Eigen::Index width = avx2 ? 8 : 4;
  const Eigen::Index groups = n / width;
  const bool stream = reinterpret_cast<std::uintptr_t>(f.normals.out) % 16 == 0;
#pragma omp parallel if (n >= 16384)
  {
    // Static halves of the groups, in chunks of 1024 vertices.
#pragma omp for schedule(static) nowait
    for (Eigen::Index c = 0; c < (groups + 127) / 128; ++c) {
      const Eigen::Index g0 = 128 * c, g1 = std::min(groups, g0 + 128);
#if defined(FFDKIT_FOLLOW_AVX2)
      if (avx2) {
        followOctets(f, g0, g1, stream);
        continue;
      }
#endif
      followQuads(f, g0, g1, stream);
    }
    if (stream) _mm_sfence();  // the streamed normals visible before the threads join
  }
  for (Eigen::Index i = width * groups; i < n; ++i) f.scalar(i);
#else
#pragma omp parallel for schedule(static) if (n >= 16384)
  for (Eigen::Index i = 0; i < n; ++i) f.scalar(i);
#endif
}

// Vertices are gathered (the sums over their triangles) a chunk at a time into columns, then
// normalised together: the square root and the division, a third of a scalar pass, run four or
// eight at a time.
constexpr Eigen::Index kChunk = 256;

#if defined(FFDKIT_FOLLOW_AVX2)
__attribute__((target("avx2"))) void normaliseOctets(float* out, const float* x, const float* y, const float* z,
                                                     Eigen::Index octets) {
  for (Eigen::Index o = 0; o < octets; ++o) {
    const Eigen::Index i = 8 * o;
    storeNormalised(out + 3 * i, _mm256_loadu_ps(x + i), _mm256_loadu_ps(y + i), _mm256_loadu_ps(z + i), false);
  }
}
#endif

// The normals of `count` vertices (columns x, y, z of their sums) into out (interleaved):
// writeNormal's arithmetic on every one, eight or four at a time.
void normaliseChunk(float* out, const float* x, const float* y, const float* z, Eigen::Index count) {
  Eigen::Index done = 0;
#if defined(__SSE2__)
#if defined(FFDKIT_FOLLOW_AVX2)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) {
    normaliseOctets(out, x, y, z, count / 8);
    done = count / 8 * 8;
  }
#endif
  for (; done + 4 <= count; done += 4)
    storeNormalised(out + 3 * done, _mm_loadu_ps(x + done), _mm_loadu_ps(y + done), _mm_loadu_ps(z + done), false);
#endif
  for (; done < count; ++done) writeNormal(out + 3 * done, x[done], y[done], z[done]);
}

// For each chunk of kChunk vertices [i0, i1), on both cores: gather(i, sum) for each vertex of it
// (its sum into `sum`), then their normals into out[3 i0 ..] (normaliseChunk).
template <class Gather>
void chunkedNormals(Eigen::Index n, float* out, const Gather& gather) {
#pragma omp parallel for schedule(static)
  for (Eigen::Index c = 0; c < (n + kChunk - 1) / kChunk; ++c) {
    const Eigen::Index i0 = c * kChunk, count = std::min(kChunk, n - i0);
    float x[kChunk], y[kChunk], z[kChunk];
    for (Eigen::Index k = 0; k < count; ++k) {
      const Eigen::Vector3f sum = gather(i0 + k);
      x[k] = sum.x();
      y[k] = sum.y();
      z[k] = sum.z();
    }
    normaliseChunk(out + 3 * i0, x, y, z, count);
  }
}

}  // namespace

void exactNormals(const Eigen::MatrixX3i& triangles, const VertexFaces& vf, const Eigen::MatrixX3d& points,
                  const Eigen::Vector3d& origin, std::vector<Eigen::Vector3f>& faceScratch, Eigen::MatrixX3f& sums,
                  vtkPoints* drawn, vtkFloatArray* normals) {
  const Eigen::Index n = points.rows();
  scene_view_shapes::faceAreaVectors(triangles, points, faceScratch);
  sums.resize(n, 3);
  sizeArrays(n, drawn, normals);
  float* out = normals->GetPointer(0);
  float* xyz = static_cast<float*>(drawn->GetVoidPointer(0));
  const double *x = points.data(), *y = x + n, *z = y + n;  // column-major
  const double ox = origin.x(), oy = origin.y(), oz = origin.z();
  // One pass per vertex: the gather of its triangles' area vectors, its point, and its normal.
  chunkedNormals(n, out, [&](Eigen::Index i) {
    const Eigen::Vector3f sum = scene_view_shapes::vertexSum(vf, faceScratch, i);
    sums.row(i) = sum.transpose();
    xyz[3 * i] = static_cast<float>(x[i] - ox);
    xyz[3 * i + 1] = static_cast<float>(y[i] - oy);
    xyz[3 * i + 2] = static_cast<float>(z[i] - oz);
    return sum;
  });
  normals->Modified();
  drawn->Modified();
}

void GestureNormals::stopFollowing() { active_ = false; }

bool GestureNormals::follows(const scenes::SceneDeformer& deformer, scenes::ObjectId object, vtkPoints* points,
                             vtkFloatArray* normals) const {
  const Eigen::Index n = sums_.rows();
  if (!active_ || points->GetDataType() != VTK_FLOAT || points->GetNumberOfPoints() != n ||
      normals->GetNumberOfTuples() != n || normals->GetNumberOfComponents() != 3 || beta_.rows() != n ||
      motion_.rows() != n)
    return false;
  const std::optional<scenes::GestureMotion> motion = deformer.gestureMotion(object);
  return motion && motion->controlPoints.size() == 1 && motion->baseRevision == baseRevision_ &&
         motion->lattice == lattice_ && motion->controlPoints[0] == controlPoint_;
}

bool GestureNormals::follow(const scenes::SceneDeformer& deformer, scenes::ObjectId object, vtkPoints* points,
                            vtkFloatArray* normals) {
  if (!follows(deformer, object, points, normals)) return false;
  const Eigen::Index n = sums_.rows();
  const Eigen::Vector3d now = deformer.gestureMotion(object)->displacements.row(0).transpose();
  // The points: x_v(t) = x_v(t') + beta_v (D(t) - D(t')) (gesture_normals.h: x_v(t) = x_v(0) + beta_v D(t)).
  const Eigen::Vector3f step = (now - shownDisplacement_).cast<float>();
  // The normals: N_v(t) = N_v(t0) + (D(t) - D(t0)) x W_v, normalised (+z for a zero sum, as exactNormals).
  const Eigen::Vector3f d = (now - startDisplacement_).cast<float>();
  const FollowedNormals followed{sums_.col(0).data(),   sums_.col(1).data(),   sums_.col(2).data(),
                                 motion_.col(0).data(), motion_.col(1).data(), motion_.col(2).data(),
                                 normals->GetPointer(0), d.x(),                 d.y(),
                                 d.z()};
  const FollowPass pass{followed, beta_.data(), static_cast<float*>(points->GetVoidPointer(0)), step.x(), step.y(), step.z()};
  followVertices(pass, n);
  shownDisplacement_ = now;
  points->Modified();
  normals->Modified();
  return true;
}

bool GestureNormals::update(const scenes::SceneDeformer& deformer, scenes::ObjectId object,
                            const Eigen::MatrixX3i& triangles, const VertexFaces& vf, const Eigen::MatrixX3d& points,
                            const Eigen::Vector3d& origin, std::vector<Eigen::Vector3f>& faceScratch, vtkPoints* drawn,
                            vtkFloatArray* normals) {
  const Eigen::Index n = points.rows();
  const std::uint64_t revision = deformer.revision(object);
  const std::optional<scenes::GestureMotion> motion = deformer.gestureMotion(object);
  if (!motion || motion->controlPoints.size() != 1) {
    stopFollowing();
    exactNormals(triangles, vf, points, origin, faceScratch, sums_, drawn, normals);
    sumsRevision_ = revision;
    sumsValid_ = true;
    return false;
  }
  // The first step of a one-control-point motion.
  const Eigen::Vector3d now = motion->displacements.row(0).transpose();
  const bool fromBase = sumsValid_ && sumsRevision_ == motion->baseRevision && sums_.rows() == n;
  if (fromBase) {
    startDisplacement_.setZero();  // sums_ holds N_v(base), where D = 0
  } else {
    exactNormals(triangles, vf, points, origin, faceScratch, sums_, drawn, normals);
    sumsRevision_ = revision;
    sumsValid_ = true;
    startDisplacement_ = now;
  }
  // The weights the deformer's step kept (into the buffer of the last drag): no second evaluation.
  deformer.gestureWeights(object, motion->controlPoints[0], weights_);
  const Eigen::VectorXd& beta = weights_;
  // Per triangle: dbeta1 e2 - dbeta2 e1 (gesture_normals.h).
  scene_view_shapes::perFace(triangles, points, faceScratch,
                             [&](int a, int b, int c, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) -> Eigen::Vector3d {
                               return (beta[b] - beta[a]) * e2 - (beta[c] - beta[a]) * e1;
                             });
  if (motion_.rows() != n) motion_.resize(n, 3);  // kept from the last drag: no fresh pages to fault in
  if (beta_.rows() != n) beta_.resize(n);
  if (fromBase) {
    // One pass per vertex: W_v, beta_v, the normal N_v(base) + D x W_v and the point.
    sizeArrays(n, drawn, normals);
    float* out = normals->GetPointer(0);
    float* xyz = static_cast<float*>(drawn->GetVoidPointer(0));
    const double *x = points.data(), *y = x + n, *z = y + n;  // column-major
    const double ox = origin.x(), oy = origin.y(), oz = origin.z();
    const Eigen::Vector3f d = now.cast<float>();
    chunkedNormals(n, out, [&](Eigen::Index i) {
      const Eigen::Vector3f w = scene_view_shapes::vertexSum(vf, faceScratch, i);
      motion_.row(i) = w.transpose();
      beta_[i] = static_cast<float>(beta[i]);
      xyz[3 * i] = static_cast<float>(x[i] - ox);
      xyz[3 * i + 1] = static_cast<float>(y[i] - oy);
      xyz[3 * i + 2] = static_cast<float>(z[i] - oz);
      return Eigen::Vector3f(Eigen::Vector3f(sums_.row(i).transpose()) + d.cross(w));
    });
    normals->Modified();
    drawn->Modified();
  } else {
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < n; ++i) {
      motion_.row(i) = scene_view_shapes::vertexSum(vf, faceScratch, i).transpose();
      beta_[i] = static_cast<float>(beta[i]);
    }
  }
  active_ = true;
  baseRevision_ = motion->baseRevision;
  lattice_ = motion->lattice;
  controlPoint_ = motion->controlPoints[0];
  shownDisplacement_ = now;
  return fromBase;
}

}  // namespace ffdkit::app
