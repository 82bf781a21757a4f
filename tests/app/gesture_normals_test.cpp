// The view's normal passes (app/render/src/gesture_normals.h) give the bits of their scalar
// arithmetic in every vector form: exactNormals normalises a chunk of gathered sums four or eight
// at a time, and its normals must be, bit for bit, the sums' normalised one by one as written here.
// And a view that follows a drag asks the deformer to let its delta passes wait
// (SceneView::evaluationRequest, EvaluationRequest::followed) and draws what it draws when the
// deformer evaluates every step.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkRenderer.h>

#include "ffdkit/render/scene_view.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "gesture_normals.h"
#include "scene_view_shapes.h"

namespace ffdkit::app {
namespace {

// The scalar normalisation: 1 / sqrt(x^2 + y^2 + z^2) times the sum, +z for a zero sum.
Eigen::Vector3f normalised(float x, float y, float z) {
  const float inverse = 1.0f / std::sqrt(x * x + y * y + z * z);
  if (!(inverse < std::numeric_limits<float>::infinity())) return Eigen::Vector3f(0.0f, 0.0f, 1.0f);
  return Eigen::Vector3f(x * inverse, y * inverse, z * inverse);
}

TEST(GestureNormals, ExactNormalsAreTheScalarNormalisationOfTheirSumsBitForBit) {
  // Random triangles over 3001 random points (not a multiple of four or eight: the last few take
  // the scalar form) on sizes from 1e-3 to 1e3, and points in no triangle (zero sums: +z).
  std::mt19937 rng(39);
  for (const int n : {3001, 20011}) {  // the second on both cores
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::uniform_int_distribution<int> pick(0, n - 1 - n / 20);  // the last twentieth in no triangle
    Eigen::MatrixX3d points(n, 3);
    for (Eigen::Index i = 0; i < n; ++i)
      points.row(i) = std::pow(10.0, 3.0 * U(rng)) * Eigen::RowVector3d(U(rng), U(rng), U(rng));
    Eigen::MatrixX3i triangles(2 * n, 3);
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) triangles.row(t) << pick(rng), pick(rng), pick(rng);
    const scene_view_shapes::VertexFaces vf = scene_view_shapes::vertexFaces(triangles, n);
    const Eigen::Vector3d origin(0.25, -0.5, 2.0);
    std::vector<Eigen::Vector3f> scratch;
    Eigen::MatrixX3f sums;
    vtkNew<vtkPoints> drawn;
    vtkNew<vtkFloatArray> normals;
    exactNormals(triangles, vf, points, origin, scratch, sums, drawn, normals);
    ASSERT_EQ(sums.rows(), n);
    ASSERT_EQ(normals->GetNumberOfTuples(), n);
    const float* out = normals->GetPointer(0);
    const float* xyz = static_cast<const float*>(drawn->GetVoidPointer(0));
    int zero = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector3f expected = normalised(sums(i, 0), sums(i, 1), sums(i, 2));
      zero += sums.row(i).isZero(0.0);
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(out[3 * i + c], expected[c]) << "vertex " << i << " coordinate " << c;
        ASSERT_EQ(xyz[3 * i + c], static_cast<float>(points(i, c) - origin[c])) << "vertex " << i;
      }
    }
    EXPECT_GE(zero, n / 20);
    // And the sums are the triangles' area vectors summed (in double here): the normals of the mesh.
    Eigen::MatrixX3d reference = Eigen::MatrixX3d::Zero(n, 3);
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
      const Eigen::Vector3d a = points.row(triangles(t, 0)), b = points.row(triangles(t, 1)), c = points.row(triangles(t, 2));
      const Eigen::RowVector3d area = (b - a).cross(c - a).transpose();
      for (int k = 0; k < 3; ++k) reference.row(triangles(t, k)) += area;
    }
    for (Eigen::Index i = 0; i < n; ++i) {
      const double size = reference.row(i).norm();
      if (size == 0.0) continue;
      EXPECT_LT((sums.row(i).cast<double>() - reference.row(i)).norm(), 1e-5 * size + 1e-30) << "vertex " << i;
    }
  }
}

