// Keep Volume during a direct-manipulation drag of an object point (headless): the grabbed point
// stays on the pointer and the volume (summed here by the divergence theorem over the evaluated
// mesh) stays within 1e-12 of the start at every step; one undo step restores the start.
#include <gtest/gtest.h>

#include <cmath>

#include "divergence_volume.h"
#include "edit_test_document.h"
#include "ffdkit/interaction/interaction_controller.h"

namespace ffdkit::app {
namespace {

using test::Document;
using widgets::WidgetId;

using ffdkit::test::divergenceVolume;

TEST(DragGuard, AnObjectPointDragWithKeepVolumeKeepsThePointOnThePointerAndTheVolume) {
  Document d;
  d.controller.addPrimitive({});
  const WidgetId lattice = d.controller.newLattice({});
  d.controller.attachLattice(lattice, "sphere1");
  const scenes::ObjectId sphere = d.scene.objectId("sphere1");
  const Eigen::MatrixX3i& triangles = d.scene.findObject(sphere)->mesh.triangles;
  const Eigen::MatrixX3d before = d.deformer.points(sphere);
  const double v0 = divergenceVolume(before, triangles);
  d.controller.setKeep(sphere, {true, false});
  const Eigen::MatrixX3d control = d.scene.widgets.controlPoints(lattice);
  const std::size_t steps = d.commands.position();
  const widgets::Ray ray{Eigen::Vector3d(5.0, 0.1, 0.2), Eigen::Vector3d(-1.0, 0.0, 0.0)};
  ASSERT_TRUE(d.controller.pressObject(ray, 1e-3).has_value());
  const Eigen::Index vertex = d.controller.grabbedPoint()->second;
  const Eigen::Vector3d grab = before.row(vertex).transpose();
  for (int step = 1; step <= 10; ++step) {
    const Eigen::Vector3d offset = 0.03 * step * Eigen::Vector3d(0.0, 1.0, 0.5);
    d.controller.drag({Eigen::Vector3d(5.0, grab.y(), grab.z()) + offset, Eigen::Vector3d(-1.0, 0.0, 0.0)});
    const Eigen::MatrixX3d now = d.deformer.points(sphere);
    EXPECT_LT((now.row(vertex).transpose() - (grab + offset)).norm(), 1e-9) << "step " << step;
    EXPECT_LE(std::abs(divergenceVolume(now, triangles) - v0) / v0, 1e-12) << "step " << step;
    ASSERT_EQ(d.controller.guardSteps().size(), 1u);
    EXPECT_TRUE(d.controller.guardSteps()[0].problem.empty()) << d.controller.guardSteps()[0].problem;
  }
  d.controller.release();
  EXPECT_EQ(d.commands.position(), steps + 1);
  EXPECT_GT((d.scene.widgets.controlPoints(lattice) - control).norm(), 0.1);
  d.commands.undo();
  EXPECT_EQ((d.scene.widgets.controlPoints(lattice) - control).cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace
}  // namespace ffdkit::app
