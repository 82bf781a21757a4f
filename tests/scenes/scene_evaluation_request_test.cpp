// What a consumer asks of evaluation (EvaluationRequest, SceneDeformer::evaluate): during a
// gesture an object requested at a subset of its points is evaluated there only, its full points
// wait (and say so: points() throws rather than hand out stale points), and the gesture's end, or
// an exact reader's request, evaluates the full mesh: bit for bit what a deformer that evaluated
// every step in full gives.
#include <algorithm>

#include <gtest/gtest.h>

#include "ffdkit/scenes/scene_deformer.h"
#include "scenes_test_support.h"

namespace ffdkit::scenes {
namespace {

struct RequestFixture {
  Scene scene;
  ObjectId ball;
  widgets::WidgetId lattice;
  std::vector<Eigen::Index> subset;  // every third point
  RequestFixture() {
    SceneObject object;
    object.name = "ball";
    object.source = PrimitiveOptions{.kind = PrimitiveKind::Sphere, .resolution = 24};
    object.mesh = buildObjectMesh(object.source, ".");
    ball = scene.addObject(std::move(object));
    AttachOptions options;
    options.counts = {4, 4, 4};
    lattice = attachNewLattice(scene, {"ball"}, options);
    for (Eigen::Index v = 0; v < scene.findObject(ball)->mesh.points.rows(); v += 3) subset.push_back(v);
  }
  EvaluationRequest request() const { return EvaluationRequest{{{ball, std::span<const Eigen::Index>(subset)}}}; }
  void moveCorner(double by) {
    Eigen::MatrixX3d control = scene.widgets.controlPoints(lattice);
    control.row(control.rows() - 1) += Eigen::RowVector3d(by, 0.5 * by, by);
    scene.widgets.setControlPoints(lattice, control);
  }
  // The exact deformed points at the subset, from a deformer of its own that evaluates the whole
  // scene once: the independent expectation of what the subset holds.
  Eigen::MatrixX3d exactAtSubset() const {
    const Eigen::MatrixX3d all = deformScene(scene).at("ball");
    Eigen::MatrixX3d out(static_cast<Eigen::Index>(subset.size()), 3);
    for (std::size_t i = 0; i < subset.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = all.row(subset[i]);
    return out;
  }
  double size() const { return scene.findObject(ball)->mesh.points.cwiseAbs().maxCoeff(); }
};

TEST(EvaluationRequest, AGestureEvaluatesARequestedSubsetOnlyAndItsEndTheFullMeshBitForBit) {
  RequestFixture f;
  SceneDeformer lod, plain;  // `plain` never gets a request: every step in full
  lod.evaluate(f.scene);
  plain.evaluate(f.scene);
  const Eigen::Index n = lod.pointCount(f.ball);
  const auto m = static_cast<Eigen::Index>(f.subset.size());
  lod.beginGesture(f.lattice);
  plain.beginGesture(f.lattice);
  const std::uint64_t fullBefore = lod.totals().deformedPoints;
  for (int step = 1; step <= 5; ++step) {
    f.moveCorner(0.05);
    const std::uint64_t revision = lod.revision(f.ball);
    EXPECT_TRUE(lod.evaluate(f.scene, f.request()));
    EXPECT_TRUE(plain.evaluate(f.scene));
    EXPECT_EQ(lod.lastStats().deformedPoints, 0) << "step " << step;  // the full mesh waits
    EXPECT_EQ(lod.lastStats().subsetPoints, m);
    EXPECT_EQ(plain.lastStats().deformedPoints, n);
    EXPECT_GT(lod.revision(f.ball), revision);
    ASSERT_EQ(lod.coverage(f.ball), PointCoverage::Subset);
    EXPECT_EQ(lod.subsetIndices(f.ball), f.subset);
    EXPECT_THROW((void)lod.points(f.ball), PointsNotEvaluated);
    EXPECT_THROW((void)lod.takePoints(f.ball), PointsNotEvaluated);
    const Eigen::MatrixX3d& at = lod.subsetPoints(f.ball);
    ASSERT_EQ(at.rows(), m);
    EXPECT_LT((at - f.exactAtSubset()).cwiseAbs().maxCoeff(), 1e-12 * f.size()) << "step " << step;
    EXPECT_FALSE(lod.evaluate(f.scene, f.request()));  // nothing changed, the same request
  }
  EXPECT_EQ(lod.totals().deformedPoints, fullBefore);
  lod.endGesture();
  plain.endGesture();
  EXPECT_TRUE(lod.evaluate(f.scene, f.request()));  // the request's subsets wait for gestures
  EXPECT_TRUE(plain.evaluate(f.scene));
  EXPECT_EQ(lod.coverage(f.ball), PointCoverage::Full);
  EXPECT_EQ(lod.lastStats().deformedPoints, n);
  EXPECT_THROW((void)lod.subsetPoints(f.ball), PointsNotEvaluated);
  EXPECT_TRUE(lod.points(f.ball) == plain.points(f.ball));  // bit for bit
  EXPECT_TRUE(lod.points(f.ball) == deformScene(f.scene).at("ball"));
}

TEST(EvaluationRequest, AnExactReaderDuringAGestureGetsTheFullMeshNow) {
  RequestFixture f;
  SceneDeformer deformer;
  deformer.evaluate(f.scene);
  deformer.beginGesture(f.lattice);
  f.moveCorner(0.1);
  EXPECT_TRUE(deformer.evaluate(f.scene, f.request()));
  ASSERT_EQ(deformer.coverage(f.ball), PointCoverage::Subset);
  const std::uint64_t revision = deformer.revision(f.ball);
  EXPECT_TRUE(deformer.evaluate(f.scene));  // an exact reader: nothing changed, but its points are due
  EXPECT_EQ(deformer.coverage(f.ball), PointCoverage::Full);
  EXPECT_EQ(deformer.lastStats().deformedPoints, deformer.pointCount(f.ball));
  EXPECT_GT(deformer.revision(f.ball), revision);
  const Eigen::MatrixX3d exact = deformScene(f.scene).at("ball");
  EXPECT_LT((deformer.points(f.ball) - exact).cwiseAbs().maxCoeff(), 1e-13 * f.size());  // a delta step
  // The full points cover any subset: the next frame's request finds nothing to do.
  EXPECT_FALSE(deformer.evaluate(f.scene, f.request()));
  deformer.endGesture();
  EXPECT_TRUE(deformer.evaluate(f.scene));
  EXPECT_TRUE(deformer.points(f.ball) == exact);
}

TEST(EvaluationRequest, ASubsetIsEmbeddedOnceAndKeptAcrossGestures) {
  RequestFixture f;
  SceneDeformer deformer;
  deformer.evaluate(f.scene);
  for (int gesture = 0; gesture < 2; ++gesture) {
    deformer.beginGesture(f.lattice);
    for (int step = 0; step < 3; ++step) {
      f.moveCorner(0.02);
      deformer.evaluate(f.scene, f.request());
      const bool first = gesture == 0 && step == 0;
      EXPECT_EQ(deformer.lastStats().latticesBuilt, first ? 1 : 0) << gesture << " " << step;
      EXPECT_EQ(deformer.lastStats().reembeddedStages, first ? 1 : 0) << gesture << " " << step;
    }
    deformer.endGesture();
    deformer.evaluate(f.scene);
    EXPECT_EQ(deformer.lastStats().reembeddedStages, 0);  // the full mesh's embedding stayed fresh
  }
}

TEST(EvaluationRequest, ALatticeMovedDuringAGestureReembedsTheSubsetOnlyUntilTheEnd) {
  RequestFixture f;
  SceneDeformer lod, plain;
  lod.evaluate(f.scene);
  plain.evaluate(f.scene);
  lod.beginGesture(f.lattice);
  plain.beginGesture(f.lattice);
  for (int step = 1; step <= 3; ++step) {
    Eigen::Affine3d frame = f.scene.widgets.latticeFrame(f.lattice);
    frame.translation() += Eigen::Vector3d(0.01, 0.0, 0.02);  // the lattice moves against the object
    f.scene.widgets.setLatticeFrame(f.lattice, frame);
    f.moveCorner(0.03);
    lod.evaluate(f.scene, f.request());
    plain.evaluate(f.scene);
    EXPECT_EQ(lod.lastStats().deformedPoints, 0);
    EXPECT_EQ(lod.lastStats().reembeddedStages, 1);  // the subset's, at its size
    EXPECT_LT((lod.subsetPoints(f.ball) - f.exactAtSubset()).cwiseAbs().maxCoeff(), 1e-12 * f.size()) << "step " << step;
  }
  lod.endGesture();
  plain.endGesture();
  lod.evaluate(f.scene, f.request());
  plain.evaluate(f.scene);
  EXPECT_TRUE(lod.points(f.ball) == plain.points(f.ball));
}

TEST(EvaluationRequest, OutsideAGestureEveryObjectIsEvaluatedInFull) {
  RequestFixture f;
  SceneDeformer deformer;
  f.moveCorner(0.1);
  EXPECT_TRUE(deformer.evaluate(f.scene, f.request()));
  EXPECT_EQ(deformer.coverage(f.ball), PointCoverage::Full);
  EXPECT_EQ(deformer.lastStats().subsetPoints, 0);
  EXPECT_TRUE(deformer.points(f.ball) == deformScene(f.scene).at("ball"));
}

TEST(EvaluationRequest, ASubsetThatIsNotIncreasingOrOutOfRangeIsRefusedWithItsEntry) {
  RequestFixture f;
  SceneDeformer deformer;
  deformer.evaluate(f.scene);
  deformer.beginGesture(f.lattice);
  f.moveCorner(0.1);
  const std::vector<Eigen::Index> backwards{4, 2};
  const std::vector<Eigen::Index> beyond{0, deformer.pointCount(f.ball)};
  for (const auto* bad : {&backwards, &beyond}) {
    try {
      deformer.evaluate(f.scene, EvaluationRequest{{{f.ball, std::span<const Eigen::Index>(*bad)}}});
      ADD_FAILURE() << "a bad subset was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("entry 1"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(deformer.evaluate(f.scene));  // the deformer stays usable
  EXPECT_EQ(deformer.coverage(f.ball), PointCoverage::Full);
}

}  // namespace
}  // namespace ffdkit::scenes
