// The GUI-free interaction controller: rays in, gestures, live deformation and one undo command
// per gesture out (STYLE 10, 15). No window, no display.
#include <QTest>

#include <cmath>

#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/widgets/thesis_examples.h"

using namespace ffdkit;
using app::InteractionController;
using widgets::WidgetId;

namespace {

// A sphere primitive with a 3x3x3 lattice attached and a translate widget on the top point.
struct Fixture {
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  InteractionController controller{scene, deformer, commands};
  widgets::WidgetId lattice, widget;
  std::string sphere;

  Fixture() {
    sphere = controller.addPrimitive({});
    lattice = controller.newLattice({});
    widget = controller.addAffineAtPoint({lattice, 1 + 3 * (1 + 3 * 2)}, widgets::AffineKind::Translate);
    controller.attachLattice(lattice, sphere);
  }
  // A ray looking down -y at a world point (the translate axis is world +x).
  static widgets::Ray rayTo(const Eigen::Vector3d& p) {
    widgets::Ray r;
    r.origin = p + Eigen::Vector3d(0, -5, 0);
    r.direction = Eigen::Vector3d(0, 1, 0);
    return r;
  }
};

// A ray looking along -view at the world point p.
widgets::Ray looking(const Eigen::Vector3d& p, const Eigen::Vector3d& view) { return {p + 10.0 * view, -view}; }

double maxDifference(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) { return (a - b).cwiseAbs().maxCoeff(); }

}  // namespace

class InteractionControllerTest : public QObject {
  Q_OBJECT

