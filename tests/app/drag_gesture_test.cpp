// The deformation during and after a drag (InteractionController -> SceneDeformer::updateGesture /
// finishGesture): every drag step updates the points by deltas (one term per point and moved
// control point), stays within 1e-12 of the lattice's size of an exact evaluation, builds no
// lattice and embeds nothing; the release evaluates them exactly again, bit for bit a fresh
// evaluation; undo and redo are exact and embed nothing.
#include <gtest/gtest.h>

#include "arrow_ray.h"
#include "drag_sphere.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/scenes/scene_deformer.h"

namespace ffdkit::app {
namespace {

using widgets::AffineKind;
using widgets::WidgetId;

struct Document {
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  InteractionController controller{scene, deformer, commands};
  std::string ball;
  WidgetId lattice, push;

  // A sphere in a 4x4x4 cubic lattice (one Bernstein cell: every point moves with every control
  // point), a translate widget on an inner point of its top layer (as bench_interaction).
  Document() {
    const testing::DragSphere made = testing::addDragSphere(controller, 48);
    ball = made.sphere;
    lattice = made.lattice;
    push = made.widget;
  }
  double latticeSize() const {
    const Eigen::MatrixX3d corners = scene.widgets.worldControlPoints(lattice);
    return (corners.colwise().maxCoeff() - corners.colwise().minCoeff()).norm();
  }
  // A ray down the widget's frame z through its arrow at `along` glyph sizes.
  widgets::Ray arrowRay(double along) const { return test::arrowRay(scene.widgets, push, along); }
  // The difference from a fresh exact evaluation of the scene as it is now.
  double errorFromExact() const {
    return (deformer.points(ball) - scenes::deformScene(scene).at(ball)).cwiseAbs().maxCoeff();
  }
  bool exact() const { return deformer.points(ball) == scenes::deformScene(scene).at(ball); }
};

void expectEmbeddedNothing(const scenes::SceneDeformer& deformer) {
  EXPECT_EQ(deformer.lastStats().latticesBuilt, 0);
  EXPECT_EQ(deformer.lastStats().reembeddedStages, 0);
}

TEST(DragGesture, StepsUpdateByDeltasWithinRoundingAndTheReleaseIsExact) {
  Document d;
  const double size = d.latticeSize();
  const Eigen::MatrixX3d start = d.deformer.points(d.ball);
  ASSERT_TRUE(d.exact());
  const double tolerance = 0.05 * d.scene.widgets.affineFrame(d.push).size;
  ASSERT_EQ(d.controller.press(d.arrowRay(0.5), tolerance), InteractionController::PressResult::Widget);
  double worst = 0.0;
  for (int step = 1; step <= 40; ++step) {
    d.controller.drag(d.arrowRay(0.5 + 0.03 * (step % 10) - 0.01 * (step % 7)));
    EXPECT_EQ(d.deformer.lastStats().deltaStages, 1) << step;
    expectEmbeddedNothing(d.deformer);
    worst = std::max(worst, d.errorFromExact());
  }
  EXPECT_LE(worst, 1e-12 * size);
  EXPECT_GT(worst, 0.0) << "deltas round differently from an exact evaluation (else this test proves nothing)";
  EXPECT_GT((d.deformer.points(d.ball) - start).cwiseAbs().maxCoeff(), 1e-3 * size) << "the drag moved nothing";

  d.controller.release();
  EXPECT_EQ(d.deformer.lastStats().deltaStages, 0);
  expectEmbeddedNothing(d.deformer);
  EXPECT_TRUE(d.exact()) << "released points differ from an exact evaluation by " << d.errorFromExact();
  const Eigen::MatrixX3d released = d.deformer.points(d.ball);

  d.commands.undo();
  expectEmbeddedNothing(d.deformer);
  EXPECT_TRUE(d.deformer.points(d.ball) == start);
  d.commands.redo();
  expectEmbeddedNothing(d.deformer);
  EXPECT_TRUE(d.deformer.points(d.ball) == released);
}

TEST(DragGesture, ACancelledDragIsExactlyTheStart) {
  Document d;
  const Eigen::MatrixX3d start = d.deformer.points(d.ball);
  const double tolerance = 0.05 * d.scene.widgets.affineFrame(d.push).size;
  ASSERT_EQ(d.controller.press(d.arrowRay(0.5), tolerance), InteractionController::PressResult::Widget);
  for (int step = 1; step <= 5; ++step) d.controller.drag(d.arrowRay(0.5 + 0.05 * step));
  d.controller.cancel();
  EXPECT_TRUE(d.deformer.points(d.ball) == start);
}

TEST(DragGesture, DirectManipulationStepsUpdateByDeltasAndTheReleaseIsExact) {
  Document d;
  const double size = d.latticeSize();
  // A ray onto an upper point of the sphere, from outside along its radius.
  const Eigen::MatrixX3d& points = d.deformer.points(d.ball);
  const Eigen::Vector3d centre = points.colwise().mean().transpose();
  Eigen::Index vertex = 0;
  (points.col(2).array() - 0.3 * (points.col(2).maxCoeff() - centre.z())).abs().minCoeff(&vertex);
  const Eigen::Vector3d target = points.row(vertex).transpose();
  const Eigen::Vector3d out = (target - centre).normalized();
  widgets::Ray ray{target + 3.0 * size * out, -out};
  ASSERT_TRUE(d.controller.pressObject(ray, 1e-3 * size).has_value());
  const Eigen::Vector3d side = out.cross(Eigen::Vector3d::UnitX()).normalized();
  for (int step = 1; step <= 10; ++step) {
    ray.origin += 0.01 * size * side;
    d.controller.drag(ray);
    EXPECT_EQ(d.deformer.lastStats().deltaStages, 1) << step;
    expectEmbeddedNothing(d.deformer);
    EXPECT_LE(d.errorFromExact(), 1e-12 * size) << step;
  }
  d.controller.release();
  EXPECT_TRUE(d.exact());
}

}  // namespace
}  // namespace ffdkit::app
