#pragma once

// Vertex normals that follow a drag instead of being recomputed from the triangles at every step
// (private to ffdkit::render; SceneView::refresh uses it).
//
// During a gesture that moves ONE control point of an object's last lattice stage
// (scenes::GestureMotion), every vertex moves by  x_v(t) = x_v(0) + beta_v D(t): the same world
// displacement D(t) of the control point, scaled by the vertex's weight beta_v = s B_ijk(u,v,w)
// (ffd::controlPointWeights), fixed during the gesture. A triangle's edges then move by
// e1(t) = e1 + D dbeta1, e2(t) = e2 + D dbeta2 (dbeta1 = beta_b - beta_a, dbeta2 = beta_c - beta_a),
// and its area vector is
//     e1(t) x e2(t) = e1 x e2 + D x (dbeta1 e2 - dbeta2 e1)          (the D x D term is 0),
// linear in D. Summed over the triangles of a vertex, the area-weighted normal (the one
// updateNormals computes) is exactly
//     N_v(t) = N_v(t0) + (D(t) - D(t0)) x W_v,   W_v = sum_f (dbeta1 e2 - dbeta2 e1)_f,
// and W_v does not change along the motion (its own change is D (dbeta1 dbeta2 - dbeta2 dbeta1) = 0),
// so it can be taken at any step t0 of it. This is the discrete, exact form of transforming a
// normal by the cofactor of the deformation's Jacobian (Barr 1984, "Global and local deformations
// of solid primitives", n' = det(J) J^-T n): with J = I + D grad(beta)^T the cofactor is
// (1 + grad(beta).D) I - grad(beta) D^T, and on a triangle of area vector A_f with the gradient g_f
// of the linear interpolant of beta, (dbeta1 e2 - dbeta2 e1) = A_f x g_f, so that
// D x (A_f x g_f) = (g_f.D) A_f - g_f (D.A_f) is that cofactor's change applied to A_f, exactly.
//
// Cost per step (follow): one cross product and a normalisation per vertex, and the point moved by
// beta_v times the step of D: 52 bytes read and 36 written, in one pass, instead of a pass over the
// triangles, a gather over each vertex's triangles and a copy of the deformer's points (whose
// delta step the deformer defers: SceneDeformer::points). The first step of a motion computes the
// exact normals, W and beta (a pass over the triangles and a gather, once).
// Motions of several control points (the general form has pairwise D_c x D_c' terms) and every
// other change are recomputed exactly.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <vtkPoints.h>

#include "ffdkit/scenes/scene_deformer.h"
#include "scene_view_shapes.h"

namespace ffdkit::app {

class GestureNormals {
 public:
  /// A later step of the one-control-point motion update() last set up: moves the view's points
  /// by x_v += beta_v (D(t) - D(t')) (t' the step last shown; beta_v in float, the points in
  /// double as VTK holds them) and writes the followed normals, in one pass over the vertices on
  /// both cores, without reading the deformer's points (SceneDeformer::points applies deferred
  /// gesture steps: the view does not ask for them). Returns false, touching nothing, when the
  /// object's motion is not that one (then call update() with the deformer's points).
  bool follow(const scenes::SceneDeformer& deformer, scenes::ObjectId object, vtkPoints* points,
              vtkFloatArray* normals);

  /// Writes the area-weighted vertex normals of `points` (the deformer's present points of
  /// `object`, whose triangles are `triangles`) into `normals`, computed from the triangles
  /// (updateNormals' bits), keeping what follow() needs when the object's motion is one control
  /// point's (its weights beta_v, W_v and N_v(t0)).
  void update(const scenes::SceneDeformer& deformer, scenes::ObjectId object, const Eigen::MatrixX3i& triangles,
              const scene_view_shapes::VertexFaces& vf, const Eigen::MatrixX3d& points,
              std::vector<Eigen::Vector3f>& faceScratch, vtkFloatArray* normals);

  /// Forgets the motion (frees its 28 bytes per vertex).
  void clear();
  /// Heap bytes held for the motion (28 per vertex while one is followed, else 0).
  std::size_t memoryBytes() const {
    return sizeof(float) * std::size_t(sums_.size() + motion_.size() + beta_.size());
  }

 private:
  bool active_ = false;
  std::uint64_t baseRevision_ = 0;
  widgets::WidgetId lattice_;
  Eigen::Index controlPoint_ = -1;
  Eigen::Vector3d startDisplacement_ = Eigen::Vector3d::Zero();  // D(t0)
  Eigen::Vector3d shownDisplacement_ = Eigen::Vector3d::Zero();  // D(t') of the points shown
  // Columns (x, y, z: the per-step loop streams and vectorises over them):
  Eigen::MatrixX3f sums_;    // N_v(t0), the unnormalised area-weighted normals
  Eigen::MatrixX3f motion_;  // W_v
  Eigen::VectorXf beta_;     // beta_v, the moved control point's weights
};

}  // namespace ffdkit::app
