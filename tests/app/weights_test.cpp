// Control-point weights in the interaction layer (headless): InteractionController::setWeight of
// several points is one undo step, and all or nothing; Keep Volume on a lattice whose weights were
// typed after the keep was turned on corrects with the weights as they are now, so each step of a
// G in the edit mode leaves the volume of the evaluated mesh (summed here by the divergence
// theorem) within 1e-12 of the kept one; a weight edit itself is no drag and changes the volume.
#include <gtest/gtest.h>

#include <cmath>

#include "divergence_volume.h"
#include "edit_test_document.h"

namespace ffdkit::app {
namespace {

using test::Document;
using test::f;
using widgets::WidgetId;

using ffdkit::test::divergenceVolume;

TEST(ControlPointWeights, SeveralPointsAreOneUndoStepAndAllOrNothing) {
  Document d;
  const WidgetId lattice = d.controller.newLattice({});
  const std::size_t steps = d.commands.position();
  d.controller.setWeight(lattice, {f(0, 0, 0), f(2, 2, 2), f(1, 1, 1)}, 0.5);
  EXPECT_EQ(d.commands.position(), steps + 1);
  Eigen::VectorXd expected = Eigen::VectorXd::Ones(27);
  expected[f(0, 0, 0)] = expected[f(2, 2, 2)] = expected[f(1, 1, 1)] = 0.5;
  EXPECT_EQ(d.scene.widgets.weights(lattice), expected);
  // A point past the end, a weight not > 0, no points: refused, nothing changed, no step.
  EXPECT_THROW(d.controller.setWeight(lattice, {f(1, 0, 0), 27}, 2.0), std::exception);
  EXPECT_THROW(d.controller.setWeight(lattice, {f(1, 0, 0)}, 0.0), std::exception);
  EXPECT_THROW(d.controller.setWeight(lattice, {}, 2.0), std::invalid_argument);
  EXPECT_EQ(d.scene.widgets.weights(lattice), expected);
  EXPECT_EQ(d.commands.position(), steps + 1);
  d.commands.undo();
  EXPECT_FALSE(d.scene.widgets.isRational(lattice));
  d.commands.redo();
  EXPECT_EQ(d.scene.widgets.weights(lattice), expected);
}

TEST(ControlPointWeights, KeepVolumeHoldsWithTheWeightsTypedAfterItWasTurnedOn) {
  Document d;
  d.controller.addPrimitive({});
  const WidgetId lattice = d.controller.newLattice({});
  d.controller.attachLattice(lattice, "sphere1");
  const scenes::ObjectId sphere = d.scene.objectId("sphere1");
  const Eigen::MatrixX3i& triangles = d.scene.findObject(sphere)->mesh.triangles;
  d.controller.setKeep(sphere, {true, false});
  const double kept = d.controller.shapeGuard().keptVolume(sphere);
  ASSERT_LE(std::abs(divergenceVolume(d.deformer.points(sphere), triangles) - kept) / kept, 1e-12);

  // Two points of the top layer weighted 3: the lattice is rational, the sphere bulges up.
  d.controller.setWeight(lattice, {f(1, 1, 2), f(2, 1, 2)}, 3.0);
  ASSERT_TRUE(d.scene.widgets.isRational(lattice));
  EXPECT_GT(std::abs(divergenceVolume(d.deformer.points(sphere), triangles) - kept) / kept, 1e-4);

  // G on the top middle point: every step brings the volume back to the kept one.
  d.edit.enter(lattice);
  d.edit.pickMany({f(1, 1, 2)}, SelectMode::Replace);
  const Eigen::Vector3d top = d.scene.widgets.worldControlPoints(lattice).row(f(1, 1, 2)).transpose();
  d.edit.beginModal(TransformMode::Move, test::downAt(top), test::kView);
  for (int step = 1; step <= 5; ++step) {
    d.edit.update(test::downAt(top + Eigen::Vector3d(0.03 * step, 0.02 * step, 0.0)), false);
    ASSERT_EQ(d.edit.guardSteps().size(), 1u);
    EXPECT_TRUE(d.edit.guardSteps()[0].problem.empty()) << d.edit.guardSteps()[0].problem;
    const double v = divergenceVolume(d.deformer.points(sphere), triangles);
    EXPECT_LE(std::abs(v - kept) / kept, 1e-12) << "step " << step << ": volume " << v << ", kept " << kept;
  }
  d.edit.confirm();
  EXPECT_LE(std::abs(divergenceVolume(d.deformer.points(sphere), triangles) - kept) / kept, 1e-12);
  EXPECT_EQ(d.scene.widgets.weights(lattice)[f(2, 1, 2)], 3.0);
}

}  // namespace
}  // namespace ffdkit::app
