// One evaluation per change (SceneDeformer::evaluate): nothing changed, nothing evaluated; a
// change evaluates once; a gesture steps by deltas and its end gives the exact result, bit for bit
// that of a deformer that never saw the gesture.
#include <gtest/gtest.h>

#include "ffdkit/scenes/scene_deformer.h"
#include "scenes_test_support.h"

namespace ffdkit::scenes {
namespace {

struct EvaluationFixture {
  Scene scene;
  widgets::WidgetId lattice;
  EvaluationFixture() {
    SceneObject ball;
    ball.name = "ball";
    ball.source = PrimitiveOptions{.kind = PrimitiveKind::Sphere, .resolution = 16};
    ball.mesh = buildObjectMesh(ball.source, ".");
    scene.addObject(std::move(ball));
    AttachOptions options;
    options.counts = {4, 4, 4};
    lattice = attachNewLattice(scene, {"ball"}, options);
  }
  void moveCorner(double by) {
    Eigen::MatrixX3d control = scene.widgets.controlPoints(lattice);
    control.row(control.rows() - 1) += Eigen::RowVector3d(by, 0.5 * by, by);
    scene.widgets.setControlPoints(lattice, control);
  }
};

TEST(SceneEvaluation, EvaluatesOncePerChangeAndNotWithoutOne) {
  EvaluationFixture f;
  SceneDeformer deformer;
  EXPECT_TRUE(deformer.evaluate(f.scene));
  EXPECT_GT(deformer.lastStats().reembeddedStages, 0);
  EXPECT_FALSE(deformer.evaluate(f.scene));  // nothing changed
  EXPECT_FALSE(deformer.evaluate(f.scene));
  f.moveCorner(0.1);
  EXPECT_TRUE(deformer.evaluate(f.scene));
  EXPECT_EQ(deformer.lastStats().reembeddedStages, 0);
  EXPECT_FALSE(deformer.evaluate(f.scene));
  Camera camera = f.scene.camera();
  camera.position.x() += 1.0;
  f.scene.setCamera(camera);
  EXPECT_TRUE(deformer.evaluate(f.scene));  // the scene moved on (a run that finds nothing to do)
  EXPECT_EQ(deformer.lastStats().reembeddedStages, 0);
  deformer.setPrecision(ffd::Precision::Single);
  EXPECT_TRUE(deformer.evaluate(f.scene));  // another arithmetic: evaluated again
  deformer.reset();
  EXPECT_TRUE(deformer.evaluate(f.scene));
  const Scene copy = f.scene;
  EXPECT_TRUE(deformer.evaluate(copy));  // another scene
}

TEST(SceneEvaluation, AGestureStepsByDeltasAndItsEndIsExact) {
  EvaluationFixture f;
  SceneDeformer deformer;
  deformer.evaluate(f.scene);
  deformer.beginGesture(f.lattice);
  EXPECT_TRUE(deformer.inGesture());
  EXPECT_FALSE(deformer.evaluate(f.scene));  // beginning a gesture changes nothing
  for (int step = 1; step <= 4; ++step) {
    f.moveCorner(0.03);
    EXPECT_TRUE(deformer.evaluate(f.scene));
    EXPECT_EQ(deformer.lastStats().deltaStages, 1) << step;
    EXPECT_EQ(deformer.lastStats().reembeddedStages, 0) << step;
  }
  deformer.endGesture();
  EXPECT_TRUE(deformer.evaluate(f.scene));  // the exact result is due though nothing changed
  EXPECT_EQ(deformer.lastStats().deltaStages, 0);
  EXPECT_FALSE(deformer.evaluate(f.scene));
  SceneDeformer fresh;
  fresh.evaluate(f.scene);
  EXPECT_EQ(deformer.points("ball"), fresh.points("ball"));  // bit for bit
}

TEST(SceneEvaluation, AFailedEvaluationIsTriedAgain) {
  EvaluationFixture f;
  SceneDeformer deformer;
  deformer.evaluate(f.scene);
  deformer.setProgress([](double fraction) { return fraction < 1.0; });  // cancels at the end
  f.moveCorner(0.1);
  EXPECT_THROW(deformer.evaluate(f.scene), ffd::Cancelled);
  deformer.setProgress({});
  // The cancel came after the work (kept): the run counts as done.
  EXPECT_FALSE(deformer.evaluate(f.scene));
  deformer.setProgress([](double) { return false; });  // cancels before any work
  f.moveCorner(0.1);
  EXPECT_THROW(deformer.evaluate(f.scene), ffd::Cancelled);
  deformer.setProgress({});
  EXPECT_TRUE(deformer.evaluate(f.scene));
  SceneDeformer fresh;
  fresh.evaluate(f.scene);
  EXPECT_EQ(deformer.points("ball"), fresh.points("ball"));
}

}  // namespace
}  // namespace ffdkit::scenes
