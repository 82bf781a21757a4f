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
// Cost per step (follow): one cross product and a normalisation per vertex, and the float point
// moved by beta_v times the step of D: 40 bytes read and 24 written, in one pass (eight vertices
// at a time with AVX2, four with SSE; the normals with streaming stores, which do not read the
// lines they overwrite), instead of a pass over the triangles, a gather over each vertex's
// triangles and a conversion of the deformer's double points. Nor does the deformer move its own
// double points at such a step: follows() tells SceneView::evaluationRequest that the view reads
// only the motion, which names the object in scenes::EvaluationRequest::followed, and the
// deformer's delta pass waits for a reader of the points (the release evaluates them exactly).
// The passes that gather over the
// triangles (exactNormals, the first step) normalise a chunk of gathered sums at a time the same
// way; every form has the scalar arithmetic's bits.
//
// The first step of a motion: every exact update (update()) keeps the unnormalised sums N_v of
// the points it drew. When the motion starts from those points (GestureMotion::baseRevision is
// their revision, as after a release, an undo or any exact evaluation), N_v(base) is known and
// D(base) = 0, so the first step only reads beta (SceneDeformer::gestureWeights: the weights the
// deformer's step computed and kept, not a second evaluation of the basis), computes the face
// terms of W (one pass over the triangles) and, per vertex, W_v and N_v(base) + D(t0) x W_v:
// no area vectors and no second gather. Otherwise it computes the exact normals first.
// Motions of several control points (the general form has pairwise D_c x D_c' terms) and every
// other change are recomputed exactly.
//
// Points are drawn as float32 relative to an origin o of the object (object_arrays.h): follow()
// adds beta_v (D(t) - D(t')) to the float point, so the drawn points drift from float(x_v(t) - o)
// by float rounding, about one unit in the last place per step; every update() writes
// float(x_v - o) exactly, so the release shows the exact mesh.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <vtkPoints.h>

#include "ffdkit/scenes/scene_deformer.h"
#include "scene_view_shapes.h"

namespace ffdkit::app {

class GestureNormals {
 public:
  /// A later step of the one-control-point motion update() last set up: moves the view's float
  /// points by x_v += beta_v (D(t) - D(t')) (t' the step last shown) and writes the followed
  /// normals, in one pass over the vertices on both cores, without reading the deformer's points.
  /// Returns false, touching nothing, when the object's motion is not that one or `points` are
  /// not float32 (then call update()).
  bool follow(const scenes::SceneDeformer& deformer, scenes::ObjectId object, vtkPoints* points,
              vtkFloatArray* normals);

  /// Whether follow() would take the object's present motion (the one-control-point motion
  /// update() last set up, `points` float32 and both arrays of its size): then the view does not
  /// read the deformer's points at the next steps of that motion, and asks it to let their delta
  /// passes wait (scenes::EvaluationRequest::followed).
  bool follows(const scenes::SceneDeformer& deformer, scenes::ObjectId object, vtkPoints* points,
               vtkFloatArray* normals) const;

  /// Writes `points` (the deformer's present points of `object`, #points x 3, whose triangles are
  /// `triangles`) into `drawn` as float32 relative to `origin` (object_arrays::setFloatPoints) and
  /// their area-weighted vertex normals into `normals`:
  /// from the triangles (exactNormals' bits), or, for the first step of a one-control-point motion
  /// from the points update() last drew, as N_v(base) + D x W_v (see above). Keeps the sums of
  /// the normals, and what follow() needs when the motion is one control point's (beta_v, W_v).
  /// Returns true when it took the first-step form.
  bool update(const scenes::SceneDeformer& deformer, scenes::ObjectId object, const Eigen::MatrixX3i& triangles,
              const scene_view_shapes::VertexFaces& vf, const Eigen::MatrixX3d& points, const Eigen::Vector3d& origin,
              std::vector<Eigen::Vector3f>& faceScratch, vtkPoints* drawn, vtkFloatArray* normals);

  /// Heap bytes held: the sums of the normals (12 per vertex) and, once a drag was followed,
  /// beta_v and W_v (16 more) and the double weights they were made from (8 more), kept for the
  /// next drag's first step (fresh buffers of 24 bytes per vertex cost it page faults: 240 MB at
  /// 10M vertices).
  std::size_t memoryBytes() const {
    return sizeof(float) * std::size_t(sums_.size() + motion_.size() + beta_.size()) +
           sizeof(double) * std::size_t(weights_.size());
  }

 private:
  // No motion followed (the buffers stay for the next one).
  void stopFollowing();

  bool active_ = false;
  std::uint64_t baseRevision_ = 0;
  widgets::WidgetId lattice_;
  Eigen::Index controlPoint_ = -1;
  // The revision (SceneDeformer::revision) of the points whose normals' sums_ holds, and the
  // displacement D of the motion at them (0 at the motion's base).
  std::uint64_t sumsRevision_ = 0;
  bool sumsValid_ = false;
  Eigen::Vector3d startDisplacement_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d shownDisplacement_ = Eigen::Vector3d::Zero();  // D(t') of the points shown
  // Columns (x, y, z: the per-step loop streams and vectorises over them):
  Eigen::MatrixX3f sums_;    // N_v at sumsRevision_, the unnormalised area-weighted normals
  Eigen::MatrixX3f motion_;  // W_v
  Eigen::VectorXf beta_;     // beta_v, the moved control point's weights
  Eigen::VectorXd weights_;  // beta_v in double (SceneDeformer::controlWeights), the first step's W_v from them
};

/// Area-weighted vertex normals of `points` (#points x 3) with triangles `triangles` (vf: the
/// triangles of each vertex): each triangle's area vector (b - a) x (c - a) in double, stored as
/// float in `faceScratch`, summed per vertex in float into the rows of `sums` (#points x 3,
/// resized) and normalised into `normals` (+z where the sum is 0); `points` also written into
/// `drawn` as float32 relative to `origin` (object_arrays::setFloatPoints). The bits SceneView
/// draws for a shaded surface outside a followed drag.
void exactNormals(const Eigen::MatrixX3i& triangles, const scene_view_shapes::VertexFaces& vf,
                  const Eigen::MatrixX3d& points, const Eigen::Vector3d& origin,
                  std::vector<Eigen::Vector3f>& faceScratch, Eigen::MatrixX3f& sums, vtkPoints* drawn,
                  vtkFloatArray* normals);

}  // namespace ffdkit::app
