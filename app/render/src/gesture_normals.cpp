#include "gesture_normals.h"

namespace ffdkit::app {

using scene_view_shapes::VertexFaces;

namespace {

// Per triangle: dbeta1 e2 - dbeta2 e1 (see gesture_normals.h), in double, stored as float.
void faceMotionVectors(const Eigen::MatrixX3i& triangles, const Eigen::MatrixX3d& points, const Eigen::VectorXd& beta,
                       std::vector<Eigen::Vector3f>& out) {
  const Eigen::Index n = points.rows();
  const Eigen::Index m = triangles.rows();
  out.resize(static_cast<std::size_t>(m));
  const double* x = points.data();
  const double* y = x + n;
  const double* z = y + n;
#pragma omp parallel for schedule(static)
  for (Eigen::Index t = 0; t < m; ++t) {
    const int a = triangles(t, 0), b = triangles(t, 1), c = triangles(t, 2);
    const Eigen::Vector3d pa(x[a], y[a], z[a]);
    const Eigen::Vector3d e1 = Eigen::Vector3d(x[b], y[b], z[b]) - pa;
    const Eigen::Vector3d e2 = Eigen::Vector3d(x[c], y[c], z[c]) - pa;
    out[static_cast<std::size_t>(t)] = ((beta[b] - beta[a]) * e2 - (beta[c] - beta[a]) * e1).cast<float>();
  }
}

void gatherSums(const VertexFaces& vf, const std::vector<Eigen::Vector3f>& faces, Eigen::Index n, Eigen::Vector3f* sums) {
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();
    for (int k = vf.start[static_cast<std::size_t>(i)]; k < vf.start[static_cast<std::size_t>(i) + 1]; ++k)
      sum += faces[static_cast<std::size_t>(vf.faces[static_cast<std::size_t>(k)])];
    sums[i] = sum;
  }
}

}  // namespace

void GestureNormals::clear() {
  active_ = false;
  sums_ = {};
  motion_ = {};
}

bool GestureNormals::update(const scenes::SceneDeformer& deformer, const std::string& object,
                            const Eigen::MatrixX3i& triangles, const VertexFaces& vf, const Eigen::MatrixX3d& points,
                            std::vector<Eigen::Vector3f>& faceScratch, vtkFloatArray* normals) {
  const Eigen::Index n = points.rows();
  const std::optional<scenes::GestureMotion> motion = deformer.gestureMotion(object);
  const bool single = motion && motion->controlPoints.size() == 1;
  if (single && active_ && motion->baseRevision == baseRevision_ && motion->lattice == lattice_ &&
      motion->controlPoints[0] == controlPoint_ && static_cast<Eigen::Index>(sums_.size()) == n) {
    // N_v(t) = N_v(t0) + (D(t) - D(t0)) x W_v, normalised as gatherNormals does.
    const Eigen::Vector3f d = (Eigen::Vector3d(motion->displacements.row(0)) - startDisplacement_).cast<float>();
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(n);
    float* out = normals->GetPointer(0);
    const Eigen::Vector3f* sums = sums_.data();
    const Eigen::Vector3f* w = motion_.data();
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector3f sum = sums[i] + d.cross(w[i]);
      const float length = sum.norm();
      const Eigen::Vector3f v = length > 0.0f ? Eigen::Vector3f(sum / length) : Eigen::Vector3f::UnitZ();
      out[3 * i] = v.x();
      out[3 * i + 1] = v.y();
      out[3 * i + 2] = v.z();
    }
    normals->Modified();
    return true;
  }
  if (!single) {
    clear();
    scene_view_shapes::updateNormals(normals, triangles, vf, points, faceScratch);
    return false;
  }
  // The first step of a one-control-point motion: the exact normals, and what follows them.
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
  sums_.resize(static_cast<std::size_t>(n));
  motion_.resize(static_cast<std::size_t>(n));
  scene_view_shapes::faceAreaVectors(triangles, points, faceScratch);
  scene_view_shapes::gatherNormals(vf, faceScratch, n, normals->GetPointer(0), sums_.data());
  faceMotionVectors(triangles, points, deformer.controlWeights(object, motion->controlPoints[0]), faceScratch);
  gatherSums(vf, faceScratch, n, motion_.data());
  normals->Modified();
  active_ = true;
  baseRevision_ = motion->baseRevision;
  lattice_ = motion->lattice;
  controlPoint_ = motion->controlPoints[0];
  startDisplacement_ = motion->displacements.row(0).transpose();
  return false;
}

}  // namespace ffdkit::app
