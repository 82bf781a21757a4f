// The GUI-free interaction controller: rays in, gestures, live deformation and one undo command
// per gesture out (STYLE 10, 15). No window, no display.
#include <QTest>

#include <cmath>

#include "ffdkit/app/interaction_controller.h"
#include "ffdkit/scenes/scene_deformer.h"

using namespace ffdkit;
using app::InteractionController;

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
    QCOMPARE(f.scene.attachments.size(), std::size_t(1));
    QCOMPARE(f.scene.latticesDeforming(f.sphere).size(), std::size_t(1));
    // The lattice was fitted to the sphere's bounding box: the sphere's extent is inside it.
    const Eigen::MatrixX3d corners = f.scene.widgets.worldControlPoints(f.lattice);
    QVERIFY(corners.col(0).minCoeff() < -0.5 && corners.col(0).maxCoeff() > 0.5);
    f.commands.undo();  // attach
    QVERIFY(f.scene.attachments.empty());
    f.commands.undo();  // widget
    QVERIFY(f.scene.widgets.widgets(widgets::WidgetType::Affine).empty());
    f.commands.redo();
    f.commands.redo();
    QCOMPARE(f.scene.attachments.size(), std::size_t(1));
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
};

QTEST_APPLESS_MAIN(InteractionControllerTest)
#include "interaction_controller_test.moc"
