#include "gesture_normals.h"

#include <algorithm>
#include <limits>

#include <Eigen/Core>

namespace ffdkit::app {

using scene_view_shapes::VertexFaces;

namespace {

// Per vertex: the sum of `faces` over its triangles, into the rows of `sums`.
void gatherSums(const VertexFaces& vf, const std::vector<Eigen::Vector3f>& faces, Eigen::MatrixX3f& sums) {
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < sums.rows(); ++i) sums.row(i) = scene_view_shapes::vertexSum(vf, faces, i).transpose();
}

}  // namespace

void GestureNormals::clear() {
  active_ = false;
  sums_.resize(0, 3);
  motion_.resize(0, 3);
  beta_.resize(0);
}

bool GestureNormals::follow(const scenes::SceneDeformer& deformer, scenes::ObjectId object, vtkPoints* points,
                            vtkFloatArray* normals) {
  const Eigen::Index n = sums_.rows();
  if (!active_ || points->GetDataType() != VTK_DOUBLE || points->GetNumberOfPoints() != n ||
      normals->GetNumberOfTuples() != n || normals->GetNumberOfComponents() != 3 || beta_.rows() != n)
    return false;
  const std::optional<scenes::GestureMotion> motion = deformer.gestureMotion(object);
  if (!motion || motion->controlPoints.size() != 1 || motion->baseRevision != baseRevision_ ||
      motion->lattice != lattice_ || motion->controlPoints[0] != controlPoint_)
    return false;
  const Eigen::Vector3d now = motion->displacements.row(0).transpose();
  // The points: x_v(t) = x_v(t') + beta_v (D(t) - D(t')) (gesture_normals.h: x_v(t) = x_v(0) + beta_v D(t)).
  const Eigen::Vector3d step = now - shownDisplacement_;
  const double sx = step.x(), sy = step.y(), sz = step.z();
  // The normals: N_v(t) = N_v(t0) + (D(t) - D(t0)) x W_v, normalised (+z for a zero sum, as gatherNormals).
  const Eigen::Vector3f d = (now - startDisplacement_).cast<float>();
  const float dx = d.x(), dy = d.y(), dz = d.z();
  double* xyz = static_cast<double*>(points->GetVoidPointer(0));
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
    double* p = xyz + 3 * first;
    const float* b = beta + first;
    for (Eigen::Index j = 0; j < m; ++j) {
      const double w = b[j];
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

void GestureNormals::update(const scenes::SceneDeformer& deformer, scenes::ObjectId object,
                            const Eigen::MatrixX3i& triangles, const VertexFaces& vf, const Eigen::MatrixX3d& points,
                            std::vector<Eigen::Vector3f>& faceScratch, vtkFloatArray* normals) {
  const Eigen::Index n = points.rows();
  const std::optional<scenes::GestureMotion> motion = deformer.gestureMotion(object);
  const bool single = motion && motion->controlPoints.size() == 1;
  if (!single) {
    clear();
    scene_view_shapes::updateNormals(normals, triangles, vf, points, faceScratch);
    return;
  }
  // The first step of a one-control-point motion: the exact normals, and what follows them.
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
  sums_.resize(n, 3);
  motion_.resize(n, 3);
  scene_view_shapes::faceAreaVectors(triangles, points, faceScratch);
  scene_view_shapes::gatherNormals(vf, faceScratch, n, normals->GetPointer(0), &sums_);
  const Eigen::VectorXd beta = deformer.controlWeights(object, motion->controlPoints[0]);
  // Per triangle: dbeta1 e2 - dbeta2 e1 (gesture_normals.h).
  scene_view_shapes::perFace(triangles, points, faceScratch,
                             [&](int a, int b, int c, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) -> Eigen::Vector3d {
                               return (beta[b] - beta[a]) * e2 - (beta[c] - beta[a]) * e1;
                             });
  beta_ = beta.cast<float>();
  gatherSums(vf, faceScratch, motion_);
  normals->Modified();
  active_ = true;
  baseRevision_ = motion->baseRevision;
  lattice_ = motion->lattice;
  controlPoint_ = motion->controlPoints[0];
  startDisplacement_ = motion->displacements.row(0).transpose();
  shownDisplacement_ = startDisplacement_;
}

}  // namespace ffdkit::app
