#include "gesture_normals.h"

#include <algorithm>
#include <cmath>
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
  // One pass per vertex: the gather of its triangles' area vectors, its normal and its point.
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3f sum = scene_view_shapes::vertexSum(vf, faceScratch, i);
    sums.row(i) = sum.transpose();
    writeNormal(out + 3 * i, sum.x(), sum.y(), sum.z());
    xyz[3 * i] = static_cast<float>(x[i] - ox);
    xyz[3 * i + 1] = static_cast<float>(y[i] - oy);
    xyz[3 * i + 2] = static_cast<float>(z[i] - oz);
  }
  normals->Modified();
  drawn->Modified();
}

void GestureNormals::stopFollowing() { active_ = false; }

bool GestureNormals::follow(const scenes::SceneDeformer& deformer, scenes::ObjectId object, vtkPoints* points,
                            vtkFloatArray* normals) {
  const Eigen::Index n = sums_.rows();
  if (!active_ || points->GetDataType() != VTK_FLOAT || points->GetNumberOfPoints() != n ||
      normals->GetNumberOfTuples() != n || normals->GetNumberOfComponents() != 3 || beta_.rows() != n ||
      motion_.rows() != n)
    return false;
  const std::optional<scenes::GestureMotion> motion = deformer.gestureMotion(object);
  if (!motion || motion->controlPoints.size() != 1 || motion->baseRevision != baseRevision_ ||
      motion->lattice != lattice_ || motion->controlPoints[0] != controlPoint_)
    return false;
  const Eigen::Vector3d now = motion->displacements.row(0).transpose();
  // The points: x_v(t) = x_v(t') + beta_v (D(t) - D(t')) (gesture_normals.h: x_v(t) = x_v(0) + beta_v D(t)).
  const Eigen::Vector3f step = (now - shownDisplacement_).cast<float>();
  const float sx = step.x(), sy = step.y(), sz = step.z();
  // The normals: N_v(t) = N_v(t0) + (D(t) - D(t0)) x W_v, normalised (+z for a zero sum, as exactNormals).
  const Eigen::Vector3f d = (now - startDisplacement_).cast<float>();
  const float dx = d.x(), dy = d.y(), dz = d.z();
  float* xyz = static_cast<float*>(points->GetVoidPointer(0));
  float* out = normals->GetPointer(0);
  // One pass per vertex on both cores, four vertices at a time where SSE is there (the sqrt and the
  // division of the normals are a third of a scalar loop's time; the stores stay interleaved as
  // VTK wants them). The same arithmetic, so the same bits, as the scalar loop that ends it.
  const float *nx = sums_.col(0).data(), *ny = sums_.col(1).data(), *nz = sums_.col(2).data();
  const float *wx = motion_.col(0).data(), *wy = motion_.col(1).data(), *wz = motion_.col(2).data();
  const float* beta = beta_.data();
  const auto scalar = [&](Eigen::Index i) {
    const float x = nx[i] + (dy * wz[i] - dz * wy[i]);
    const float y = ny[i] + (dz * wx[i] - dx * wz[i]);
    const float z = nz[i] + (dx * wy[i] - dy * wx[i]);
    const float w = beta[i];
    xyz[3 * i] += w * sx;
    xyz[3 * i + 1] += w * sy;
    xyz[3 * i + 2] += w * sz;
    writeNormal(out + 3 * i, x, y, z);
  };
#if defined(__SSE2__)
  const Eigen::Index quads = n / 4;
  const __m128 vdx = _mm_set1_ps(dx), vdy = _mm_set1_ps(dy), vdz = _mm_set1_ps(dz);
  // The step in the pattern of four interleaved points: (x y z x) (y z x y) (z x y z).
  const __m128 s0 = _mm_setr_ps(sx, sy, sz, sx), s1 = _mm_setr_ps(sy, sz, sx, sy), s2 = _mm_setr_ps(sz, sx, sy, sz);
  const __m128 infinity = _mm_set1_ps(std::numeric_limits<float>::infinity()), one = _mm_set1_ps(1.0f);
#pragma omp parallel for schedule(static)
  for (Eigen::Index q = 0; q < quads; ++q) {
    const Eigen::Index i = 4 * q;
    const __m128 ax = _mm_loadu_ps(wx + i), ay = _mm_loadu_ps(wy + i), az = _mm_loadu_ps(wz + i);
    const __m128 x = _mm_add_ps(_mm_loadu_ps(nx + i), _mm_sub_ps(_mm_mul_ps(vdy, az), _mm_mul_ps(vdz, ay)));
    const __m128 y = _mm_add_ps(_mm_loadu_ps(ny + i), _mm_sub_ps(_mm_mul_ps(vdz, ax), _mm_mul_ps(vdx, az)));
    const __m128 z = _mm_add_ps(_mm_loadu_ps(nz + i), _mm_sub_ps(_mm_mul_ps(vdx, ay), _mm_mul_ps(vdy, ax)));
    const __m128 length =
        _mm_sqrt_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(x, x), _mm_mul_ps(y, y)), _mm_mul_ps(z, z)));
    const __m128 inverse = _mm_div_ps(one, length);
    const __m128 some = _mm_cmplt_ps(inverse, infinity);
    alignas(16) float ox[4], oy[4], oz[4];
    _mm_store_ps(ox, _mm_and_ps(some, _mm_mul_ps(x, inverse)));
    _mm_store_ps(oy, _mm_and_ps(some, _mm_mul_ps(y, inverse)));
    _mm_store_ps(oz, _mm_or_ps(_mm_and_ps(some, _mm_mul_ps(z, inverse)), _mm_andnot_ps(some, one)));
    float* o = out + 3 * i;
    for (int k = 0; k < 4; ++k) {
      o[3 * k] = ox[k];
      o[3 * k + 1] = oy[k];
      o[3 * k + 2] = oz[k];
    }
    const __m128 b = _mm_loadu_ps(beta + i);
    float* p = xyz + 3 * i;
    _mm_storeu_ps(p, _mm_add_ps(_mm_loadu_ps(p), _mm_mul_ps(_mm_shuffle_ps(b, b, _MM_SHUFFLE(1, 0, 0, 0)), s0)));
    _mm_storeu_ps(p + 4, _mm_add_ps(_mm_loadu_ps(p + 4), _mm_mul_ps(_mm_shuffle_ps(b, b, _MM_SHUFFLE(2, 2, 1, 1)), s1)));
    _mm_storeu_ps(p + 8, _mm_add_ps(_mm_loadu_ps(p + 8), _mm_mul_ps(_mm_shuffle_ps(b, b, _MM_SHUFFLE(3, 3, 3, 2)), s2)));
  }
  for (Eigen::Index i = 4 * quads; i < n; ++i) scalar(i);
#else
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) scalar(i);
#endif
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
  deformer.controlWeights(object, motion->controlPoints[0], weights_);  // into the buffer of the last drag
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
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector3f w = scene_view_shapes::vertexSum(vf, faceScratch, i);
      motion_.row(i) = w.transpose();
      beta_[i] = static_cast<float>(beta[i]);
      const Eigen::Vector3f sum = Eigen::Vector3f(sums_.row(i).transpose()) + d.cross(w);
      writeNormal(out + 3 * i, sum.x(), sum.y(), sum.z());
      xyz[3 * i] = static_cast<float>(x[i] - ox);
      xyz[3 * i + 1] = static_cast<float>(y[i] - oy);
      xyz[3 * i + 2] = static_cast<float>(z[i] - oz);
    }
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
