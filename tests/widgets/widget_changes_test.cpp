// Revisions and change sets of the widget model (widget_changes.h): each kind of mutation takes
// exactly one new revision and stamps exactly the items it changed.
#include "ffdkit/widgets/widget_changes.h"

#include <algorithm>
#include <functional>

#include <gtest/gtest.h>

#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::widgets {
namespace {

// A root lattice with a child lattice riding on its top slab (hierarchy), a point cell with a
// translate widget bound (variation) to a rotate widget on the slab, and a free widget.
struct Rig {
  WidgetModel m;
  WidgetId root, top, child, point, push, turn, free;
  BindingId hierarchy, rule;
  Rig() {
    root = m.addLattice("root", Eigen::Vector3i(3, 3, 3));
    top = m.addCell(root, CellSpec::slab(2, 2), "top");
    child = m.addLattice("child", Eigen::Vector3i(2, 2, 2));
    hierarchy = m.bind(top, child);
    point = m.addCell(root, CellSpec::point(0, 0, 0), "corner");
    push = m.addAffine(point, AffineKind::Translate, "push");
    turn = m.addAffine(top, AffineKind::Rotate, "turn");
    rule = m.bind(turn, push, ConversionRule(0.1));
    AffineOptions options;
    options.name = "free";
    free = m.addFreeAffine(AffineKind::Scale, options);
  }
};

// What a mutation should change, built fluently: Expected().control({a}).frames({b}).
struct Expected {
  bool structure = false;
  std::vector<WidgetId> controlPoints, frames, widgets;
  std::vector<BindingId> bindings;
  Expected& tree() { structure = true; return *this; }
  Expected& control(std::vector<WidgetId> ids) { controlPoints = std::move(ids); return *this; }
  Expected& frame(std::vector<WidgetId> ids) { frames = std::move(ids); return *this; }
  Expected& own(std::vector<WidgetId> ids) { widgets = std::move(ids); return *this; }
  Expected& binding(std::vector<BindingId> ids) { bindings = std::move(ids); return *this; }
};

template <class T>
std::vector<T> sorted(std::vector<T> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// Runs `mutation`, then checks it took one revision and changed exactly `expect()` (evaluated
// after the mutation, so that it may name the widgets the mutation made).
void expectChanges(WidgetModel& m, const std::function<void()>& mutation, const std::function<Expected()>& expect) {
  const std::uint64_t before = m.revision();
  const std::uint64_t instance = m.instance();
  mutation();
  const Expected expected = expect();
  EXPECT_EQ(m.revision(), before + 1);
  EXPECT_EQ(m.instance(), instance);
  const WidgetChanges c = m.changesSince(before);
  EXPECT_EQ(c.since, before);
  EXPECT_EQ(c.revision, m.revision());
  EXPECT_EQ(c.structure, expected.structure);
  EXPECT_EQ(sorted(c.controlPoints), sorted(expected.controlPoints));
  EXPECT_EQ(sorted(c.frames), sorted(expected.frames));
  EXPECT_EQ(sorted(c.widgets), sorted(expected.widgets));
  EXPECT_EQ(sorted(c.bindings), sorted(expected.bindings));
  // The stamps agree with the per-item revisions.
  for (WidgetId id : expected.controlPoints) EXPECT_EQ(m.controlRevision(id), m.revision());
  for (WidgetId id : expected.frames) EXPECT_EQ(m.frameRevision(id), m.revision());
  for (WidgetId id : expected.widgets) EXPECT_EQ(m.widgetRevision(id), m.revision());
  for (BindingId id : expected.bindings) EXPECT_EQ(m.bindingRevision(id), m.revision());
  if (expected.structure) {
    EXPECT_EQ(m.structureRevision(), m.revision());
  }
  EXPECT_TRUE(m.changesSince(m.revision()).empty());
}

void expectChanges(WidgetModel& m, const std::function<void()>& mutation, const Expected& expected) {
  expectChanges(m, mutation, [&] { return expected; });
}

TEST(WidgetChanges, ControlPointsOfAParentMoveItsChildsFrame) {
  Rig r;
  Eigen::MatrixX3d p = r.m.controlPoints(r.root);
  p(4, 0) += 0.1;  // a point of the middle layer: the top slab's fit does not move, the stamp does
  expectChanges(r.m, [&] { r.m.setControlPoints(r.root, p); }, Expected().control({r.root}).frame({r.child}));
  Eigen::MatrixX3d q = r.m.controlPoints(r.child);
  q(0, 2) -= 0.2;
  expectChanges(r.m, [&] { r.m.setControlPoints(r.child, q); }, Expected().control({r.child}));
  expectChanges(r.m, [&] { r.m.resetLattice(r.child); }, Expected().control({r.child}));
}

TEST(WidgetChanges, FramesAndSettingsAreRestChanges) {
  Rig r;
  expectChanges(r.m, [&] { r.m.setLatticeFrame(r.root, Eigen::Affine3d(Eigen::Translation3d(1, 0, 0))); },
                Expected().frame({r.root, r.child}));
  LatticeSettings settings = r.m.latticeSettings(r.child);
  settings.outside = ffd::OutsidePolicy::clampEdge();
  expectChanges(r.m, [&] { r.m.setLatticeSettings(r.child, settings); }, Expected().frame({r.child}).own({r.child}));
  expectChanges(r.m, [&] { r.m.setMask(r.hierarchy, AffineMask::t()); }, Expected().frame({r.child}).binding({r.hierarchy}));
}

TEST(WidgetChanges, OwnDataOfAWidget) {
  Rig r;
  expectChanges(r.m, [&] { r.m.setPlacement(r.free, Eigen::Affine3d(Eigen::Translation3d(0, 2, 0))); },
                Expected().own({r.free}));
  Glyph glyph = r.m.glyph(r.push);
  glyph.size = 0.5;
  expectChanges(r.m, [&] { r.m.setGlyph(r.push, glyph); }, Expected().own({r.push}));
  expectChanges(r.m, [&] { r.m.rename(r.push, "pusher"); }, Expected().own({r.push}));
  expectChanges(r.m, [&] { r.m.setAffineKind(r.free, AffineKind::Rotate); }, Expected().own({r.free}));
  expectChanges(r.m, [&] { r.m.setRule(r.rule, ConversionRule(0.2)); }, Expected().binding({r.rule}));
  expectChanges(r.m, [&] { r.m.setOneWay(r.rule, true); }, Expected().binding({r.rule}));
}

TEST(WidgetChanges, AGestureStampsWhatItMoves) {
  Rig r;
  // The turn widget rotates the top slab (root points, so the child follows) and drives push
  // (0.1 per radian), which moves the corner point.
  expectChanges(r.m, [&] { r.m.beginGesture(r.turn); r.m.updateGesture(0.3); },
                Expected().control({r.root}).frame({r.child}).own({r.turn, r.push}));
  const std::uint64_t before = r.m.revision();
  r.m.endGesture();  // the points stay where the last update put them
  EXPECT_EQ(r.m.revision(), before);
  expectChanges(r.m, [&] { r.m.beginGesture(r.child); r.m.updateGesture(Eigen::Affine3d(Eigen::Translation3d(0, 0, 0.1))); },
                Expected().control({r.root}).frame({r.child}));  // a bound child moves its parent cell
  expectChanges(r.m, [&] { r.m.cancelGesture(); }, Expected().control({r.root}).frame({r.child}));
}

TEST(WidgetChanges, StructureEdits) {
  Rig r;
  WidgetId cell;
  expectChanges(r.m, [&] { cell = r.m.addCell(r.root, CellSpec::point(2, 2, 0), "other"); },
                [&] { return Expected().tree().own({cell}); });
  WidgetId widget;
  expectChanges(r.m, [&] { widget = r.m.addAffine(cell, AffineKind::Translate, "other-push"); },
                [&] { return Expected().tree().own({widget}); });
  WidgetId lattice;
  expectChanges(r.m, [&] { lattice = r.m.addLattice("second", Eigen::Vector3i(2, 2, 2)); },
                [&] { return Expected().tree().control({lattice}).frame({lattice}).own({lattice}); });
  expectChanges(r.m, [&] { r.m.setSiblingPosition(lattice, 0); }, Expected().tree());
  BindingId binding;
  expectChanges(r.m, [&] { binding = r.m.bind(widget, r.free, ConversionRule(1.0)); },
                [&] { return Expected().tree().binding({binding}); });
  expectChanges(r.m, [&] { r.m.unbind(binding); }, Expected().tree());
  // Unbinding the child makes it a root at its world frame; removing a cell frees its widgets.
  expectChanges(r.m, [&] { r.m.unbind(r.hierarchy); }, Expected().tree().frame({r.child}));
  expectChanges(r.m, [&] { r.m.remove(cell); }, [&] { return Expected().tree().own({widget}); });
  expectChanges(r.m, [&] { r.m.setLatticeCounts(r.root, Eigen::Vector3i(4, 3, 3)); },
                Expected().tree().control({r.root}).frame({r.root}).own({r.root, r.top, r.point}));
}

TEST(WidgetChanges, RestoringAStateStampsOnlyWhatDiffers) {
  Rig r;
  const WidgetModelState start = r.m.captureState();
  r.m.setVariation(r.push, 0.25);  // moves the corner; the bound turn widget follows and turns the top
  expectChanges(r.m, [&] { r.m.restoreState(start); }, Expected().control({r.root}).frame({r.child}).own({r.push, r.turn}));
  const std::uint64_t before = r.m.revision();
  r.m.restoreState(start);  // already there: nothing changes
  EXPECT_TRUE(r.m.changesSince(before).empty());
}

// assignData (an undo or redo of a structural edit) keeps the instance and stamps only the
// records that differ; ids come back exactly.
TEST(WidgetChanges, AssigningDataStampsOnlyTheRecordsThatDiffer) {
  Rig r;
  const WidgetModelData start = r.m.toData();
  const WidgetId cell = r.m.addCell(r.root, CellSpec::point(2, 2, 0), "other");
  const WidgetId widget = r.m.addAffine(cell, AffineKind::Translate, "other-push");
  const BindingId attachment = r.m.bindingsOf(widget).front();
  const WidgetModelData added = r.m.toData();
  // Undo: the two widgets go; no lattice, frame or other widget is touched.
  expectChanges(r.m, [&] { r.m.assignData(start); }, Expected().tree());
  EXPECT_FALSE(r.m.contains(cell));
  // Redo: they come back with their ids, and only they (and their binding) are stamped.
  expectChanges(r.m, [&] { r.m.assignData(added); }, Expected().tree().own({cell, widget}).binding({attachment}));
  EXPECT_EQ(r.m.name(widget), "other-push");
  EXPECT_EQ(r.m.attachedCell(widget), cell);
  // The same data again changes nothing.
  expectChanges(r.m, [&] { r.m.assignData(added); }, Expected());
  // Re-parenting undone: the child is bound again (its rest lattice in the world follows the parent).
  r.m.unbind(r.hierarchy);
  expectChanges(r.m, [&] { r.m.assignData(added); }, Expected().tree().frame({r.child}).binding({r.hierarchy}));
  EXPECT_EQ(r.m.parentCell(r.child), r.top);
  // New counts undone: the lattice's points and rest, and the cells whose points moved, are stamped.
  const WidgetModelData beforeCounts = r.m.toData();
  r.m.setLatticeCounts(r.root, Eigen::Vector3i(4, 3, 3));
  expectChanges(r.m, [&] { r.m.assignData(beforeCounts); },
                Expected().tree().control({r.root}).frame({r.root, r.child}).own({r.top, cell}));
  EXPECT_EQ(r.m.toData().lattices.front().controlPoints, beforeCounts.lattices.front().controlPoints);
  // Bad data is refused with its location and changes nothing.
  WidgetModelData bad = added;
  bad.cells.front().lattice = widget;
  const std::uint64_t revision = r.m.revision();
  try {
    r.m.assignData(bad);
    ADD_FAILURE() << "assignData accepted a cell on an affine widget";
  } catch (const WidgetError& e) {
    EXPECT_EQ(e.where(), "/cells/0/lattice");
  }
  EXPECT_EQ(r.m.revision(), revision);
  EXPECT_TRUE(r.m.contains(widget));
}

TEST(WidgetChanges, QueriesChangeNothingAndCopiesAreNewInstances) {
  Rig r;
  const std::uint64_t before = r.m.revision();
  Ray ray;
  ray.origin = Eigen::Vector3d(0.5, 0.5, 5);
  ray.direction = -Eigen::Vector3d::UnitZ();
  (void)r.m.pick(ray);
  (void)r.m.affineFrame(r.push);
  (void)r.m.ffdLattice(r.child);
  (void)r.m.toData();
  EXPECT_EQ(r.m.revision(), before);
  const WidgetModel copy = r.m;
  EXPECT_NE(copy.instance(), r.m.instance());
  EXPECT_EQ(copy.revision(), r.m.revision());
  const std::uint64_t instance = r.m.instance();
  const WidgetModel moved = std::move(r.m);
  EXPECT_EQ(moved.instance(), instance);
  EXPECT_NE(WidgetModel::fromData(moved.toData()).instance(), instance);
}

}  // namespace
}  // namespace ffdkit::widgets
