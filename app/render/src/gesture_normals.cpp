#include "gesture_normals.h"

#include <algorithm>
#include <limits>

#include <Eigen/Core>
#include <vtkFloatArray.h>
#include <vtkType.h>

namespace ffdkit::app {

using scene_view_shapes::VertexFaces;

namespace {

// The normalised `sum` into out[0..2] (+z for a zero sum).
inline void writeNormal(float* out, const Eigen::Vector3f& sum) {
  const float length = sum.norm();
  const Eigen::Vector3f v = length > 0.0f ? Eigen::Vector3f(sum / length) : Eigen::Vector3f::UnitZ();
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
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
    writeNormal(out + 3 * i, sum);
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
  // In chunks: the arithmetic on columns (Eigen vectorises it, sqrt included), then the
  // interleaved stores VTK wants; memory bound, so both cores.
  constexpr Eigen::Index kChunk = 1024;
  using Column = Eigen::Array<float, Eigen::Dynamic, 1, 0, kChunk, 1>;
  using In = Eigen::Map<const Eigen::ArrayXf>;
  const float *nx = sums_.col(0).data(), *ny = sums_.col(1).data(), *nz = sums_.col(2).data();
  const float *wx = motion_.col(0).data(), *wy = motion_.col(1).data(), *wz = motion_.col(2).data();
  const float* beta = beta_.data();
  const Eigen::Index chunks = (n + kChunk - 1) / kChunk;
#pragma omp parallel for schedule(static)
  for (Eigen::Index c = 0; c < chunks; ++c) {
    const Eigen::Index first = c * kChunk, m = std::min(kChunk, n - first);
    const Column x = In(nx + first, m) + (dy * In(wz + first, m) - dz * In(wy + first, m));
    const Column y = In(ny + first, m) + (dz * In(wx + first, m) - dx * In(wz + first, m));
    const Column z = In(nz + first, m) + (dx * In(wy + first, m) - dy * In(wx + first, m));
    const Column inverse = (x.square() + y.square() + z.square()).sqrt().inverse();  // inf for a zero sum
    float* o = out + 3 * first;
    float* p = xyz + 3 * first;
    const float* b = beta + first;
    for (Eigen::Index j = 0; j < m; ++j) {
      const float w = b[j];
      p[3 * j] += w * sx;
      p[3 * j + 1] += w * sy;
      p[3 * j + 2] += w * sz;
      const bool some = inverse[j] < std::numeric_limits<float>::infinity();
      o[3 * j] = some ? x[j] * inverse[j] : 0.0f;
      o[3 * j + 1] = some ? y[j] * inverse[j] : 0.0f;
      o[3 * j + 2] = some ? z[j] * inverse[j] : 1.0f;
    }
  }
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
      writeNormal(out + 3 * i, Eigen::Vector3f(sums_.row(i).transpose()) + d.cross(w));
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
