#include "ffdkit/scenes/scene_deformer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "ffdkit/ffd/embedding.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/scene_file.h"
#include "scenes_test_support.h"

namespace ffdkit::scenes {
namespace {
using test_support::kExamples;

AttachOptions withCounts(int l, int m, int n) {
  AttachOptions options;
  options.counts = {l, m, n};
  return options;
}

Scene sphereScene() {
  Scene scene;
  SceneObject sphere;
  sphere.name = "sphere";
  sphere.source = PrimitiveOptions{.kind = PrimitiveKind::Sphere, .resolution = 16};
  sphere.mesh = buildObjectMesh(sphere.source, ".");
  scene.addObject(sphere);
  return scene;
}

TEST(SceneDeformer, AnObjectWithNoLatticeKeepsItsPoints) {
  const Scene scene = sphereScene();
  SceneDeformer deformer;
  deformer.update(scene);
  EXPECT_EQ(deformer.points("sphere"), scene.objects()[0].mesh.points);
}

TEST(SceneDeformer, AttachedLatticeAtRestReproducesThePoints) {
  Scene scene = sphereScene();
  attachNewLattice(scene, {"sphere"}, withCounts(4, 3, 5));
  SceneDeformer deformer;
  deformer.update(scene);
  EXPECT_LE((deformer.points("sphere") - scene.objects()[0].mesh.points).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(SceneDeformer, MovingEveryControlPointAffinelyMovesTheObjectAffinely) {
  Scene scene = sphereScene();
  const auto lattice = attachNewLattice(scene, {"sphere"}, withCounts(3, 3, 3));
  SceneDeformer deformer;
  deformer.update(scene);
  // An affine map of the lattice's local space, applied to every control point.
  Eigen::Affine3d local = Eigen::Translation3d(0.1, -0.2, 0.3) * Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()) *
                          Eigen::Scaling(1.2, 0.9, 1.1);
  Eigen::MatrixX3d points = scene.widgets.controlPoints(lattice);
  for (Eigen::Index i = 0; i < points.rows(); ++i) points.row(i) = (local * Eigen::Vector3d(points.row(i))).transpose();
  scene.widgets.setControlPoints(lattice, points);
  deformer.update(scene);  // an edit: incremental
  const Eigen::Affine3d frame = scene.widgets.latticeFrame(lattice);
  const Eigen::Affine3d world = frame * local * frame.inverse();
  const Eigen::MatrixX3d& deformed = deformer.points("sphere");
  for (Eigen::Index i = 0; i < deformed.rows(); ++i) {
    const Eigen::Vector3d expected = world * Eigen::Vector3d(scene.objects()[0].mesh.points.row(i));
    EXPECT_LE((Eigen::Vector3d(deformed.row(i)) - expected).norm(), 1e-12) << "point " << i;
  }
  EXPECT_EQ(deformer.lastStats().reembeddedStages, 0) << "an edit of control points must not re-embed";
}

TEST(SceneDeformer, DetachRestoresTheObjectsOwnPoints) {
  Scene scene = sphereScene();
  AttachOptions named;
  named.latticeName = "box";
  const auto lattice = attachNewLattice(scene, {"sphere"}, named);
  Eigen::MatrixX3d points = scene.widgets.controlPoints(lattice);
  points.col(2) *= 2.0;
  scene.widgets.setControlPoints(lattice, points);
  SceneDeformer deformer;
  deformer.update(scene);
  EXPECT_GT((deformer.points("sphere") - scene.objects()[0].mesh.points).cwiseAbs().maxCoeff(), 0.1);
  scene.detach(lattice, "sphere");
  deformer.update(scene);
  EXPECT_EQ(deformer.points("sphere"), scene.objects()[0].mesh.points);
  EXPECT_THROW(scene.detach(lattice, "sphere"), std::invalid_argument);
}

// takePoints hands over what points() gives; the object is then forgotten, and the next run
// builds it again to the same bits. Through a two-stage tree, so the output is the child's.
TEST(SceneDeformer, TakePointsHandsOverThePointsAndTheNextRunRebuildsTheObject) {
  const Scene scene = readScene(kExamples / "hierarchy");
  const std::string name = scene.objects().at(0).name;
  SceneDeformer reference;
  reference.finishGesture(scene);
  const Eigen::MatrixX3d expected = reference.points(name);
  ASSERT_GT((expected - scene.objects().at(0).mesh.points).cwiseAbs().maxCoeff(), 0.05) << "the sample deforms";
  SceneDeformer deformer;
  deformer.finishGesture(scene);
  EXPECT_EQ(deformer.takePoints(name), expected);
  EXPECT_THROW((void)deformer.points(name), std::invalid_argument);
  EXPECT_THROW((void)deformer.takePoints(name), std::invalid_argument);
  deformer.finishGesture(scene);
  EXPECT_EQ(deformer.points(name), expected);
  EXPECT_EQ(deformScene(scene).at(name), expected);
  // An object no lattice deforms: its own points.
  const Scene plain = sphereScene();
  deformer.update(plain);
  EXPECT_EQ(deformer.takePoints("sphere"), plain.objects()[0].mesh.points);
}

// finishGestureTakingPoints gives finishGesture's points bit for bit; the objects' points move
// into the pipelines (Pipeline.AdoptingTakesThePointsOver...: no copy), the meshes keep their faces.
TEST(SceneDeformer, FinishGestureTakingPointsMovesTheObjectsPointsIntoThePipelines) {
  Scene scene = readScene(kExamples / "hierarchy");
  const SceneObject& object = scene.objects().at(0);
  const std::string name = object.name;
  const Eigen::MatrixX3i faces = object.mesh.triangles;
  SceneDeformer reference;
  reference.finishGesture(scene);
  const Eigen::MatrixX3d expected = reference.points(name);
  SceneDeformer deformer;
  deformer.finishGestureTakingPoints(scene);
  EXPECT_EQ(scene.objects().at(0).mesh.points.rows(), 0);
  EXPECT_EQ(scene.objects().at(0).mesh.triangles, faces);
  EXPECT_EQ(deformer.lastStats().deformedPoints, expected.rows());
  EXPECT_EQ(deformer.takePoints(name), expected);
}

TEST(SceneDeformer, HierarchyRunsParentThenChild) {
  // Fig. 6-9 sample: the parent's top face lifted by 0.2 stretches z by 1.2; the child lattice
  // straddles that face and its bottom front edge is pushed (child-push 0.15), so the top of the
  // column runs through both. Every point must be the child's map of the parent's map: inside
  // the child's box the child's trilinear map, beyond its falloff (0.5 of its size) the parent's
  // alone.
  const Scene scene = readScene(kExamples / "hierarchy");
  const auto deformed = deformScene(scene);
  const SceneObject& column = scene.objects().at(0);
  const Eigen::MatrixX3d& out = deformed.at(column.name);
  const ffd::Lattice parent = scene.widgets.ffdLattice(scene.widgets.find("parent"));
  const ffd::Lattice child = scene.widgets.ffdLattice(scene.widgets.find("child"));
  ASSERT_EQ(child.outsidePolicy(), ffd::OutsidePolicy::falloff(0.5));
  Eigen::Index inChild = 0, parentOnly = 0;
  double childMotion = 0.0;
  for (Eigen::Index i = 0; i < out.rows(); ++i) {
    const Eigen::Vector3d q = column.mesh.points.row(i);
    const Eigen::Vector3d local = parent.frame().inverse() * q;
    ASSERT_TRUE((local.array() >= 0.0).all() && (local.array() <= 1.0).all()) << "the column lies in the parent";
    const Eigen::Vector3d afterParent = parent.frame() * parent.evaluate(local);
    const Eigen::Vector3d c = child.frame().inverse() * afterParent;
    const double outside = (c.array() - c.array().min(1.0).max(0.0)).matrix().norm();
    if (outside == 0.0) {
      ++inChild;
      const Eigen::Vector3d expected = child.frame() * child.evaluate(c);
      EXPECT_LE((Eigen::Vector3d(out.row(i)) - expected).norm(), 1e-9) << "point " << i << " at " << q.transpose();
      childMotion = std::max(childMotion, (expected - afterParent).norm());
    } else if (outside > 0.5) {
      ++parentOnly;
      EXPECT_LE((Eigen::Vector3d(out.row(i)) - afterParent).norm(), 1e-9) << "point " << i << " at " << q.transpose();
    }
  }
  // The top of the column is in the child, and child-push moves it visibly (its bottom front
  // edge moves 0.15; the column's front top rim is near it).
  EXPECT_GT(inChild, out.rows() / 10);
  EXPECT_GT(parentOnly, out.rows() / 10);
  EXPECT_GT(childMotion, 0.05);
}

// The points a GestureMotion stands for: base + sum_c weight_c * displacement_c.
Eigen::MatrixX3d followMotion(const SceneDeformer& deformer, const std::string& object, const Eigen::MatrixX3d& base,
                              const GestureMotion& motion) {
  Eigen::MatrixX3d out = base;
  for (std::size_t c = 0; c < motion.controlPoints.size(); ++c)
    out += deformer.controlWeights(object, motion.controlPoints[c]) * motion.displacements.row(Eigen::Index(c));
  return out;
}

TEST(SceneDeformer, AGestureMotionIsLinearInTheControlPointsTheLastStageMovedByDeltas) {
  Scene scene = sphereScene();
  const auto lattice = attachNewLattice(scene, {"sphere"}, withCounts(4, 4, 4));
  scene.widgets.setLatticeFrame(lattice, Eigen::Affine3d(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())) *
                                             scene.widgets.latticeFrame(lattice));
  SceneDeformer deformer;
  deformer.update(scene);
  EXPECT_FALSE(deformer.gestureMotion("sphere"));
  EXPECT_FALSE(deformer.gestureMotion("no such object"));
  const Eigen::MatrixX3d base = deformer.points("sphere");
  const std::uint64_t baseRevision = deformer.revision("sphere");
  const Eigen::Affine3d frame = scene.widgets.latticeFrame(lattice);
  Eigen::MatrixX3d control = scene.widgets.controlPoints(lattice);
  const Eigen::Index f = 1 + 4 * (2 + 4 * 3), g = 2 + 4 * (1 + 4 * 2);
  // Three steps of one control point, then a second one joins.
  Eigen::Vector3d moved = Eigen::Vector3d::Zero();
  for (int step = 1; step <= 4; ++step) {
    const Eigen::Vector3d dP(0.02 * step, -0.01, 0.03);
    moved += dP;
    control.row(f) += dP.transpose();
    if (step == 4) control(g, 2) += 0.1;
    scene.widgets.setControlPoints(lattice, control);
    deformer.updateGesture(scene, lattice);
    ASSERT_EQ(deformer.lastStats().deltaStages, 1);
    const std::optional<GestureMotion> motion = deformer.gestureMotion("sphere");
    ASSERT_TRUE(motion) << "step " << step;
    EXPECT_EQ(motion->baseRevision, baseRevision);
    EXPECT_EQ(motion->lattice, lattice);
    ASSERT_EQ(motion->controlPoints.size(), step == 4 ? 2u : 1u);
    const Eigen::Index at = step == 4 ? 1 : 0;  // by flat index: g < f
    EXPECT_EQ(motion->controlPoints[std::size_t(at)], f);
    EXPECT_LE((Eigen::Vector3d(motion->displacements.row(at)) - frame.linear() * moved).norm(), 1e-15);
    if (step == 4) {
      EXPECT_EQ(motion->controlPoints[0], g);
      EXPECT_LE((Eigen::Vector3d(motion->displacements.row(0)) - frame.linear() * Eigen::Vector3d(0, 0, 0.1)).norm(), 1e-15);
    }
    EXPECT_LE((followMotion(deformer, "sphere", base, *motion) - deformer.points("sphere")).cwiseAbs().maxCoeff(), 1e-14);
  }
  // The end of the gesture is the next base: nothing to follow.
  deformer.finishGesture(scene);
  EXPECT_FALSE(deformer.gestureMotion("sphere"));
  control(f, 0) += 0.05;
  scene.widgets.setControlPoints(lattice, control);
  deformer.update(scene, lattice);  // an exact update is a base too
  EXPECT_FALSE(deformer.gestureMotion("sphere"));
}

// Every gesture step is evaluated where it is reported (no step is left for a read of the
// points to apply): each moves the revision and the motion, points() is a pure read (reading
// twice moves nothing), and after several steps the points are those of an exact evaluation of
// the same scene, to the rounding of the delta steps; the release is bit for bit exact.
TEST(SceneDeformer, EveryGestureStepIsEvaluatedWhereItIsReportedAndPointsIsAPureRead) {
  Scene scene = sphereScene();
  const auto lattice = attachNewLattice(scene, {"sphere"}, withCounts(4, 4, 4));
  SceneDeformer deformer;
  deformer.update(scene);
  const Eigen::Index rows = scene.objects().front().mesh.points.rows();
  Eigen::MatrixX3d control = scene.widgets.controlPoints(lattice);
  const Eigen::Index f = 1 + 4 * (2 + 4 * 1);
  std::uint64_t revision = deformer.revision("sphere");
  Eigen::Vector3d moved = Eigen::Vector3d::Zero();
  // A reader's reference taken before the gesture shows every step without another call (a step
  // left for points() to apply would leave it behind from the second step on).
  const Eigen::MatrixX3d& held = deformer.points("sphere");
  for (int step = 1; step <= 6; ++step) {
    const Eigen::Vector3d dP(0.03, -0.02 * step, 0.01);
    moved += dP;
    control.row(f) += dP.transpose();
    scene.widgets.setControlPoints(lattice, control);
    deformer.updateGesture(scene, lattice);
    EXPECT_EQ(deformer.lastStats().deltaStages, 1) << "step " << step;
    EXPECT_GT(deformer.revision("sphere"), revision) << "step " << step;
    revision = deformer.revision("sphere");
    const std::optional<GestureMotion> motion = deformer.gestureMotion("sphere");
    ASSERT_TRUE(motion) << "step " << step;
    ASSERT_EQ(motion->controlPoints.size(), 1u);
    EXPECT_LE((Eigen::Vector3d(motion->displacements.row(0)) - scene.widgets.latticeFrame(lattice).linear() * moved).norm(), 1e-14);
    EXPECT_EQ(deformer.pointCount("sphere"), rows);
    SceneDeformer exact;
    exact.update(scene);
    EXPECT_LE((held - exact.points("sphere")).cwiseAbs().maxCoeff(), 1e-13) << "step " << step;
    EXPECT_EQ(&deformer.points("sphere"), &held);
  }
  SceneDeformer fresh;
  fresh.update(scene);
  const std::uint64_t evaluations = deformer.totals().evaluations;
  const Eigen::MatrixX3d read = deformer.points("sphere");
  EXPECT_EQ(deformer.revision("sphere"), revision);  // reading does not move the points
  EXPECT_EQ(deformer.totals().evaluations, evaluations);
  EXPECT_GT((read - scene.objects().front().mesh.points).cwiseAbs().maxCoeff(), 0.01);
  EXPECT_LE((read - fresh.points("sphere")).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_EQ(deformer.points("sphere"), read);  // a second read applies nothing more
  deformer.finishGesture(scene);
  EXPECT_EQ(deformer.points("sphere"), fresh.points("sphere"));
}

TEST(SceneDeformer, AGestureMotionIsOnlyFollowedThroughTheLastStage) {
  // Fig. 6-9: parent, then child. Dragging the child (the last stage) is linear in its control
  // points; dragging the parent moves the child's input, which the child evaluates again.
  Scene scene = readScene(kExamples / "hierarchy");
  const std::string object = scene.objects().at(0).name;
  const auto parent = scene.widgets.find("parent");
  const auto child = scene.widgets.find("child");
  SceneDeformer deformer;
  deformer.update(scene);
  const Eigen::MatrixX3d base = deformer.points(object);
  Eigen::MatrixX3d control = scene.widgets.controlPoints(child);
  control(0, 0) -= 0.1;
  scene.widgets.setControlPoints(child, control);
  deformer.updateGesture(scene, child);
  const std::optional<GestureMotion> motion = deformer.gestureMotion(object);
  ASSERT_TRUE(motion);
  EXPECT_EQ(motion->lattice, child);
  ASSERT_EQ(motion->controlPoints.size(), 1u);
  EXPECT_LE((followMotion(deformer, object, base, *motion) - deformer.points(object)).cwiseAbs().maxCoeff(), 1e-14);
  deformer.finishGesture(scene);
  Eigen::MatrixX3d top = scene.widgets.controlPoints(parent);
  top(top.rows() - 1, 2) += 0.1;
  scene.widgets.setControlPoints(parent, top);
  deformer.updateGesture(scene, parent);
  EXPECT_FALSE(deformer.gestureMotion(object));
}

// A caller that follows a one-control-point motion itself (EvaluationRequest::followed: the view's
// normals and points) lets the delta passes of the steps after the first wait: each such step
// moves the revision and the motion (what the follower reads) but not the points, which say so
// (PointCoverage::Motion, points() throws); an exact reader gets them at once (all the waiting
// steps in one delta pass), any step that moves another control point evaluates, and the end of
// the gesture is bit for bit that of a deformer that evaluated every step.
TEST(SceneDeformer, AFollowedMotionOfOneControlPointLeavesItsDeltaPassesWaitingUntilThePointsAreRead) {
  Scene scene = sphereScene();
  const auto lattice = attachNewLattice(scene, {"sphere"}, withCounts(4, 4, 4));
  const ObjectId sphere = scene.objects().front().id;
  SceneDeformer follower, plain;  // `plain` is never asked to let a step wait
  follower.evaluate(scene);
  plain.evaluate(scene);
  const Eigen::Index n = follower.pointCount(sphere);
  EvaluationRequest request;
  request.followed.insert(sphere);
  follower.beginGesture(lattice);
  plain.beginGesture(lattice);
  Eigen::MatrixX3d control = scene.widgets.controlPoints(lattice);
  const Eigen::Index f = 1 + 4 * (2 + 4 * 1), g = 2 + 4 * (1 + 4 * 2);
  const Eigen::Matrix3d linear = scene.widgets.latticeFrame(lattice).linear();
  Eigen::Vector3d moved = Eigen::Vector3d::Zero();
  // The exact points of the scene as it is now, from a deformer of their own.
  const auto exactNow = [&scene] { return deformScene(scene).at("sphere"); };
  const auto step = [&](const Eigen::Vector3d& dP) {
    moved += dP;
    control.row(f) += dP.transpose();
    scene.widgets.setControlPoints(lattice, control);
    EXPECT_TRUE(plain.evaluate(scene));
  };
  for (int k = 1; k <= 5; ++k) {
    step(Eigen::Vector3d(0.02, -0.01 * k, 0.015));
    const std::uint64_t revision = follower.revision(sphere);
    const std::uint64_t deformed = follower.totals().deformedPoints;
    EXPECT_TRUE(follower.evaluate(scene, request));
    EXPECT_GT(follower.revision(sphere), revision) << "step " << k;
    const std::optional<GestureMotion> motion = follower.gestureMotion(sphere);
    ASSERT_TRUE(motion) << "step " << k;
    ASSERT_EQ(motion->controlPoints, std::vector<Eigen::Index>{f});
    EXPECT_LE((Eigen::Vector3d(motion->displacements.row(0)) - linear * moved).norm(), 1e-15) << "step " << k;
    if (k == 1) {  // the first step of the motion evaluates: nothing to follow from yet
      EXPECT_EQ(follower.lastStats().deltaStages, 1);
      EXPECT_EQ(follower.lastStats().waitingObjects, 0);
      EXPECT_EQ(follower.coverage(sphere), PointCoverage::Full);
      continue;
    }
    EXPECT_EQ(follower.lastStats().deltaStages, 0) << "step " << k;
    EXPECT_EQ(follower.lastStats().waitingObjects, 1) << "step " << k;
    EXPECT_EQ(follower.totals().deformedPoints, deformed) << "step " << k;
    ASSERT_EQ(follower.coverage(sphere), PointCoverage::Motion);
    EXPECT_THROW((void)follower.points(sphere), PointsNotEvaluated);
    EXPECT_THROW((void)follower.takePoints(sphere), PointsNotEvaluated);
    EXPECT_THROW((void)follower.subsetPoints(sphere), PointsNotEvaluated);
    Eigen::VectorXd weights;
    EXPECT_TRUE(follower.gestureWeights(sphere, f, weights));  // kept by the first step's delta pass
    EXPECT_FALSE(follower.evaluate(scene, request)) << "step " << k;  // nothing changed, the same request
  }
  // An exact reader during the gesture: the waiting steps in one delta pass, now.
  const std::uint64_t revision = follower.revision(sphere);
  EXPECT_TRUE(follower.evaluate(scene));
  EXPECT_EQ(follower.lastStats().deltaStages, 1);
  EXPECT_EQ(follower.lastStats().deformedPoints, n);
  EXPECT_EQ(follower.coverage(sphere), PointCoverage::Full);
  EXPECT_GT(follower.revision(sphere), revision);
  EXPECT_LE((follower.points(sphere) - exactNow()).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_FALSE(follower.evaluate(scene, request));  // the full points cover a follower's request too
  ASSERT_TRUE(follower.gestureMotion(sphere));  // the motion goes on from the same base
  step(Eigen::Vector3d(0.01, 0.01, -0.02));
  EXPECT_TRUE(follower.evaluate(scene, request));
  EXPECT_EQ(follower.lastStats().waitingObjects, 1);
  EXPECT_EQ(follower.coverage(sphere), PointCoverage::Motion);
  // A second control point joins: the motion is no longer one control point's; evaluated.
  control(g, 2) += 0.05;
  step(Eigen::Vector3d(0.0, 0.02, 0.0));
  EXPECT_TRUE(follower.evaluate(scene, request));
  EXPECT_EQ(follower.lastStats().waitingObjects, 0);
  EXPECT_EQ(follower.lastStats().deltaStages, 1);
  EXPECT_EQ(follower.coverage(sphere), PointCoverage::Full);
  ASSERT_TRUE(follower.gestureMotion(sphere));
  EXPECT_EQ(follower.gestureMotion(sphere)->controlPoints.size(), 2u);
  EXPECT_LE((follower.points(sphere) - exactNow()).cwiseAbs().maxCoeff(), 1e-13);
  step(Eigen::Vector3d(0.0, 0.0, 0.01));
  EXPECT_TRUE(follower.evaluate(scene, request));
  EXPECT_EQ(follower.lastStats().waitingObjects, 0);
  // The end of the gesture: exact, bit for bit what the deformer that evaluated every step gives.
  follower.endGesture();
  plain.endGesture();
  EXPECT_TRUE(follower.evaluate(scene, request));
  EXPECT_TRUE(plain.evaluate(scene));
  EXPECT_EQ(follower.coverage(sphere), PointCoverage::Full);
  EXPECT_TRUE(follower.points(sphere) == plain.points(sphere));
  EXPECT_TRUE(follower.points(sphere) == exactNow());
}

// A followed motion that comes back to where the deformer last evaluated it (a drag that returns
// to the position of its first step) is still that motion: a step there waits too (its delta pass
// is empty), and a reader then finds the points of that first step, still following.
TEST(SceneDeformer, AFollowedMotionBackAtItsLastEvaluatedPositionIsStillFollowed) {
  Scene scene = sphereScene();
  const auto lattice = attachNewLattice(scene, {"sphere"}, withCounts(4, 4, 4));
  const ObjectId sphere = scene.objects().front().id;
  SceneDeformer follower;
  follower.evaluate(scene);
  EvaluationRequest request;
  request.followed.insert(sphere);
  follower.beginGesture(lattice);
  const Eigen::Index f = 2 + 4 * (1 + 4 * 2);
  const Eigen::MatrixX3d rest = scene.widgets.controlPoints(lattice);
  const auto moveTo = [&](double x) {
    Eigen::MatrixX3d control = rest;
    control(f, 0) += x;
    scene.widgets.setControlPoints(lattice, control);
    return follower.evaluate(scene, request);
  };
  EXPECT_TRUE(moveTo(0.1));  // the first step: evaluated
  EXPECT_EQ(follower.lastStats().deltaStages, 1);
  const Eigen::MatrixX3d first = follower.points(sphere);
  for (const double x : {0.2, 0.1, 0.3, 0.1}) {
    const std::uint64_t revision = follower.revision(sphere);
    EXPECT_TRUE(moveTo(x));
    EXPECT_EQ(follower.lastStats().waitingObjects, 1) << "at " << x;
    EXPECT_GT(follower.revision(sphere), revision) << "at " << x;
    ASSERT_TRUE(follower.gestureMotion(sphere));
    EXPECT_EQ(follower.gestureMotion(sphere)->controlPoints, std::vector<Eigen::Index>{f});
  }
  const std::uint64_t revision = follower.revision(sphere);
  EXPECT_TRUE(follower.evaluate(scene));  // a reader, with the motion back at the first step's position
  EXPECT_GT(follower.revision(sphere), revision);  // the follower showed other positions since
  EXPECT_TRUE(follower.points(sphere) == first);
  ASSERT_TRUE(follower.gestureMotion(sphere));  // the same motion, from the same base
  EXPECT_EQ(follower.gestureMotion(sphere)->controlPoints, std::vector<Eigen::Index>{f});
  EXPECT_TRUE(moveTo(0.25));
  EXPECT_EQ(follower.lastStats().waitingObjects, 1);
  follower.endGesture();
  EXPECT_TRUE(follower.evaluate(scene));
  EXPECT_TRUE(follower.points(sphere) == deformScene(scene).at("sphere"));
}

// The end of a gesture whose last steps waited is exact too, and a followed object that moves
// through another stage than its last (a parent lattice) is evaluated, not left waiting.
TEST(SceneDeformer, AFollowedMotionWaitsOnlyForItsLastStageAndItsReleaseIsExact) {
  Scene scene = readScene(kExamples / "hierarchy");
  const SceneObject& object = scene.objects().at(0);
  const ObjectId id = object.id;
  const std::string name = object.name;
  const auto parent = scene.widgets.find("parent");
  const auto child = scene.widgets.find("child");
  EvaluationRequest request;
  request.followed.insert(id);
  SceneDeformer follower;
  follower.evaluate(scene);
  follower.beginGesture(child);
  Eigen::MatrixX3d control = scene.widgets.controlPoints(child);
  for (int k = 1; k <= 3; ++k) {
    control(0, 0) -= 0.05;
    scene.widgets.setControlPoints(child, control);
    EXPECT_TRUE(follower.evaluate(scene, request));
    EXPECT_EQ(follower.lastStats().waitingObjects, k == 1 ? 0 : 1) << "step " << k;
  }
  follower.endGesture();
  EXPECT_TRUE(follower.evaluate(scene, request));
  EXPECT_EQ(follower.coverage(id), PointCoverage::Full);
  EXPECT_TRUE(follower.points(id) == deformScene(scene).at(name));
  // The parent moves during a gesture on the child: the child's input moved, no motion to follow.
  follower.beginGesture(parent);
  Eigen::MatrixX3d top = scene.widgets.controlPoints(parent);
  for (int k = 1; k <= 2; ++k) {
    top(top.rows() - 1, 2) += 0.05;
    scene.widgets.setControlPoints(parent, top);
    EXPECT_TRUE(follower.evaluate(scene, request));
    EXPECT_EQ(follower.lastStats().waitingObjects, 0) << "step " << k;
    EXPECT_EQ(follower.coverage(id), PointCoverage::Full);
    EXPECT_LE((follower.points(id) - deformScene(scene).at(name)).cwiseAbs().maxCoeff(), 1e-12);
  }
  follower.endGesture();
  EXPECT_TRUE(follower.evaluate(scene));
  EXPECT_TRUE(follower.points(id) == deformScene(scene).at(name));
}

TEST(SceneDeformer, CylindricalLatticeEmbedsTheWholeCylinderIncludingItsAxis) {
  // EFFD (Fig. 6-11): the cylinder lies inside its cylindrical lattice, caps and axis included.
  const Scene scene = readScene(kExamples / "cylinder-twist");
  SceneDeformer deformer;
  deformer.update(scene);
  EXPECT_EQ(deformer.lastStats().outsidePoints, 0);
  EXPECT_EQ(deformer.lastStats().failedPoints, 0);
  // The top cap is turned by the twist: its rim points moved, its centre stays on the axis.
  const SceneObject& cylinder = scene.objects().at(0);
  const Eigen::MatrixX3d& out = deformer.points(cylinder.name);
  for (Eigen::Index i = 0; i < out.rows(); ++i) {
    const Eigen::Vector3d q = cylinder.mesh.points.row(i);
    if (q.head<2>().norm() < 1e-12) {
      EXPECT_LE(Eigen::Vector2d(out(i, 0), out(i, 1)).norm(), 1e-9) << "axis point " << i;
    }
  }
}

TEST(SceneDeformer, EverySampleSceneDeformsToFinitePoints) {
  for (const char* name : {"default", "press", "vise", "mirror", "hierarchy", "cylinder-twist"}) {
    SCOPED_TRACE(name);
    Scene scene = readScene(kExamples / name);
    // The keyed samples store their first frame, the rest pose: frame 36 shows them moved.
    if (!scene.animation().channels.empty()) applyAnimationFrame(scene, 36);
    SceneDeformer deformer;
    deformer.update(scene);
    deformer.finishGesture(scene);
    EXPECT_EQ(deformer.lastStats().failedPoints, 0);
    for (const auto& object : scene.objects()) {
      const Eigen::MatrixX3d& points = deformer.points(object.name);
      EXPECT_TRUE(points.allFinite());
      EXPECT_GT((points - object.mesh.points).cwiseAbs().maxCoeff(), 1e-3) << "the sample should show a deformation";
    }
  }
}

// The hierarchy sample (a parent and a child lattice on one column) with the column replaced by
// n random points in its bounding box, plus a second object with a lattice of its own: progress
// then spans two objects and three stages, n points each.
Scene largeScene(Eigen::Index n) {
  Scene scene = readScene(kExamples / "hierarchy");
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  MeshData column = scene.objects().at(0).mesh;
  const Eigen::Vector3d lo = column.points.colwise().minCoeff();
  const Eigen::Vector3d hi = column.points.colwise().maxCoeff();
  column.points.resize(n, 3);
  for (Eigen::Index r = 0; r < n; ++r)
    for (int c = 0; c < 3; ++c) column.points(r, c) = lo[c] + (hi[c] - lo[c]) * U(rng);
  scene.setObjectMesh(scene.objects().at(0).name, std::move(column));
  SceneObject extra = scene.objects().at(0);
  extra.name = "extra";
  extra.mesh.points.col(0).array() += 2.0 * (hi[0] - lo[0]);
  scene.addObject(extra);
  AttachOptions box = withCounts(3, 3, 3);
  box.latticeName = "extra-box";
  const auto lattice = attachNewLattice(scene, {"extra"}, box);
  Eigen::MatrixX3d control = scene.widgets.controlPoints(lattice);
  control.col(2) += 0.1 * control.col(0).cwiseProduct(control.col(0));
  scene.widgets.setControlPoints(lattice, control);
  return scene;
}

void expectSamePoints(const SceneDeformer& a, const SceneDeformer& b, const Scene& scene) {
  for (const auto& object : scene.objects()) EXPECT_EQ(a.points(object.name), b.points(object.name)) << object.name;
}

TEST(SceneDeformerProgress, GoesFromZeroToOneOverEveryObjectAndStageOnTheCallingThread) {
  const Eigen::Index n = ffd::kEmbedProgressChunk + 3000;
  const Scene scene = largeScene(n);
  std::vector<double> fractions;
  bool otherThread = false;
  SceneDeformer deformer;
  const std::thread::id caller = std::this_thread::get_id();
  deformer.setProgress([&](double fraction) {
    fractions.push_back(fraction);
    otherThread = otherThread || std::this_thread::get_id() != caller;
    return true;
  });
  deformer.finishGesture(scene);
  EXPECT_FALSE(otherThread);
  ASSERT_GE(fractions.size(), 8u);  // 0, 2 calls per chunk end in 3 stages of 2 chunks, 1
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  for (std::size_t i = 1; i < fractions.size(); ++i) {
    EXPECT_GE(fractions[i], fractions[i - 1]) << "call " << i;
    EXPECT_LE(fractions[i], 1.0);
  }
  // A third of the work per stage: a value close to 1/3 and 2/3 is reported at each stage end.
  EXPECT_NE(std::find(fractions.begin(), fractions.end(), 1.0 / 3.0), fractions.end());
  EXPECT_EQ(deformer.lastStats().reembeddedStages, 3);
  EXPECT_GT(deformer.lastStats().embedSeconds, 0.0);
  EXPECT_LE(deformer.lastStats().embedSeconds, deformer.lastStats().seconds);

  // Nothing to embed: just 0 and 1.
  fractions.clear();
  deformer.update(scene);
  EXPECT_EQ(fractions, (std::vector<double>{0.0, 1.0}));
  EXPECT_EQ(deformer.lastStats().reembeddedStages, 0);
  EXPECT_EQ(deformer.lastStats().embedSeconds, 0.0);
}

TEST(SceneDeformerProgress, CancelAtAboutHalfLeavesADeformerWhoseNextRunIsExact) {
  const Eigen::Index n = ffd::kEmbedProgressChunk + 3000;
  const Scene scene = largeScene(n);
  SceneDeformer deformer;
  deformer.update(scene);  // some previous state, with different lattices
  Scene moved = scene;
  for (const char* name : {"parent", "extra-box"}) {  // the child follows the parent
    const auto lattice = moved.widgets.find(name);
    Eigen::Affine3d frame = moved.widgets.latticeFrame(lattice);
    frame.pretranslate(Eigen::Vector3d(0.01, 0.02, 0.0));
    moved.widgets.setLatticeFrame(lattice, frame);
  }
  const SceneDeformStats statsBefore = deformer.lastStats();
  std::vector<double> fractions;
  deformer.setProgress([&](double fraction) {
    fractions.push_back(fraction);
    return fraction < 0.5;
  });
  EXPECT_THROW(deformer.finishGesture(moved), ffd::Cancelled);
  ASSERT_FALSE(fractions.empty());
  EXPECT_GE(fractions.back(), 0.5);
  EXPECT_LT(fractions.back(), 1.0);
  EXPECT_EQ(deformer.lastStats().seconds, statsBefore.seconds) << "stats of the last completed run";

  deformer.setProgress({});
  deformer.finishGesture(moved);
  EXPECT_EQ(deformer.lastStats().reembeddedStages, 2) << "the parent's embedding was kept; the child's and the box's redone";
  SceneDeformer fresh;
  fresh.finishGesture(moved);
  expectSamePoints(deformer, fresh, moved);

  // The same through update() with an active lattice, cancelled right at the start.
  deformer.setProgress([](double) { return false; });
  Scene again = moved;
  const auto parent = again.widgets.find("parent");
  Eigen::Affine3d frame = again.widgets.latticeFrame(parent);
  frame.pretranslate(Eigen::Vector3d(0.0, 0.0, 0.01));
  again.widgets.setLatticeFrame(parent, frame);
  EXPECT_THROW(deformer.update(again, parent), ffd::Cancelled);
  expectSamePoints(deformer, fresh, moved);  // nothing changed yet
  deformer.setProgress({});
  deformer.update(again, parent);
  SceneDeformer fresh2;
  fresh2.update(moved);
  fresh2.update(again, parent);
  expectSamePoints(deformer, fresh2, again);
}

}  // namespace
}  // namespace ffdkit::scenes
