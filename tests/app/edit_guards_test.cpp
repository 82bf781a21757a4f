// Keep Volume / Keep Centre and soft selection in the edit mode, headless
// (app/interaction/shape_guard.h, edit_controller.h): the volume of the evaluated mesh (summed
// here by the divergence theorem) stays through a modal move and its undo is one step; an open
// surface is refused with its reason; soft-selected points move by their falloff times the move;
// the fold-over tint follows the lattice.
#include <gtest/gtest.h>

#include <cmath>

#include "divergence_volume.h"
#include "edit_test_document.h"
#include "ffdkit/interaction/edit_controller.h"
#include "ffdkit/scenes/scene_deformer.h"

namespace ffdkit::app {
namespace {

using widgets::WidgetId;

using test::Document;
using test::downAt;
using test::f;
using test::kView;


// The volume a closed triangle mesh encloses: sum over triangles of a . (b x c) / 6.
using ffdkit::test::divergenceVolume;

// A G along z of the selected points by a typed amount.
void moveAlongZ(EditController& edit, const Eigen::Vector3d& pivot, const char* amount) {
  edit.beginModal(TransformMode::Move, downAt(pivot), kView);
  edit.modal()->setConstraint(AxisConstraint{2, false});
  for (const char* c = amount; *c; ++c) edit.modal()->typed().type(*c);
  edit.update(downAt(pivot), false);
}

TEST(ShapeGuard, KeepVolumeHoldsThroughAMoveOfPointsAndIsOneUndoStep) {
  Document d;
  d.controller.addPrimitive({});
  const WidgetId lattice = d.controller.newLattice({});
  d.controller.attachLattice(lattice, "sphere1");  // the lattice fitted round the sphere
  const scenes::ObjectId sphere = d.scene.objectId("sphere1");
  const Eigen::MatrixX3i& triangles = d.scene.findObject(sphere)->mesh.triangles;
  const double v0 = divergenceVolume(d.deformer.points(sphere), triangles);
  d.edit.shapeGuard().setKeep(d.scene, d.deformer, sphere, {true, false});
  EXPECT_NEAR(d.edit.shapeGuard().keptVolume(sphere), v0, 1e-14 * v0);
  d.edit.enter(lattice);
  const Eigen::Vector3d top = d.scene.widgets.worldControlPoints(lattice).row(f(1, 1, 2));  // the top's middle
  d.edit.click(downAt(top), 0.05, SelectMode::Replace);
  ASSERT_EQ(d.edit.points().indices(), std::vector<Eigen::Index>{f(1, 1, 2)});
  const Eigen::MatrixX3d start = d.scene.widgets.controlPoints(lattice);
  const Eigen::MatrixX3d startWorld = d.scene.widgets.worldControlPoints(lattice);
  const std::size_t steps = d.commands.position();

  moveAlongZ(d.edit, top, "0.4");
  const Eigen::MatrixX3d moved = d.scene.widgets.controlPoints(lattice);
  const Eigen::MatrixX3d movedWorld = d.scene.widgets.worldControlPoints(lattice);
  EXPECT_NEAR(movedWorld(f(1, 1, 2), 2), startWorld(f(1, 1, 2), 2) + 0.4, 1e-15);  // where it was sent
  EXPECT_GT((movedWorld - startWorld).norm(), 0.401);                              // and the others gave way
  const double v = divergenceVolume(d.deformer.points(sphere), triangles);
  EXPECT_LE(std::abs(v - v0) / v0, 1e-12) << v << " vs " << v0;
  ASSERT_EQ(d.edit.guardSteps().size(), 1u);
  EXPECT_TRUE(d.edit.guardSteps()[0].problem.empty()) << d.edit.guardSteps()[0].problem;
  EXPECT_LE(std::abs(d.edit.guardSteps()[0].volumeChange), 1e-12);
  d.edit.confirm();
  EXPECT_LE(std::abs(divergenceVolume(d.deformer.points(sphere), triangles) - v0) / v0, 1e-12);
  EXPECT_EQ(d.commands.position(), steps + 1);
  d.commands.undo();
  EXPECT_EQ(d.scene.widgets.controlPoints(lattice), start);
  d.commands.redo();
  EXPECT_EQ(d.scene.widgets.controlPoints(lattice), moved);

  // Keep Centre too: the solid's centroid stays as well.
  d.edit.shapeGuard().setKeep(d.scene, d.deformer, sphere, {true, true});
  const Eigen::MatrixX3d before = d.deformer.points(sphere);
  moveAlongZ(d.edit, top + Eigen::Vector3d(0, 0, 0.4), "-0.2");
  d.edit.confirm();
  EXPECT_TRUE(d.edit.guardSteps().at(0).problem.empty()) << d.edit.guardSteps()[0].problem;
  const Eigen::MatrixX3d after = d.deformer.points(sphere);
  EXPECT_LE(std::abs(divergenceVolume(after, triangles) - v0) / v0, 1e-12);
  // The centroid: sum det[a,b,c] (a + b + c) / 24 over the volume.
  auto centroid = [&](const Eigen::MatrixX3d& p) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (Eigen::Index i = 0; i < triangles.rows(); ++i) {
      const Eigen::Vector3d a = p.row(triangles(i, 0)), b = p.row(triangles(i, 1)), e = p.row(triangles(i, 2));
      c += a.dot(b.cross(e)) * (a + b + e) / 24.0;
    }
    return Eigen::Vector3d(c / divergenceVolume(p, triangles));
  };
  EXPECT_LT((centroid(after) - centroid(before)).norm(), 1e-10);
}

TEST(ShapeGuard, AnOpenSurfaceIsRefusedWithItsReason) {
  Document d;
  scenes::PrimitiveOptions plane;
  plane.kind = scenes::PrimitiveKind::Plane;
  const std::string name = d.controller.addPrimitive(plane);
  const scenes::ObjectId id = d.scene.objectId(name);
  try {
    d.edit.shapeGuard().setKeep(d.scene, d.deformer, id, {true, false});
    FAIL() << "an open surface was kept";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'" + name + "' encloses no volume: it is not a closed surface"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(d.edit.shapeGuard().keep(id).any());
  // Its centre is the mean of its points: that may be kept.
  d.edit.shapeGuard().setKeep(d.scene, d.deformer, id, {false, true});
  EXPECT_TRUE(d.edit.shapeGuard().keep(id).centre);
}

TEST(SoftSelection, AMoveTakesTheFalloffOfEveryPointWithinTheRadius) {
  Document d;
  const WidgetId lattice = d.controller.newLattice({});
  d.edit.enter(lattice);
  d.edit.click(downAt({0.5, 0.5, 1.0}), 0.05, SelectMode::Replace);  // (1,1,2) at (0.5, 0.5, 1)
  SoftSelection soft;
  soft.enabled = true;
  soft.radius = 0.6;
  soft.falloff = Falloff::Sharp;
  d.edit.setSoftSelection(soft);
  const Eigen::MatrixX3d start = d.scene.widgets.worldControlPoints(lattice);
  moveAlongZ(d.edit, {0.5, 0.5, 1.0}, "0.5");
  d.edit.scaleSoftRadius(1.5);  // the wheel during the move: radius 0.9
  const Eigen::MatrixX3d moved = d.scene.widgets.worldControlPoints(lattice);
  for (Eigen::Index i = 0; i < start.rows(); ++i) {
    const double distance = (start.row(i) - start.row(f(1, 1, 2))).norm();
    const double weight = distance <= 0.9 ? std::pow((0.9 - distance) / 0.9, 2) : 0.0;
    EXPECT_NEAR(moved(i, 2) - start(i, 2), 0.5 * weight, 1e-15) << i;
    EXPECT_EQ(moved(i, 0), start(i, 0));
  }
  ASSERT_TRUE(d.edit.highlights({}).softRadius.has_value());
  EXPECT_EQ(d.edit.highlights({}).softRadius->centre, Eigen::Vector3d(0.5, 0.5, 1.0));
  EXPECT_NEAR(d.edit.highlights({}).softRadius->radius, 0.9, 1e-15);
  d.edit.cancel();
  EXPECT_EQ(d.scene.widgets.worldControlPoints(lattice), start);
}

TEST(EditController, TheFoldTintFollowsTheEditedLattice) {
  Document d;
  const WidgetId lattice = d.controller.newLattice({});
  d.edit.enter(lattice);
  EXPECT_TRUE(d.edit.foldTints().empty());  // the rest lattice is certified
  // (1,1,2) pushed down through (1,1,1) to z = -2: at the top's middle dX/dw =
  // 2 sum B_i(1/2) B_j(1/2) (P_ij2 - P_ij1) has z = 2 (0.25 (-2 - 0.5) + 0.75 (1 - 0.5)) < 0 while
  // dX/du and dX/dv are +x and +y: det J < 0 there, the map turns inside out.
  d.edit.click(downAt({0.5, 0.5, 1.0}), 0.05, SelectMode::Replace);
  moveAlongZ(d.edit, {0.5, 0.5, 1.0}, "-3");
  ASSERT_NEAR(d.scene.widgets.worldControlPoints(lattice)(f(1, 1, 2), 2), -2.0, 1e-15);
  ASSERT_EQ(d.edit.foldTints().size(), 1u);
  EXPECT_EQ(d.edit.foldTints()[0].lattice, lattice);
  EXPECT_EQ(d.edit.foldTints()[0].cells, std::vector<ffd::CellFolding>{ffd::CellFolding::Folds});
  EXPECT_EQ(d.edit.highlights({}).foldTints, d.edit.foldTints());
  d.edit.cancel();
  EXPECT_TRUE(d.edit.foldTints().empty());
}

}  // namespace
}  // namespace ffdkit::app