 private slots:
  void looksChangeAsOneUndoableCommandWithoutReDeforming() {
    Fixture f;
    f.controller.setVariation(f.widget, 0.2);
    const Eigen::MatrixX3d deformed = f.deformer.points(f.sphere);
    const std::size_t position = f.commands.position();
    int notified = 0;
    f.controller.onChanged = [&] { ++notified; };
    scenes::DisplaySettings look = f.scene.findObject(f.sphere)->display;
    look.surfaceStyle = scenes::SurfaceStyle::Zebra;
    look.zebraStripes = 5;
    f.controller.setDisplay({f.sphere}, {look}, "Zebra");
    QVERIFY(f.scene.findObject(f.sphere)->display == look);
    QCOMPARE(f.commands.position(), position + 1);
    QCOMPARE(f.commands.undoDescription(), std::string("Zebra"));
    QCOMPARE(notified, 1);
    QVERIFY(maxDifference(f.deformer.points(f.sphere), deformed) == 0.0);
    f.commands.undo();
    QCOMPARE(f.scene.findObject(f.sphere)->display.surfaceStyle, scenes::SurfaceStyle::Shaded);
    f.commands.redo();
    QCOMPARE(f.scene.findObject(f.sphere)->display.zebraStripes, 5);
    // The same look again is no command.
    f.controller.setDisplay({f.sphere}, {look});
    QCOMPARE(f.commands.position(), position + 1);
    // Refused, with nothing changed.
    scenes::DisplaySettings bad = look;
    bad.zebraStripes = 0;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, f.controller.setDisplay({f.sphere}, {bad}));
    bad = look;
    bad.combScale = -1.0;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, f.controller.setDisplay({f.sphere}, {bad}));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, f.controller.setDisplay({"nobody"}, {look}));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, f.controller.setDisplay({f.sphere}, {}));
    QVERIFY(f.scene.findObject(f.sphere)->display == look);
    QCOMPARE(f.commands.position(), position + 1);
  }

  void operationsBuildTheModelAsUndoableCommands() {
    Fixture f;
    QCOMPARE(f.commands.position(), std::size_t(4));
    QCOMPARE(f.scene.widgets.type(f.widget), widgets::WidgetType::Affine);
    QCOMPARE(f.scene.attachments().size(), std::size_t(1));
    QCOMPARE(f.scene.latticesDeforming(f.sphere).size(), std::size_t(1));
    // The lattice was fitted to the sphere's bounding box: the sphere's extent is inside it.
    const Eigen::MatrixX3d corners = f.scene.widgets.worldControlPoints(f.lattice);
    QVERIFY(corners.col(0).minCoeff() < -0.5 && corners.col(0).maxCoeff() > 0.5);
    f.commands.undo();  // attach
    QVERIFY(f.scene.attachments().empty());
    f.commands.undo();  // widget
    QVERIFY(f.scene.widgets.widgets(widgets::WidgetType::Affine).empty());
    f.commands.redo();
    f.commands.redo();
    QCOMPARE(f.scene.attachments().size(), std::size_t(1));
    QVERIFY(f.scene.widgets.contains(f.widget));
  }

  void dragDeformsLiveAsTheModelPredictsAndUndoRestores() {
    Fixture f;
    const Eigen::MatrixX3d before = f.deformer.points(f.sphere);
    scenes::Scene expected = f.scene;  // the same model, driven by setVariation instead of rays
    const widgets::WidgetFrame frame = f.scene.widgets.affineFrame(f.widget);
    const Eigen::Vector3d o = frame.frame.translation(), x = frame.frame.linear().col(0);
    const Eigen::Vector3d grab = o + 0.5 * frame.size * x;

    QCOMPARE(f.controller.press(Fixture::rayTo(grab), 0.01), InteractionController::PressResult::Widget);
    QVERIFY(f.controller.dragging());
    f.controller.drag(Fixture::rayTo(grab + 0.1 * x));
    QVERIFY(!f.controller.highlights().visited.empty());  // the gesture visits the widget and its cell
    f.controller.drag(Fixture::rayTo(grab + 0.25 * x));
    QVERIFY(maxDifference(f.deformer.points(f.sphere), before) > 0.01);  // live, before release
    f.controller.release();
    QCOMPARE(f.commands.position(), std::size_t(5));
    QVERIFY(std::abs(f.scene.widgets.variation(f.widget) - 0.25) < 1e-9);

    expected.widgets.setVariation(f.widget, 0.25);
    scenes::SceneDeformer model;
    model.update(expected);
    model.finishGesture(expected);
    QVERIFY(maxDifference(f.deformer.points(f.sphere), model.points(f.sphere)) < 1e-9);

    f.commands.undo();
    QVERIFY(maxDifference(f.deformer.points(f.sphere), before) < 1e-12);
    QCOMPARE(f.scene.widgets.variation(f.widget), 0.0);
    f.commands.redo();
    QVERIFY(maxDifference(f.deformer.points(f.sphere), model.points(f.sphere)) < 1e-9);
  }

  void pressOnEmptySpaceMissesAndAPointIsPicked() {
    Fixture f;
    widgets::Ray away;
    away.origin = Eigen::Vector3d(10, 10, 10);
    away.direction = Eigen::Vector3d(1, 0, 0);
    QCOMPARE(f.controller.press(away, 0.01), InteractionController::PressResult::Nothing);
    const Eigen::Vector3d corner = f.scene.widgets.worldControlPoints(f.lattice).row(0);
    QCOMPARE(f.controller.press(Fixture::rayTo(corner), 0.01), InteractionController::PressResult::Point);
    QVERIFY(f.controller.pickedPoint().has_value());
    QCOMPARE(f.controller.pickedPoint()->index, Eigen::Index(0));
  }

  void boundWidgetsMoveTogether() {
    Fixture f;
    const auto second = f.controller.addAffineAtPoint({f.lattice, 0}, widgets::AffineKind::Translate);
    const auto binding = f.controller.bind(f.widget, second);
    QCOMPARE(f.scene.widgets.binding(binding).kind, widgets::BindingKind::Variation);
    const widgets::WidgetFrame frame = f.scene.widgets.affineFrame(f.widget);
    const Eigen::Vector3d grab = frame.frame.translation() + 0.5 * frame.size * frame.frame.linear().col(0);
    f.controller.press(Fixture::rayTo(grab), 0.01);
    f.controller.drag(Fixture::rayTo(grab + 0.2 * frame.frame.linear().col(0)));
    f.controller.release();
    QVERIFY(std::abs(f.scene.widgets.variation(second) - 0.2) < 1e-9);
  }

  void aFailedOperationLeavesNoCommand() {
    Fixture f;
    const std::size_t n = f.commands.position();
    QVERIFY_THROWS_EXCEPTION(std::exception, f.controller.bind(f.widget, f.widget));
    QCOMPARE(f.commands.position(), n);
  }

  // ---- the transformer manipulator -----------------------------------------------------------

  void transformerShowsForOneAffineOrLatticeWidget() {
    Fixture f;
    QCOMPARE(f.controller.selection(), std::vector{f.widget});  // a new widget is selected: its transformer shows
    f.controller.clearSelection();
    QVERIFY(!f.controller.transformer());
    f.controller.setSelection({f.widget});
    const auto t = f.controller.transformer();
    QVERIFY(t.has_value());
    const widgets::WidgetFrame frame = f.scene.widgets.affineFrame(f.widget);
    QVERIFY(t->frame.isApprox(frame.frame, 1e-15));
    QVERIFY(t->uniformSize);
    QCOMPARE(t->size, 2.5 * frame.size);
    QVERIFY(f.controller.highlights().transformer.has_value());
    // A lattice: at the centre of its rest box, size handles per axis.
    f.controller.setSelection({f.lattice});
    const Eigen::MatrixX3d rest = f.scene.widgets.worldRestPoints(f.lattice);
    QVERIFY(f.controller.transformer()->frame.translation().isApprox(rest.colwise().mean().transpose(), 1e-14));
    QVERIFY(!f.controller.transformer()->uniformSize);
    // Two widgets, a cell, nothing: no transformer.
    f.controller.setSelection({f.widget, f.lattice});
    QVERIFY(!f.controller.transformer());
    f.controller.setSelection({*f.scene.widgets.attachedCell(f.widget)});
    QVERIFY(!f.controller.transformer());
    f.controller.clearSelection();
    QVERIFY(!f.controller.highlights().transformer.has_value());
  }

  void hoveringAHandleHighlightsIt() {
    Fixture f;
    f.controller.setSelection({f.widget});
    const auto t = *f.controller.transformer();
    const Eigen::Vector3d cube = t.frame * Eigen::Vector3d(0, app::TransformerLayout::sizeAt * t.size, 0);
    QVERIFY(f.controller.hover(looking(cube, t.frame.linear().col(2)), 1e-3));
    QCOMPARE(f.controller.highlights().transformerHandle, std::optional(app::TransformerHandle::SizeY));
    QVERIFY(!f.controller.highlights().hovered.has_value());
    QVERIFY(f.controller.hover(looking(cube + Eigen::Vector3d(5, 5, 5), t.frame.linear().col(2)), 1e-3));
    QVERIFY(!f.controller.highlights().transformerHandle.has_value());
  }

  // Moving, turning and sizing an affine widget changes its placement: the widget moves by
  // exactly the drag, the lattice and the sphere do not; each drag is one command.
  void transformerSetsAnAffineWidgetsPlacement() {
    Fixture f;
    f.controller.setVariation(f.widget, 0.1);
    const Eigen::MatrixX3d points = f.scene.widgets.controlPoints(f.lattice);
    const Eigen::MatrixX3d sphere = f.deformer.points(f.sphere);
    f.controller.setSelection({f.widget});
    const app::Transformer t = *f.controller.transformer();
    const Eigen::Vector3d o = t.frame.translation(), z = t.frame.linear().col(2);
    const Eigen::Vector3d view = (t.frame.linear().col(0) + t.frame.linear().col(1)).normalized();
    const std::size_t position = f.commands.position();

    // Move z by 0.3.
    QCOMPARE(f.controller.press(looking(o + 0.7 * t.size * z, view), 1e-3), InteractionController::PressResult::Handle);
    f.controller.drag(looking(o + (0.7 * t.size + 0.3) * z, view));
    f.controller.release();
    widgets::WidgetFrame now = f.scene.widgets.affineFrame(f.widget);
    QVERIFY(now.frame.translation().isApprox(o + 0.3 * z, 1e-12));
    QVERIFY(now.frame.linear().isApprox(t.frame.linear(), 1e-12));
    QCOMPARE(f.scene.widgets.controlPoints(f.lattice), points);
    QCOMPARE(f.deformer.points(f.sphere), sphere);
    QCOMPARE(f.commands.position(), position + 1);
    QVERIFY(f.commands.undoDescription().rfind("Move z ", 0) == 0);
    QCOMPARE(f.scene.widgets.variation(f.widget), 0.1);  // the variation is not touched

    // Turn z by a quarter: the translate axis (world x) now points along world y, and the
    // next variation moves the point along y.
    const app::Transformer t2 = *f.controller.transformer();
    const Eigen::Vector3d o2 = t2.frame.translation();
    const Eigen::Vector3d x = t2.frame.linear().col(0), y = t2.frame.linear().col(1);
    const double r = app::TransformerLayout::turnRadius * t2.size;
    QCOMPARE(f.controller.press(looking(o2 + r * (std::cos(0.3) * x + std::sin(0.3) * y), z), 1e-3),
             InteractionController::PressResult::Handle);
    f.controller.drag(looking(o2 + r * (std::cos(0.3 + M_PI / 2) * x + std::sin(0.3 + M_PI / 2) * y), z));
    f.controller.release();
    now = f.scene.widgets.affineFrame(f.widget);
    QVERIFY(now.frame.linear().col(0).isApprox(y, 1e-12));
    QVERIFY(now.frame.translation().isApprox(o2, 1e-12));
    const Eigen::Index top = 1 + 3 * (1 + 3 * 2);
    const Eigen::Vector3d before = f.scene.widgets.worldControlPoints(f.lattice).row(top).transpose();
    f.controller.setVariation(f.widget, 0.3);
    const Eigen::Vector3d after = f.scene.widgets.worldControlPoints(f.lattice).row(top).transpose();
    QVERIFY((after - before).isApprox(0.2 * y, 1e-9));
    f.commands.undo();

    // Size: twice as big, about its origin.
    const app::Transformer t3 = *f.controller.transformer();
    const double at = app::TransformerLayout::sizeAt * t3.size;
    const Eigen::Vector3d x3 = t3.frame.linear().col(0);
    QCOMPARE(f.controller.press(looking(t3.frame * Eigen::Vector3d(at, 0, 0), z), 1e-3),
             InteractionController::PressResult::Handle);
    f.controller.drag(looking(t3.frame.translation() + 2.0 * at * x3, z));
    f.controller.release();
    now = f.scene.widgets.affineFrame(f.widget);
    QVERIFY(std::abs(now.size - 2.0 * t3.size / 2.5) < 1e-12);
    QVERIFY(now.frame.translation().isApprox(t3.frame.translation(), 1e-12));

    // Undo all three: the placement of the start.
    while (f.commands.position() > position) f.commands.undo();
    QVERIFY(f.scene.widgets.affineFrame(f.widget).frame.isApprox(t.frame, 1e-14));
    QCOMPARE(f.deformer.points(f.sphere), sphere);
  }

  void escapeDuringAHandleDragPutsTheWidgetBack() {
    Fixture f;
    f.controller.setSelection({f.widget});
    const app::Transformer t = *f.controller.transformer();
    const Eigen::Vector3d o = t.frame.translation(), z = t.frame.linear().col(2);
    const Eigen::Vector3d view = (t.frame.linear().col(0) + t.frame.linear().col(1)).normalized();
    const Eigen::Affine3d placement = f.scene.widgets.placement(f.widget);
    const std::size_t position = f.commands.position();
    f.controller.press(looking(o + 0.7 * t.size * z, view), 1e-3);
    f.controller.drag(looking(o + (0.7 * t.size + 0.5) * z, view));
    QVERIFY(!f.scene.widgets.placement(f.widget).isApprox(placement));
    f.controller.cancel();
    QCOMPARE(f.scene.widgets.placement(f.widget).matrix(), placement.matrix());
    QCOMPARE(f.commands.position(), position);
    QVERIFY(!f.controller.dragging());
  }

  // Turning a deformed lattice with its transformer: the frame turns about the lattice's centre,
  // the sphere is re-embedded, and its points are what a lattice set to that frame directly
  // gives (computed independently on a copy); undo restores the sphere exactly.
  void transformerTurnsALatticeAndTheSphereFollowsTheModel() {
    Fixture f;
    f.controller.setVariation(f.widget, 0.3);
    const Eigen::MatrixX3d sphere = f.deformer.points(f.sphere);
    const Eigen::Affine3d frame = f.scene.widgets.latticeFrame(f.lattice);
    f.controller.setSelection({f.lattice});
    const app::Transformer t = *f.controller.transformer();
    const Eigen::Vector3d o = t.frame.translation();
    const Eigen::Vector3d x = t.frame.linear().col(0), y = t.frame.linear().col(1), z = t.frame.linear().col(2);
    const double r = app::TransformerLayout::turnRadius * t.size;
    auto onRing = [&](double a) { return looking(o + r * (std::cos(a) * y + std::sin(a) * z), x); };
    QCOMPARE(f.controller.press(onRing(0.4), 1e-3), InteractionController::PressResult::Handle);
    f.controller.drag(onRing(0.4 + 0.2));
    QVERIFY(maxDifference(f.deformer.points(f.sphere), sphere) > 1e-3);  // live
    f.controller.drag(onRing(0.4 + 0.5));
    f.controller.release();
    const Eigen::Affine3d turn = Eigen::Translation3d(o) * Eigen::AngleAxisd(0.5, x) * Eigen::Translation3d(-o);
    QVERIFY(f.scene.widgets.latticeFrame(f.lattice).isApprox(turn * frame, 1e-12));
    QVERIFY(f.commands.undoDescription().rfind("Turn x ", 0) == 0);

    scenes::Scene expected = f.scene;
    expected.widgets.setLatticeFrame(f.lattice, turn * frame);
    scenes::SceneDeformer independent;
    independent.finishGesture(expected);
    QVERIFY(maxDifference(f.deformer.points(f.sphere), independent.points(f.sphere)) < 1e-12);

    // Size along y by 1.5, then undo both.
    const app::Transformer t2 = *f.controller.transformer();
    const double at = app::TransformerLayout::sizeAt * t2.size;
    const Eigen::Vector3d y2 = t2.frame.linear().col(1);
    QCOMPARE(f.controller.press(looking(t2.frame.translation() + at * y2, t2.frame.linear().col(2)), 1e-3),
             InteractionController::PressResult::Handle);
    f.controller.drag(looking(t2.frame.translation() + 1.5 * at * y2, t2.frame.linear().col(2)));
    f.controller.release();
    // The lattice's extent along y2 grew by 1.5 about the centre: its rest points' spread.
    auto spread = [&widgets = f.scene.widgets, lattice = f.lattice](const Eigen::Vector3d& axis) {
      const Eigen::VectorXd d = widgets.worldRestPoints(lattice) * axis;
      return d.maxCoeff() - d.minCoeff();
    };
    f.commands.undo();
    const double spreadBefore = spread(y2);
    f.commands.redo();
    QVERIFY(std::abs(spread(y2) - 1.5 * spreadBefore) < 1e-9);
    QVERIFY((f.controller.transformer()->frame.translation() - o).norm() < 1e-12);
    f.commands.undo();
    f.commands.undo();
    QVERIFY(f.scene.widgets.latticeFrame(f.lattice).isApprox(frame, 1e-14));
    QVERIFY(maxDifference(f.deformer.points(f.sphere), sphere) < 1e-12);
  }

  // A child lattice's transformer moves it through its gesture: the hierarchy binding carries
  // the motion to the parent's face, and the child follows that face (Fig. 6-9).
  void aChildLatticesTransformerMovesItsParentCell() {
    scenes::Scene scene;
    scenes::SceneDeformer deformer;
    scenes::CommandStack commands;
    InteractionController controller(scene, deformer, commands);
    widgets::Fig69 fig = widgets::buildFig69();
    // The child straddles the top face, centred on it: the face's lift arrow runs up the child's
    // z handle, and a glyph is picked before a handle. This test is about the handle.
    fig.model.remove(fig.faceLift);
    controller.replaceWidgets(fig.model);
    const Eigen::Affine3d frame = scene.widgets.latticeFrame(fig.child);
    const Eigen::MatrixX3d parent = scene.widgets.controlPoints(fig.parent);
    controller.setSelection({fig.child});
    const app::Transformer t = *controller.transformer();
    const Eigen::Vector3d o = t.frame.translation(), z = t.frame.linear().col(2);
    const Eigen::Vector3d view = (t.frame.linear().col(0) + t.frame.linear().col(1)).normalized();
    QCOMPARE(controller.press(looking(o + 0.6 * t.size * z, view), 1e-3), InteractionController::PressResult::Handle);
    controller.drag(looking(o + (0.6 * t.size + 0.2) * z, view));
    controller.release();
    QVERIFY(scene.widgets.latticeFrame(fig.child).isApprox(Eigen::Translation3d(0.2 * z) * frame, 1e-12));
    const Eigen::MatrixX3d moved = scene.widgets.controlPoints(fig.parent) - parent;
    QVERIFY(std::abs(moved.col(2).maxCoeff() - 0.2 * z.z()) < 1e-12);  // the top face rose with it
    QVERIFY(std::abs(moved.col(2).minCoeff()) < 1e-12);                // the bottom stayed
    commands.undo();
    QVERIFY(scene.widgets.latticeFrame(fig.child).isApprox(frame, 1e-14));
    QCOMPARE(scene.widgets.controlPoints(fig.parent), parent);
  }

  // ---- direct manipulation -------------------------------------------------------------------

  // Dragging a point of the sphere: the lattice gets the least-norm change that puts the point
  // exactly on the pointer ray; far points move less; one command; undo and cancel restore.
  void draggingAnObjectPointMovesItExactlyUnderThePointer() {
    Fixture f;
    f.controller.clearSelection();
    const Eigen::MatrixX3d before = f.deformer.points(f.sphere);
    const Eigen::MatrixX3d control = f.scene.widgets.controlPoints(f.lattice);
    const std::size_t position = f.commands.position();
    widgets::Ray ray{Eigen::Vector3d(5.0, 0.1, 0.2), Eigen::Vector3d(-1.0, 0.0, 0.0)};
    QCOMPARE(f.controller.pressObject(ray, 1e-3), std::optional<std::string>(f.sphere));
    QVERIFY(f.controller.dragging());
    const auto [object, vertex] = *f.controller.grabbedPoint();
    QVERIFY(object == f.scene.objectId(f.sphere));
    const Eigen::Vector3d grab = before.row(vertex).transpose();
    QVERIFY(grab.x() > 0.2);  // on the side facing the ray
    // The pointer moves by (0, 0.1, 0.05) in the drag plane (normal: the ray, -x).
    const Eigen::Vector3d offset(0.0, 0.1, 0.05);
    f.controller.drag({Eigen::Vector3d(5.0, grab.y(), grab.z()) + offset, Eigen::Vector3d(-1.0, 0.0, 0.0)});
    QVERIFY((f.deformer.points(f.sphere).row(vertex).transpose() - (grab + offset)).norm() < 1e-9);  // live
    f.controller.drag({Eigen::Vector3d(5.0, grab.y(), grab.z()) + 2.0 * offset, Eigen::Vector3d(-1.0, 0.0, 0.0)});
    f.controller.release();
    QVERIFY(!f.controller.grabbedPoint());
    const Eigen::MatrixX3d after = f.deformer.points(f.sphere);
    QVERIFY((after.row(vertex).transpose() - (grab + 2.0 * offset)).norm() < 1e-9);
    // Smooth: the opposite side of the sphere moves much less than the grabbed point.
    Eigen::Index far = 0;
    (before.rowwise() - grab.transpose()).rowwise().norm().maxCoeff(&far);
    QVERIFY((after.row(far) - before.row(far)).norm() < 0.5 * (2.0 * offset).norm());
    QCOMPARE(f.commands.position(), position + 1);
    QVERIFY(f.commands.undoDescription().rfind("Drag point ", 0) == 0);
    // The deformation is the model's: a fresh deformer of the same scene gives the same points.
    QVERIFY(maxDifference(after, scenes::deformScene(f.scene).at(f.sphere)) < 1e-12);
    f.commands.undo();
    QCOMPARE(f.scene.widgets.controlPoints(f.lattice), control);
    QVERIFY(maxDifference(f.deformer.points(f.sphere), before) < 1e-12);

    // Esc (cancel) mid-drag puts the lattice back; a miss grabs nothing.
    QVERIFY(f.controller.pressObject(ray, 1e-3).has_value());
    f.controller.drag({Eigen::Vector3d(5.0, grab.y(), grab.z()) + offset, Eigen::Vector3d(-1.0, 0.0, 0.0)});
    f.controller.cancel();
    QCOMPARE(f.scene.widgets.controlPoints(f.lattice), control);
    QVERIFY(maxDifference(f.deformer.points(f.sphere), before) < 1e-12);
    QCOMPARE(f.commands.position(), position);
    QVERIFY(!f.controller.pressObject({Eigen::Vector3d(5.0, 5.0, 5.0), Eigen::Vector3d(1.0, 0.0, 0.0)}, 1e-3));
  }

  // Pins (headless): pinned object points keep their place within 1e-9 while another point is
  // dragged onto the pointer; with carryPins they move by the dragged point's displacement.
  // Pins are no edit; they are drawn (highlights) and pruned with their object.
  void pinnedPointsHoldOrMoveAlong() {
    Fixture f;
    f.controller.clearSelection();
    const Eigen::MatrixX3d before = f.deformer.points(f.sphere);
    Eigen::Index top = 0, bottom = 0;
    before.col(2).maxCoeff(&top);
    before.col(2).minCoeff(&bottom);
    const std::size_t position = f.commands.position();
    f.controller.togglePin({f.scene.objectId(f.sphere), top});
    f.controller.togglePin({f.scene.objectId(f.sphere), bottom});
    const scenes::ObjectId sphere = f.scene.objectId(f.sphere);
    f.controller.togglePin({sphere, 7});
    f.controller.togglePin({sphere, 7});  // a second toggle unpins
    QCOMPARE(f.controller.pins().size(), std::size_t{2});
    QCOMPARE(f.commands.position(), position);
    QCOMPARE(f.controller.highlights().pins.size(), std::size_t{2});
    QVERIFY((f.controller.highlights().pins[0] - before.row(top).transpose()).norm() == 0.0);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, f.controller.togglePin({sphere, before.rows()}));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, f.controller.togglePin({scenes::ObjectId{999}, 0}));

    const widgets::Ray ray{Eigen::Vector3d(5.0, 0.1, 0.2), Eigen::Vector3d(-1.0, 0.0, 0.0)};
    const Eigen::Vector3d offset(0.0, 0.1, 0.05);
    for (bool carry : {false, true}) {
      const Eigen::MatrixX3d start = f.deformer.points(f.sphere);
      QVERIFY(f.controller.pressObject(ray, 1e-3, carry).has_value());
      const Eigen::Index vertex = f.controller.grabbedPoint()->second;
      const Eigen::Vector3d grab = start.row(vertex).transpose();
      for (int step = 1; step <= 3; ++step) {
        f.controller.drag({Eigen::Vector3d(5.0, grab.y(), grab.z()) + step * offset, Eigen::Vector3d(-1.0, 0.0, 0.0)});
        const Eigen::MatrixX3d now = f.deformer.points(f.sphere);
        QVERIFY((now.row(vertex).transpose() - (grab + step * offset)).norm() < 1e-9);  // on the pointer
        for (Eigen::Index pin : {top, bottom}) {
          const Eigen::Vector3d expected = start.row(pin).transpose() + (carry ? double(step) : 0.0) * offset;
          QVERIFY2((now.row(pin).transpose() - expected).norm() < 1e-9,
                   qPrintable(QString("pin %1 off by %2 (carry %3)").arg(pin).arg((now.row(pin).transpose() - expected).norm()).arg(carry)));
        }
      }
      f.controller.release();
      QCOMPARE(f.commands.position(), position + (carry ? 2 : 1));
      QVERIFY(maxDifference(f.deformer.points(f.sphere), scenes::deformScene(f.scene).at(f.sphere)) < 1e-12);
    }
    // Without pins the same drag moves them: the constraint is what holds them.
    f.controller.clearPins();
    QVERIFY(f.controller.highlights().pins.empty());
    const Eigen::MatrixX3d start = f.deformer.points(f.sphere);
    QVERIFY(f.controller.pressObject(ray, 1e-3).has_value());
    const Eigen::Vector3d grab = start.row(f.controller.grabbedPoint()->second).transpose();
    f.controller.drag({Eigen::Vector3d(5.0, grab.y(), grab.z()) + offset, Eigen::Vector3d(-1.0, 0.0, 0.0)});
    f.controller.release();
    QVERIFY((f.deformer.points(f.sphere).row(top) - start.row(top)).norm() > 1e-4);
    // Pins go with their object.
    f.controller.togglePin({f.scene.objectId(f.sphere), top});
    f.controller.removeObjects({f.sphere});
    QVERIFY(f.controller.pins().empty());
  }

  void anObjectWithoutALatticeCannotBeDraggedAndSaysWhy() {
    Fixture f;
    scenes::PrimitiveOptions cube;
    cube.kind = scenes::PrimitiveKind::Cube;
    cube.placement = Eigen::Translation3d(3.0, 0.0, 0.0);
    const std::string name = f.controller.addPrimitive(cube);
    try {
      f.controller.pressObject({Eigen::Vector3d(3.0, 0.0, 5.0), Eigen::Vector3d(0.0, 0.0, -1.0)}, 1e-3);
      QFAIL("expected std::invalid_argument");
    } catch (const std::invalid_argument& e) {
      QVERIFY2(std::string(e.what()).find("'" + name + "' is not deformed by a lattice") != std::string::npos, e.what());
    }
    QVERIFY(!f.controller.dragging());
  }

  // A lattice tree (Kuriyama 1996, sec. 6.2.3): a child lattice around the sphere's top cap, bound to the top slab
  // of the sphere's lattice. A point of the cap (inside the child) is moved by the child; a
  // point at the bottom (outside it: the identity outside policy leaves it alone) by the parent.
  // Both land on the pointer.
  void directManipulationPicksTheLatticeThatHoldsThePoint() {
    Fixture f;
    const WidgetId top = f.scene.widgets.addCell(f.lattice, widgets::CellSpec::slab(2, 2), "top");
    const WidgetId child = f.controller.newLattice({});
    f.controller.setLatticeFrame(child, Eigen::Translation3d(-0.3, -0.3, 0.2) * Eigen::Scaling(0.6, 0.6, 0.45));
    f.controller.bind(top, child);
    QCOMPARE(f.scene.widgets.parentLattice(child), std::optional(f.lattice));
    f.controller.clearSelection();
    const Eigen::MatrixX3d before = f.deformer.points(f.sphere);
    Eigen::Index highest = 0, lowest = 0;
    before.col(2).maxCoeff(&highest);
    before.col(2).minCoeff(&lowest);
    for (Eigen::Index vertex : {highest, lowest}) {
      const Eigen::Vector3d view = vertex == highest ? Eigen::Vector3d(0, 0, -1) : Eigen::Vector3d(0, 0, 1);
      const Eigen::Vector3d p = before.row(vertex).transpose();
      QVERIFY(f.controller.pressObject({p - 5.0 * view, view}, 1e-3).has_value());
      const Eigen::Index grabbed = f.controller.grabbedPoint()->second;
      const Eigen::Vector3d grab = before.row(grabbed).transpose();
      const Eigen::MatrixX3d parentBefore = f.scene.widgets.controlPoints(f.lattice);
      const Eigen::MatrixX3d childBefore = f.scene.widgets.controlPoints(child);
      const Eigen::Vector3d offset(0.05, -0.04, 0.0);
      f.controller.drag({grab + offset - 5.0 * view, view});
      f.controller.release();
      QVERIFY((f.deformer.points(f.sphere).row(grabbed).transpose() - (grab + offset)).norm() < 1e-9);
      QCOMPARE(f.scene.widgets.controlPoints(child) != childBefore, vertex == highest);
      QCOMPARE(f.scene.widgets.controlPoints(f.lattice) != parentBefore, vertex == lowest);
      f.commands.undo();
      QVERIFY(maxDifference(f.deformer.points(f.sphere), before) < 1e-12);
    }
  }
};

QTEST_APPLESS_MAIN(InteractionControllerTest)
#include "interaction_controller_test.moc"