// A sphere in a 4x4x4 lattice drawn in full by a view (no level of detail), its deformer
// evaluated once per step: with the view's request (`follows`), or every object in full.
struct ViewedDrag {
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
  vtkNew<vtkRenderer> renderer;
  SceneView view{renderer};
  widgets::WidgetId lattice;
  scenes::ObjectId sphere;
  bool follows;

  explicit ViewedDrag(bool follows) : follows(follows) {
    scenes::SceneObject object;
    object.name = "sphere";
    object.source = scenes::PrimitiveOptions{.kind = scenes::PrimitiveKind::Sphere, .resolution = 40};
    object.mesh = scenes::buildObjectMesh(object.source, ".");
    sphere = scene.addObject(std::move(object));
    scenes::AttachOptions options;
    options.counts = {4, 4, 4};
    lattice = scenes::attachNewLattice(scene, {"sphere"}, options);
    view.setLevelOfDetail(LevelOfDetail{.enabled = false});
    deformer.evaluate(scene);
    view.show(scene, deformer);
  }
  // One change evaluated and drawn, as the window's frame does.
  void frame() {
    deformer.evaluate(scene, follows ? view.evaluationRequest(scene, deformer) : scenes::EvaluationRequest{});
    view.refresh(scene, deformer);
  }
  void moveControlPoint(Eigen::Index f, const Eigen::Vector3d& by) {
    Eigen::MatrixX3d control = scene.widgets.controlPoints(lattice);
    control.row(f) += by.transpose();
    scene.widgets.setControlPoints(lattice, control);
  }
};

TEST(GestureNormals, AFollowingViewLetsTheDeformersDeltaPassesWaitAndDrawsWhatAFullEvaluationDraws) {
  ViewedDrag follower(true), plain(false);
  const Eigen::Index f = 1 + 4 * (2 + 4 * 3), g = 2 + 4 * (1 + 4 * 3);
  for (ViewedDrag* d : {&follower, &plain}) d->deformer.beginGesture(d->lattice);
  const SceneViewStats before = follower.view.stats();
  const auto sameDrawing = [&] {
    return follower.view.objectPoints("sphere") == plain.view.objectPoints("sphere") &&
           follower.view.objectNormals("sphere") == plain.view.objectNormals("sphere");
  };
  for (int step = 1; step <= 6; ++step) {
    for (ViewedDrag* d : {&follower, &plain}) {
      d->moveControlPoint(f, Eigen::Vector3d(0.03, -0.02, 0.04 * step));
      d->frame();
    }
    // The first step reads the deformer's points (what the next ones follow from); the next ones
    // the motion only, and the deformer leaves its delta pass for later.
    EXPECT_EQ(follower.deformer.lastStats().waitingObjects, step == 1 ? 0 : 1) << "step " << step;
    EXPECT_EQ(follower.deformer.coverage(follower.sphere),
              step == 1 ? scenes::PointCoverage::Full : scenes::PointCoverage::Motion);
    EXPECT_EQ(plain.deformer.lastStats().waitingObjects, 0);
    EXPECT_EQ(follower.view.stats().followedNormals, before.followedNormals + step - 1) << "step " << step;
    // Both views follow the same motion from the same first step: the same bits.
    EXPECT_TRUE(sameDrawing()) << "step " << step;
  }
  // A second control point: the view recomputes from the deformer's points, which are evaluated.
  for (ViewedDrag* d : {&follower, &plain}) {
    d->moveControlPoint(g, Eigen::Vector3d(0.0, 0.05, 0.0));
    d->frame();
  }
  EXPECT_EQ(follower.deformer.lastStats().waitingObjects, 0);
  EXPECT_EQ(follower.deformer.coverage(follower.sphere), scenes::PointCoverage::Full);
  EXPECT_LT((follower.deformer.points(follower.sphere) - plain.deformer.points(plain.sphere)).cwiseAbs().maxCoeff(), 1e-13);
  // The release: exact, and drawn bit for bit as the view of the deformer that evaluated every step.
  for (ViewedDrag* d : {&follower, &plain}) {
    d->deformer.endGesture();
    d->frame();
  }
  EXPECT_TRUE(follower.deformer.points(follower.sphere) == plain.deformer.points(plain.sphere));
  EXPECT_TRUE(sameDrawing());
}

}  // namespace
}  // namespace ffdkit::app
