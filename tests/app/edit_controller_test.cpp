// The lattice edit mode and group transforms, headless (app/interaction/edit_controller.h):
// semantic steps (pick, box, G / R / S with constraints and typed values, handles, Make Cell,
// undo) against control points and frames computed by hand.
#include <gtest/gtest.h>

#include <numbers>

#include "edit_test_document.h"
#include "ffdkit/interaction/edit_controller.h"
#include "ffdkit/scenes/scene_deformer.h"

namespace ffdkit::app {
namespace {

using std::numbers::pi;
using widgets::CellKind;
using widgets::WidgetId;

using test::Document;
using test::downAt;
using test::f;
using test::kView;

// From above and a little to the front (+y), through p: the turn rings are not seen edge-on.
widgets::Ray tiltedAt(const Eigen::Vector3d& p) {
  widgets::Ray r;
  r.origin = p + Eigen::Vector3d(0, 3, 10);
  r.direction = -Eigen::Vector3d(0, 3, 10);
  return r;
}

TEST(EditController, PickBoxAndTheSelectionCount) {
  Document d;
  const WidgetId lattice = d.controller.newLattice({});
  d.edit.enter(lattice);
  // Seen from above, (1,1,k) for k = 0..2 lie on one ray: the nearest (k = 2) is picked.
  EXPECT_TRUE(d.edit.click(downAt({0.5, 0.5, 0}), 0.05, SelectMode::Replace));
  EXPECT_EQ(d.edit.points().indices(), std::vector<Eigen::Index>{f(1, 1, 2)});
  EXPECT_FALSE(d.edit.click(downAt({0.25, 0.25, 0}), 0.05, SelectMode::Replace));  // a miss changes nothing
  EXPECT_EQ(d.edit.points().count(), 1);
  d.edit.selectAll();
  EXPECT_EQ(d.edit.points().count(), 27);
  d.edit.invert();
  EXPECT_TRUE(d.edit.points().empty());
  EXPECT_EQ(d.edit.refusal(), "select points first (click, Shift+click, drag a box, A for all)");
  EXPECT_THROW(d.edit.enter(WidgetId(999)), std::invalid_argument);
}

TEST(EditController, AnUndoThatRemovesTheLatticeEndsTheEditMode) {
  Document d;
  const WidgetId lattice = d.controller.newLattice({});
  d.edit.enter(lattice);
  d.edit.selectAll();
  d.commands.undo();  // the lattice is gone
  EXPECT_FALSE(d.edit.editing());
  EXPECT_TRUE(d.edit.highlights({}).selectedPoints.empty());
  EXPECT_FALSE(d.edit.transformer().has_value());
  EXPECT_FALSE(d.edit.click(downAt({0, 0, 0}), 0.05, SelectMode::Replace));
}

TEST(EditController, GAlongZWithATypedValueMovesExactlyAndIsOneUndoStep) {
  Document d;
  d.controller.addPrimitive({});
  const WidgetId lattice = d.controller.newLattice({});
  d.controller.attachLattice(lattice, "sphere1");
  const std::size_t steps = d.commands.position();
  const Eigen::MatrixX3d start = d.scene.widgets.controlPoints(lattice);
  const Eigen::MatrixX3d sphereStart = d.deformer.points("sphere1");
  d.edit.enter(lattice);
  d.edit.pickMany({f(0, 0, 2), f(1, 0, 2)}, SelectMode::Replace);
  d.edit.beginModal(TransformMode::Move, downAt({0.3, 0.3, 1}), kView);
  d.edit.update(downAt({0.6, 0.1, 1}), false);  // the pointer moves the points live ...
  EXPECT_GT((d.scene.widgets.controlPoints(lattice) - start).norm(), 0.1);
  EXPECT_GT((d.deformer.points("sphere1") - sphereStart).norm(), 0.0);  // ... and the sphere with them
  d.edit.modal()->setConstraint({2, false});
  for (char c : std::string("0.5")) d.edit.modal()->typed().type(c);
  d.edit.update(downAt({0.6, 0.1, 1}), false);
  d.edit.confirm();
  // Fitted frame: local = frame^-1 (world + 0.5 z); compare in the world.
  const Eigen::MatrixX3d world0 = (d.scene.widgets.latticeFrame(lattice) * start.transpose()).transpose();
  Eigen::MatrixX3d expected = world0;
  expected(f(0, 0, 2), 2) += 0.5;
  expected(f(1, 0, 2), 2) += 0.5;
  EXPECT_LE((d.scene.widgets.worldControlPoints(lattice) - expected).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(d.commands.position(), steps + 1);
  EXPECT_EQ(d.commands.undoDescription(), "Move 2 points of " + d.scene.widgets.name(lattice));
  d.commands.undo();
  EXPECT_EQ(d.scene.widgets.controlPoints(lattice), start);
  EXPECT_LE((d.deformer.points("sphere1") - sphereStart).cwiseAbs().maxCoeff(), 1e-12);
  d.commands.redo();
  EXPECT_LE((d.scene.widgets.worldControlPoints(lattice) - expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(EditController, CancelPutsThePointsBackAndPushesNothing) {
  Document d;
  const WidgetId lattice = d.controller.newLattice({});
  const std::size_t steps = d.commands.position();
  d.edit.enter(lattice);
  d.edit.selectAll();
  d.edit.beginModal(TransformMode::Scale, downAt({1, 1, 0}), kView);
  d.edit.update(downAt({2, 2, 0}), false);
  d.edit.cancel();
  EXPECT_EQ(d.scene.widgets.controlPoints(lattice), d.scene.widgets.restPoints(lattice));
  EXPECT_EQ(d.commands.position(), steps);
}

TEST(EditController, RotateAboutTheActivePointAndIndividualOriginsRefused) {
  Document d;
  const WidgetId lattice = d.controller.newLattice({});
  d.edit.enter(lattice);
  d.edit.pickMany({f(0, 0, 0), f(2, 0, 0)}, SelectMode::Replace);
  d.edit.setPivot(PivotChoice::Individual);
  EXPECT_THROW(d.edit.beginModal(TransformMode::Rotate, downAt({0, 0, 0}), kView), std::invalid_argument);
  d.edit.pickMany({}, SelectMode::Replace);
  d.edit.click(downAt({0, 0, 0}), 0.05, SelectMode::Add);  // (0,0,2) is nearest: active
  d.edit.click(downAt({1, 0, 0}), 0.05, SelectMode::Add);  // (2,0,2): active now
  d.edit.setPivot(PivotChoice::Active);
  EXPECT_TRUE(d.edit.pivotPoint()->isApprox(Eigen::Vector3d(1, 0, 1)));
  d.edit.beginModal(TransformMode::Rotate, downAt({0, 0, 0}), kView);
  d.edit.modal()->setConstraint({2, false});
  d.edit.modal()->typed().type('9');
  d.edit.modal()->typed().type('0');
  d.edit.update(downAt({0, 0, 0}), false);
  d.edit.confirm();
  // (0,0,1) turned 90 degrees about +z through (1,0,1): (1,-1,1); the active point stays.
  const Eigen::MatrixX3d p = d.scene.widgets.worldControlPoints(lattice);
  EXPECT_LE((p.row(f(0, 0, 2)) - Eigen::RowVector3d(1, -1, 1)).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LE((p.row(f(2, 0, 2)) - Eigen::RowVector3d(1, 0, 1)).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(d.commands.undoDescription(), "Turn 2 points of " + d.scene.widgets.name(lattice));
}

TEST(EditController, TransformerHandleDragMovesTheSelectionWithSnapping) {
  Document d;
  const WidgetId lattice = d.controller.newLattice({});
  d.edit.enter(lattice);
  d.edit.pickMany({f(2, 2, 2)}, SelectMode::Replace);
  const auto t = d.edit.transformer();
  ASSERT_TRUE(t.has_value());
  EXPECT_TRUE(t->frame.translation().isApprox(Eigen::Vector3d(1, 1, 1)));
  // Grab the x arrow and pull it by 0.23: snapped to 0.2.
  const Eigen::Vector3d grab = t->frame.translation() + 0.6 * t->size * Eigen::Vector3d::UnitX();
  ASSERT_TRUE(d.edit.pressHandle(tiltedAt(grab), 0.02));
  d.edit.update(tiltedAt(grab + Eigen::Vector3d(0.23, 0.1, 0)), /*snap=*/true);
  d.edit.confirm();
  EXPECT_LE((d.scene.widgets.worldControlPoints(lattice).row(f(2, 2, 2)) - Eigen::RowVector3d(1.2, 1, 1)).cwiseAbs().maxCoeff(),
            1e-12);
}

TEST(EditController, AValueTypedDuringAHandleDragSetsItsAmountExactlyAsOneUndoStep) {
  Document d;
  const WidgetId lattice = d.controller.newLattice({});
  const auto& m = d.scene.widgets;
  d.edit.enter(lattice);
  d.edit.pickMany({f(1, 1, 2), f(2, 1, 2)}, SelectMode::Replace);
  EXPECT_FALSE(d.edit.setDragValue(0.5));  // no drag: nothing changes
  const Eigen::MatrixX3d start = m.worldControlPoints(lattice);
  const std::size_t steps = d.commands.position();
  const Transformer t = *d.edit.transformer();
  const Eigen::Vector3d grab = t.frame.translation() + 0.6 * t.size * Eigen::Vector3d::UnitX();
  ASSERT_TRUE(d.edit.pressHandle(tiltedAt(grab), 0.02));
  EXPECT_EQ(d.edit.draggedHandle(), TransformerHandle::MoveX);
  d.edit.update(tiltedAt(grab + Eigen::Vector3d(0.23, 0, 0)), false);
  ASSERT_TRUE(d.edit.setDragValue(0.5));
  d.edit.update(tiltedAt(grab + Eigen::Vector3d(0.1, 0, 0)), true);  // the typed value rules
  EXPECT_EQ(d.edit.describe(), "move x 0.500");
  d.edit.confirm();
  Eigen::MatrixX3d expected = start;
  expected(f(1, 1, 2), 0) += 0.5;
  expected(f(2, 1, 2), 0) += 0.5;
  EXPECT_EQ((m.worldControlPoints(lattice) - expected).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(d.commands.position(), steps + 1);
  d.commands.undo();
  EXPECT_EQ((m.worldControlPoints(lattice) - start).cwiseAbs().maxCoeff(), 0.0);
  d.edit.exit();

  // A group's turn ring: 90 degrees (typed as rad) about z through the median pivot.
  const WidgetId other = d.controller.newLattice({});
  d.controller.setLatticeFrame(other, Eigen::Affine3d(Eigen::Translation3d(2, 0, 0)));
  d.controller.setSelection({lattice, other});
  const Eigen::Affine3d a0 = m.latticeFrame(lattice), b0 = m.latticeFrame(other);
  const Transformer g = *d.edit.transformer();
  const Eigen::Vector3d pivot = g.frame.translation();
  EXPECT_TRUE(pivot.isApprox(Eigen::Vector3d(1.5, 0.5, 0.5), 1e-14));
  const double r = TransformerLayout::turnRadius * g.size;
  const Eigen::Vector3d ring = pivot + r * Eigen::Vector3d(std::cos(0.7), std::sin(0.7), 0);
  ASSERT_TRUE(d.edit.pressHandle(tiltedAt(ring), 0.02));
  ASSERT_EQ(d.edit.draggedHandle(), TransformerHandle::TurnZ);
  ASSERT_TRUE(d.edit.setDragValue(pi / 2));
  d.edit.confirm();
  const Eigen::Affine3d turn =
      Eigen::Translation3d(pivot) * Eigen::AngleAxisd(pi / 2, Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(-pivot);
  EXPECT_TRUE(m.latticeFrame(lattice).matrix().isApprox((turn * a0).matrix(), 1e-12));
  EXPECT_TRUE(m.latticeFrame(other).matrix().isApprox((turn * b0).matrix(), 1e-12));
  EXPECT_EQ(d.commands.undoDescription(), "Turn 2 widgets");
  // A size handle refuses a factor that is not positive.
  const Eigen::Vector3d cube = pivot + TransformerLayout::sizeAt * g.size * Eigen::Vector3d::UnitX();
  ASSERT_TRUE(d.edit.pressHandle(tiltedAt(cube), 0.02));
  ASSERT_EQ(d.edit.draggedHandle(), TransformerHandle::SizeX);
  EXPECT_FALSE(d.edit.setDragValue(0.0));
  EXPECT_TRUE(d.edit.setDragValue(2.0));
  d.edit.cancel();
  EXPECT_FALSE(d.edit.draggedHandle().has_value());
}

TEST(EditController, MirrorEditingMovesEachImageByTheMirroredMotion) {
  Document d;
  const WidgetId lattice = d.controller.newLattice({});
  const auto& m = d.scene.widgets;
  // A lattice frame that is no identity: the mid-plane is the lattice's, not the world's.
  d.controller.setLatticeFrame(lattice, Eigen::Translation3d(0.3, -0.2, 0.1) * Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()));
  EXPECT_THROW(d.edit.setMirror(3), std::invalid_argument);
  d.edit.setMirror(0);  // across the mid-plane i = 1 (local x = 0.5)
  d.edit.enter(lattice);
  const Eigen::MatrixX3d start = m.controlPoints(lattice);  // local
  const std::size_t steps = d.commands.position();
  // (2,1,2) and the mid-plane point (1,0,0) selected; a typed world move (0.1, 0.2, 0.3).
  d.edit.pickMany({f(2, 1, 2), f(1, 0, 0)}, SelectMode::Replace);
  const Eigen::Vector3d pivot = *d.edit.pivotPoint();
  d.edit.beginModal(TransformMode::Move, downAt(pivot), kView);
  for (char c : std::string("0.1,0.2,0.3")) d.edit.modal()->typed().type(c);
  d.edit.update(downAt(pivot), false);
  d.edit.confirm();
  EXPECT_EQ(d.commands.position(), steps + 1);
  EXPECT_EQ(d.commands.undoDescription(), "Move 2 points of " + m.name(lattice) + " (mirrored)");
  // In local coordinates the world move is R^T (0.1, 0.2, 0.3); the image (0,1,2) moves by it
  // with x negated; the mid-plane point and everything else by M or not at all.
  const Eigen::Vector3d local = Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d(0.1, 0.2, 0.3);
  Eigen::MatrixX3d expected = start;
  expected.row(f(2, 1, 2)) += local.transpose();
  expected.row(f(1, 0, 0)) += local.transpose();
  expected.row(f(0, 1, 2)) += Eigen::RowVector3d(-local.x(), local.y(), local.z());
  EXPECT_LE((m.controlPoints(lattice) - expected).cwiseAbs().maxCoeff(), 1e-15);
  d.commands.undo();
  EXPECT_EQ((m.controlPoints(lattice) - start).cwiseAbs().maxCoeff(), 0.0);

  // A turn of 30 degrees about world z through the two points' median: the images turn the
  // other way about the mirrored pivot, each pair stays symmetric (x' = 1 - x, y' = y, z' = z
  // locally).
  d.edit.pickMany({f(2, 0, 0), f(2, 2, 2)}, SelectMode::Replace);
  d.edit.beginModal(TransformMode::Rotate, downAt(*d.edit.pivotPoint()), kView);
  d.edit.modal()->setConstraint({2, false});
  for (char c : std::string("30")) d.edit.modal()->typed().type(c);
  d.edit.update(downAt(*d.edit.pivotPoint()), false);
  d.edit.confirm();
  const Eigen::MatrixX3d p = m.controlPoints(lattice);
  for (const auto& [a, b] : {std::pair(f(2, 0, 0), f(0, 0, 0)), std::pair(f(2, 2, 2), f(0, 2, 2))}) {
    EXPECT_GT((p.row(a) - start.row(a)).norm(), 0.05);
    EXPECT_LE(std::abs(p(b, 0) - (1.0 - p(a, 0))), 1e-15);
    EXPECT_LE(std::abs(p(b, 1) - p(a, 1)), 1e-15);
    EXPECT_LE(std::abs(p(b, 2) - p(a, 2)), 1e-15);
  }
  // Both of a pair selected: each moves by M (no image is added).
  d.commands.undo();
  d.edit.pickMany({f(2, 1, 1), f(0, 1, 1)}, SelectMode::Replace);
  d.edit.beginModal(TransformMode::Move, downAt(pivot), kView);
  d.edit.modal()->typed().type('1');
  d.edit.update(downAt(pivot), false);
  d.edit.confirm();
  EXPECT_EQ(d.commands.undoDescription(), "Move 2 points of " + m.name(lattice));
  EXPECT_GT(m.controlPoints(lattice)(f(0, 1, 1), 0) - start(f(0, 1, 1), 0), 0.5);
  d.edit.setMirror(std::nullopt);
  EXPECT_FALSE(d.edit.mirror().has_value());
}

TEST(EditController, MakeCellYieldsEachKindAndRefusesAMisfit) {
  Document d;
  const WidgetId lattice = d.controller.newLattice({});
  d.edit.enter(lattice);
  const auto& m = d.scene.widgets;
  auto make = [&](std::vector<Eigen::Index> points, std::optional<CellKind> kind) -> std::optional<WidgetId> {
    d.edit.pickMany(points, SelectMode::Replace);
    const CellFromSelection cell = d.edit.cellFor(kind);
    if (!cell.spec) return std::nullopt;
    return d.edit.makeCell(*cell.spec);
  };
  EXPECT_EQ(m.cellSpec(*make({f(2, 2, 0)}, std::nullopt)), widgets::CellSpec::point(2, 2, 0));
  EXPECT_EQ(m.cellSpec(*make({f(0, 2, 0), f(1, 2, 0)}, std::nullopt)), widgets::CellSpec::edge(0, 2, 0, 0));
  const WidgetId face = *make({f(0, 0, 2), f(1, 0, 2), f(0, 1, 2), f(1, 1, 2)}, std::nullopt);
  EXPECT_EQ(m.cellSpec(face), widgets::CellSpec::face(0, 0, 2, 2));
  EXPECT_EQ(d.controller.selection(), std::vector{face});  // Add Translate / Rotate / Scale act on it
  std::vector<Eigen::Index> plane, box;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) plane.push_back(f(i, j, 1));
  EXPECT_EQ(m.cellSpec(*make(plane, std::nullopt)), widgets::CellSpec::slab(2, 1));
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) box.push_back(f(i, j, k));
  EXPECT_EQ(m.cellSpec(*make(box, std::nullopt)), widgets::CellSpec::box(0, 0, 0));
  EXPECT_EQ(m.cellSpec(*make({f(0, 0, 0), f(2, 2, 2)}, CellKind::Custom)).kind, CellKind::Custom);
  EXPECT_FALSE(make({f(0, 0, 0), f(2, 2, 2)}, std::nullopt).has_value());
  d.edit.pickMany({f(0, 0, 0), f(2, 2, 2)}, SelectMode::Replace);
  EXPECT_EQ(d.edit.cellFor(CellKind::Edge).why,
            "an edge cell is 2 neighbouring points along one axis; (0,0,0) and (2,2,2) differ by 2 along i, 2 along j, "
            "2 along k");
  // The face's rotate widget acts; a point cell's is refused with the reason.
  EXPECT_NO_THROW(d.controller.addAffine(face, widgets::AffineKind::Rotate));
  EXPECT_THROW(d.controller.addAffine(m.cellsOf(lattice).front(), widgets::AffineKind::Rotate), std::invalid_argument);
  EXPECT_THROW(d.controller.addAffineAtPoint({lattice, 0}, widgets::AffineKind::Scale), std::invalid_argument);
}

TEST(EditController, AGroupOfWidgetsMovesAndTurnsAsOneUndoStep) {
  Document d;
  const WidgetId a = d.controller.newLattice({});
  const WidgetId b = d.controller.newLattice({});
  d.controller.setLatticeFrame(b, Eigen::Affine3d(Eigen::Translation3d(2, 0, 0)));
  const WidgetId third = d.controller.newLattice({});
  d.controller.setLatticeFrame(third, Eigen::Affine3d(Eigen::Translation3d(0, 3, 0)));
  const WidgetId arrow = d.controller.addAffineAtPoint({third, f(1, 1, 2)}, widgets::AffineKind::Translate);
  const auto& m = d.scene.widgets;
  const Eigen::Affine3d frameA = m.latticeFrame(a), frameB = m.latticeFrame(b);
  const Eigen::Vector3d arrowAt = m.affineFrame(arrow).frame.translation();
  d.controller.setSelection({a, b, arrow});
  EXPECT_FALSE(d.edit.refusal().has_value());
  // Median pivot: the mean of the two lattice centres and the arrow.
  const Eigen::Vector3d pivot = (Eigen::Vector3d(0.5, 0.5, 0.5) + Eigen::Vector3d(2.5, 0.5, 0.5) + arrowAt) / 3.0;
  EXPECT_TRUE(d.edit.pivotPoint()->isApprox(pivot, 1e-14));
  const std::size_t steps = d.commands.position();
  d.edit.beginModal(TransformMode::Rotate, downAt(pivot), kView);
  d.edit.modal()->setConstraint({2, false});
  for (char c : std::string("30")) d.edit.modal()->typed().type(c);
  d.edit.update(downAt(pivot), false);
  d.edit.confirm();
  EXPECT_EQ(d.commands.position(), steps + 1);
  EXPECT_EQ(d.commands.undoDescription(), "Turn 3 widgets");
  const Eigen::Affine3d turn = Eigen::Translation3d(pivot) * Eigen::AngleAxisd(pi / 6, Eigen::Vector3d::UnitZ()) *
                               Eigen::Translation3d(-pivot);
  EXPECT_TRUE(m.latticeFrame(a).matrix().isApprox((turn * frameA).matrix(), 1e-12));
  EXPECT_TRUE(m.latticeFrame(b).matrix().isApprox((turn * frameB).matrix(), 1e-12));
  EXPECT_TRUE(m.affineFrame(arrow).frame.translation().isApprox(turn * arrowAt, 1e-12));
  d.commands.undo();
  EXPECT_TRUE(m.latticeFrame(a).matrix().isApprox(frameA.matrix(), 1e-15));
  EXPECT_TRUE(m.latticeFrame(b).matrix().isApprox(frameB.matrix(), 1e-15));
  EXPECT_TRUE(m.affineFrame(arrow).frame.translation().isApprox(arrowAt, 1e-14));
  // A widget on a selected lattice moves with it, not twice: {a, its widget} is one item.
  const WidgetId onA = d.controller.addAffineAtPoint({a, f(1, 1, 2)}, widgets::AffineKind::Translate);
  d.controller.setSelection({a, onA});
  EXPECT_TRUE(d.edit.refusal().has_value());
  // Fewer than two widgets: nothing to group.
  d.controller.setSelection({a});
  EXPECT_TRUE(d.edit.refusal().has_value());
  EXPECT_FALSE(d.edit.transformer().has_value());
}

}  // namespace
}  // namespace ffdkit::app
