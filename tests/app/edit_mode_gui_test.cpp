// A lattice's edit mode in the real window (Xvfb, real Qt mouse and key events): Tab enters it,
// clicks and boxes select points (the status bar counts them), G with an axis and a typed value
// moves them exactly as one undo step, Make Cell makes each kind (and says why a selection does
// not fit), a group of widgets turns as one undo step, a rotate widget on a point is refused
// with a message, and the thesis's Fig. 6-2 is built from an empty scene through the GUI alone.
#include <QDialog>
#include <QLabel>
#include <QAbstractButton>
#include <QMenu>
#include <QMessageBox>
#include <QTest>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "ffdkit/interaction/edit_controller.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/widgets/thesis_examples.h"
#include "fig62_steps.h"
#include "gui_test_support.h"

using namespace ffdkit;
using app::MainWindow;
using widgets::WidgetId;
using namespace ffdkit::app::testing;

namespace {

// True when every grid point of the unit box is drawn inside the view.
bool unitBoxInView(MainWindow& w) {
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i)
        if (!w.view()->rect().adjusted(4, 4, -4, -4).contains(toWidget(w, Eigen::Vector3d(0.5 * i, 0.5 * j, 0.5 * k))))
          return false;
  return true;
}

QString countText(MainWindow& w) { return w.findChild<QLabel*>("editCount")->text(); }

}  // namespace

class EditModeGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = startWindow();
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  void tabEntersTheEditModeAndClicksAndBoxesSelectPoints() {
    MainWindow& w = *window_;
    const WidgetId lattice = newLatticeInEditMode(w);
    QVERIFY(w.findChild<QAction*>("actionEditMode")->isChecked());
    const app::EditController* edit = &editOf(w);
    QVERIFY(edit->editing());
    QCOMPARE(countText(w), QString("%1: 0 of 27 points selected").arg(QString::fromStdString(w.scene().widgets.name(lattice))));

    clickPoint(w, lattice, flat(2, 0, 2));
    clickPoint(w, lattice, flat(1, 0, 2), Qt::ShiftModifier);
    QCOMPARE(edit->points().indices(), (std::vector<Eigen::Index>{flat(1, 0, 2), flat(2, 0, 2)}));
    clickPoint(w, lattice, flat(2, 0, 2), Qt::ShiftModifier);  // Shift+click toggles it off
    QCOMPARE(edit->points().indices(), std::vector<Eigen::Index>{flat(1, 0, 2)});

    // A box round the whole view takes all 27; Ctrl+box round one point takes it out.
    QVERIFY(unitBoxInView(w));
    dragPixels(w, QPoint(2, 2), QPoint(w.view()->width() - 3, w.view()->height() - 3));
    QCOMPARE(edit->points().count(), Eigen::Index(27));
    QVERIFY(countText(w).endsWith("27 of 27 points selected"));
    const QPoint corner = toWidget(w, Eigen::Vector3d(0, 0, 0));
    sendMouse(w.view(), QEvent::MouseButtonPress, corner - QPoint(5, 5), Qt::LeftButton, Qt::LeftButton, Qt::ControlModifier);
    sendMouse(w.view(), QEvent::MouseMove, corner + QPoint(5, 5), Qt::NoButton, Qt::LeftButton, Qt::ControlModifier);
    sendMouse(w.view(), QEvent::MouseButtonRelease, corner + QPoint(5, 5), Qt::LeftButton, Qt::NoButton, Qt::ControlModifier);
    QCOMPARE(edit->points().count(), Eigen::Index(26));
    QVERIFY(!edit->points().contains(flat(0, 0, 0)));
    // Invert, none, all by their keys; a click on empty space selects nothing.
    pressKey(w, Qt::Key_I, Qt::ControlModifier);
    QCOMPARE(edit->points().indices(), std::vector<Eigen::Index>{flat(0, 0, 0)});
    pressKey(w, Qt::Key_A);
    QCOMPARE(edit->points().count(), Eigen::Index(27));
    pressKey(w, Qt::Key_A, Qt::AltModifier);
    QCOMPARE(edit->points().count(), Eigen::Index(0));
    pressKey(w, Qt::Key_A);
    click(w, QPoint(5, 5));
    QCOMPARE(edit->points().count(), Eigen::Index(0));
    // Linked: the row along i through (0,1,1).
    clickPoint(w, lattice, flat(0, 1, 1));
    action(w, "actionSelectRowsi")->trigger();
    QCOMPARE(edit->points().indices(), (std::vector<Eigen::Index>{flat(0, 1, 1), flat(1, 1, 1), flat(2, 1, 1)}));
    // Alt+drag orbits the camera and leaves the selection alone.
    const Eigen::Vector3d eye = w.sceneView().camera().position;
    sendMouse(w.view(), QEvent::MouseButtonPress, QPoint(40, 40), Qt::LeftButton, Qt::LeftButton, Qt::AltModifier);
    for (int step = 1; step <= 5; ++step)
      sendMouse(w.view(), QEvent::MouseMove, QPoint(40 + 20 * step, 40), Qt::NoButton, Qt::LeftButton, Qt::AltModifier);
    sendMouse(w.view(), QEvent::MouseButtonRelease, QPoint(140, 40), Qt::LeftButton, Qt::NoButton, Qt::AltModifier);
    QVERIFY((w.sceneView().camera().position - eye).norm() > 0.1);
    QCOMPARE(edit->points().count(), Eigen::Index(3));
    pressKey(w, Qt::Key_Tab);
    QVERIFY(!edit->editing());
    QVERIFY(!w.findChild<QLabel*>("editCount")->isVisible());
  }

  void gWithAnAxisAndATypedValueMovesExactlyAsOneUndoStep() {
    MainWindow& w = *window_;
    const WidgetId lattice = newLatticeInEditMode(w);
    clickPoint(w, lattice, flat(1, 1, 2));
    clickPoint(w, lattice, flat(2, 1, 2), Qt::ShiftModifier);
    const Eigen::MatrixX3d start = w.scene().widgets.worldControlPoints(lattice);
    const std::size_t steps = w.commands().position();
    hover(w, toWidget(w, Eigen::Vector3d(0.7, 0.5, 1.0)));
    pressKey(w, Qt::Key_G);
    hover(w, toWidget(w, Eigen::Vector3d(0.9, 0.8, 1.1)));  // the pointer moves the points ...
    QVERIFY((w.scene().widgets.worldControlPoints(lattice) - start).norm() > 0.05);
    pressKey(w, Qt::Key_Z);  // ... along z only, then by the typed 0.5
    typeKeys(w, "0.5");
    QVERIFY2(w.statusMessage().contains("along z"), qPrintable(w.statusMessage()));
    pressKey(w, Qt::Key_Return);
    Eigen::MatrixX3d expected = start;
    expected(flat(1, 1, 2), 2) += 0.5;
    expected(flat(2, 1, 2), 2) += 0.5;
    QCOMPARE((w.scene().widgets.worldControlPoints(lattice) - expected).cwiseAbs().maxCoeff(), 0.0);
    QCOMPARE(w.commands().position(), steps + 1);
    action(w, "actionUndo")->trigger();
    QCOMPARE((w.scene().widgets.worldControlPoints(lattice) - start).cwiseAbs().maxCoeff(), 0.0);

    // X with the pointer: only x changes; Escape puts the points back.
    const Eigen::Vector3d pivot(0.75, 0.5, 1.0);
    hover(w, toWidget(w, pivot));
    pressKey(w, Qt::Key_G);
    pressKey(w, Qt::Key_X);
    hover(w, toWidget(w, pivot + Eigen::Vector3d(0.4, 0.0, 0.0)));
    const Eigen::MatrixX3d moved = w.scene().widgets.worldControlPoints(lattice);
    QVERIFY(std::abs(moved(flat(1, 1, 2), 0) - start(flat(1, 1, 2), 0) - 0.4) < 0.02);
    QCOMPARE(moved(flat(1, 1, 2), 1), start(flat(1, 1, 2), 1));
    QCOMPARE(moved(flat(1, 1, 2), 2), start(flat(1, 1, 2), 2));
    pressKey(w, Qt::Key_Escape);
    QCOMPARE((w.scene().widgets.worldControlPoints(lattice) - start).cwiseAbs().maxCoeff(), 0.0);
    QCOMPARE(w.commands().position(), steps);
  }

  // A number typed while a transformer handle is held sets its amount exactly (as for one
  // widget's glyph or handle): the edit mode's z arrow by 0.5, a group's z ring by 90 degrees;
  // each one undo step.
  void aValueTypedDuringAHandleDragSetsItsAmountExactly() {
    MainWindow& w = *window_;
    const auto& m = w.scene().widgets;
    const WidgetId lattice = newLatticeInEditMode(w);
    clickPoint(w, lattice, flat(1, 1, 2));
    clickPoint(w, lattice, flat(2, 1, 2), Qt::ShiftModifier);
    QCOMPARE(editOf(w).points().count(), Eigen::Index(2));
    const Eigen::MatrixX3d start = m.worldControlPoints(lattice);
    const std::size_t steps = w.commands().position();
    const app::Transformer t = *editOf(w).transformer();
    const Eigen::Vector3d o = t.frame.translation(), z = Eigen::Vector3d::UnitZ();
    const QPoint grab = toWidget(w, o + 0.6 * t.size * z);
    sendMouse(w.view(), QEvent::MouseButtonPress, grab, Qt::LeftButton, Qt::LeftButton);
    QCOMPARE(editOf(w).draggedHandle(), std::optional(app::TransformerHandle::MoveZ));
    sendMouse(w.view(), QEvent::MouseMove, toWidget(w, o + 0.8 * t.size * z), Qt::NoButton, Qt::LeftButton);
    QVERIFY((m.worldControlPoints(lattice) - start).norm() > 0.05);  // the pointer moves them ...
    typeKeys(w, "0.5");                                               // ... then the typed amount
    QVERIFY2(w.statusMessage().contains("typed 0.5"), qPrintable(w.statusMessage()));
    sendMouse(w.view(), QEvent::MouseMove, toWidget(w, o + 0.7 * t.size * z), Qt::NoButton, Qt::LeftButton);  // the typed value rules
    pressKey(w, Qt::Key_Return);
    sendMouse(w.view(), QEvent::MouseButtonRelease, grab, Qt::LeftButton, Qt::NoButton);
    Eigen::MatrixX3d expected = start;
    expected(flat(1, 1, 2), 2) += 0.5;
    expected(flat(2, 1, 2), 2) += 0.5;
    QCOMPARE((m.worldControlPoints(lattice) - expected).cwiseAbs().maxCoeff(), 0.0);
    QCOMPARE(w.commands().position(), steps + 1);
    action(w, "actionUndo")->trigger();
    QCOMPARE((m.worldControlPoints(lattice) - start).cwiseAbs().maxCoeff(), 0.0);
    pressKey(w, Qt::Key_Tab);
    QVERIFY(!editOf(w).editing());

    // A group of two lattices: its z ring, turned by a typed 90 degrees about the group's pivot.
    triggerWithDialog(w, "actionNewLattice");
    const WidgetId other = m.roots().back();
    w.controller().setLatticeFrame(other, Eigen::Affine3d(Eigen::Translation3d(1.5, 0, 0)));
    clickRow(w, QString::fromStdString(m.name(lattice)));
    clickRow(w, QString::fromStdString(m.name(other)), Qt::ControlModifier);
    QCOMPARE(w.controller().selection().size(), std::size_t(2));
    const Eigen::Affine3d a0 = m.latticeFrame(lattice), b0 = m.latticeFrame(other);
    const app::Transformer g = *editOf(w).transformer();
    const Eigen::Vector3d pivot = g.frame.translation();
    QVERIFY(pivot.isApprox(Eigen::Vector3d(1.25, 0.5, 0.5), 1e-14));
    const double r = app::TransformerLayout::turnRadius * g.size;
    auto onRing = [&](double degrees) {
      const double a = degrees * std::numbers::pi / 180.0;
      return toWidget(w, pivot + r * Eigen::Vector3d(std::cos(a), std::sin(a), 0));
    };
    const std::size_t groupSteps = w.commands().position();
    sendMouse(w.view(), QEvent::MouseButtonPress, onRing(-70), Qt::LeftButton, Qt::LeftButton);
    QCOMPARE(editOf(w).draggedHandle(), std::optional(app::TransformerHandle::TurnZ));
    sendMouse(w.view(), QEvent::MouseMove, onRing(-50), Qt::NoButton, Qt::LeftButton);
    typeKeys(w, "90");
    pressKey(w, Qt::Key_Return);
    sendMouse(w.view(), QEvent::MouseButtonRelease, onRing(-50), Qt::LeftButton, Qt::NoButton);
    const Eigen::Affine3d turn =
        Eigen::Translation3d(pivot) * Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(-pivot);
    QVERIFY(m.latticeFrame(lattice).matrix().isApprox((turn * a0).matrix(), 1e-12));
    QVERIFY(m.latticeFrame(other).matrix().isApprox((turn * b0).matrix(), 1e-12));
    QCOMPARE(w.commands().position(), groupSteps + 1);
    action(w, "actionUndo")->trigger();
    QVERIFY(m.latticeFrame(lattice).matrix().isApprox(a0.matrix(), 1e-15));
    QVERIFY(m.latticeFrame(other).matrix().isApprox(b0.matrix(), 1e-15));
  }

  // An undo that removes the edited lattice ends the mode, and the toolbar toggle follows; a redo
  // does not bring the mode back.
  void theEditModeToggleFollowsAnUndoThatRemovesTheLattice() {
    MainWindow& w = *window_;
    triggerWithDialog(w, "actionNewLattice");
    lookAtUnitBox(w);
    QAction* toggle = action(w, "actionEditMode");
    pressKey(w, Qt::Key_Tab);
    QVERIFY(toggle->isChecked());
    QVERIFY(editOf(w).editing());
    pressKey(w, Qt::Key_A);
    pressKey(w, Qt::Key_Z, Qt::ControlModifier);  // undo New Lattice
    QVERIFY(w.scene().widgets.roots().empty());
    QVERIFY(!editOf(w).editing());
    QVERIFY(!toggle->isChecked());
    QVERIFY(!w.findChild<QLabel*>("editCount")->isVisible());
    pressKey(w, Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);  // redo: the lattice is back, the mode is not
    QCOMPARE(w.scene().widgets.roots().size(), std::size_t(1));
    QVERIFY(!editOf(w).editing());
    QVERIFY(!toggle->isChecked());
    pressKey(w, Qt::Key_Tab);
    QVERIFY(toggle->isChecked());
    QVERIFY(editOf(w).editing());
    QCOMPARE(editOf(w).points().count(), Eigen::Index(0));
  }

  // Select > Mirror > Across the Mid-Plane of i: G X 0.25 on the point (2,1,2) moves its image
  // (0,1,2) by -0.25 along x; one undo step puts both back.
  void mirrorEditingMovesTheImageAcrossTheMidPlane() {
    MainWindow& w = *window_;
    const auto& m = w.scene().widgets;
    const WidgetId lattice = newLatticeInEditMode(w);
    action(w, "actionMirrori")->trigger();
    QCOMPARE(editOf(w).mirror(), std::optional(0));
    clickPoint(w, lattice, flat(2, 1, 2));
    QCOMPARE(editOf(w).points().indices(), std::vector<Eigen::Index>{flat(2, 1, 2)});
    const Eigen::MatrixX3d start = m.worldControlPoints(lattice);
    const std::size_t steps = w.commands().position();
    hover(w, toWidget(w, Eigen::Vector3d(1.0, 0.5, 1.0)));
    pressKey(w, Qt::Key_G);
    pressKey(w, Qt::Key_X);
    typeKeys(w, "0.25");
    pressKey(w, Qt::Key_Return);
    Eigen::MatrixX3d expected = start;
    expected(flat(2, 1, 2), 0) += 0.25;
    expected(flat(0, 1, 2), 0) -= 0.25;
    QCOMPARE((m.worldControlPoints(lattice) - expected).cwiseAbs().maxCoeff(), 0.0);
    QCOMPARE(w.commands().position(), steps + 1);
    action(w, "actionUndo")->trigger();
    QCOMPARE((m.worldControlPoints(lattice) - start).cwiseAbs().maxCoeff(), 0.0);
    action(w, "actionMirrorOff")->trigger();
    QVERIFY(!editOf(w).mirror().has_value());
  }

  void makeCellYieldsEachKindAndSaysWhyASelectionDoesNotFit() {
    MainWindow& w = *window_;
    triggerWithDialog(w, "actionNewLattice");
    const WidgetId lattice = w.scene().widgets.roots().front();
    const auto& m = w.scene().widgets;
    lookAtUnitBox(w);
    pressKey(w, Qt::Key_Tab);
    // Selects exactly `points` by Shift+clicks; false (and the test stops) if the clicks missed.
    auto select = [&](const std::vector<Eigen::Index>& points) {
      pressKey(w, Qt::Key_A, Qt::AltModifier);
      for (Eigen::Index p : points) clickPoint(w, lattice, p, Qt::ShiftModifier);
      std::vector<Eigen::Index> sorted = points;
      std::sort(sorted.begin(), sorted.end());
      return editOf(w).points().indices() == sorted;
    };
    auto lastCell = [&] { return m.cellSpec(m.cellsOf(lattice).back()); };
    QVERIFY(select({flat(2, 2, 0)}));
    pressKey(w, Qt::Key_M, Qt::ControlModifier);
    QCOMPARE(lastCell(), widgets::CellSpec::point(2, 2, 0));
    QVERIFY(select({flat(0, 2, 0), flat(1, 2, 0)}));
    pressKey(w, Qt::Key_M, Qt::ControlModifier);
    QCOMPARE(lastCell(), widgets::CellSpec::edge(0, 2, 0, 0));
    QVERIFY(select({flat(0, 0, 2), flat(1, 0, 2), flat(0, 1, 2), flat(1, 1, 2)}));
    pressKey(w, Qt::Key_M, Qt::ControlModifier);
    QCOMPARE(lastCell(), widgets::CellSpec::face(0, 0, 2, 2));
    QCOMPARE(w.controller().selection(), std::vector{m.cellsOf(lattice).back()});
    QVERIFY(select({flat(0, 0, 1)}));
    action(w, "actionSelectPlanesk")->trigger();  // the plane k = 1
    pressKey(w, Qt::Key_M, Qt::ControlModifier);
    QCOMPARE(lastCell(), widgets::CellSpec::slab(2, 1));
    QVERIFY(select({flat(1, 1, 1), flat(2, 1, 1), flat(1, 2, 1), flat(2, 2, 1), flat(1, 1, 2), flat(2, 1, 2), flat(1, 2, 2),
            flat(2, 2, 2)}));
    pressKey(w, Qt::Key_M, Qt::ControlModifier);
    QCOMPARE(lastCell(), widgets::CellSpec::box(1, 1, 1));
    // Anything else is asked about, then made a custom cell.
    QVERIFY(select({flat(0, 0, 0), flat(2, 0, 0)}));
    ModalAnswers yes({[](QWidget* modal) {
      auto* box = qobject_cast<QMessageBox*>(modal);
      QVERIFY(box != nullptr);
      QVERIFY(box->text().contains("no point, edge, face, slab or box"));
      QTest::mouseClick(box->button(QMessageBox::Yes), Qt::LeftButton);
    }});
    pressKey(w, Qt::Key_M, Qt::ControlModifier);
    QCOMPARE(yes.answered(), 1);
    QCOMPARE(lastCell(), widgets::CellSpec::custom({flat(0, 0, 0), flat(2, 0, 0)}));
    // The kind asked does not fit: a message says why, nothing is made.
    const std::size_t cells = m.cellsOf(lattice).size();
    action(w, "actionMakeCellEdge")->trigger();
    QVERIFY2(w.statusMessage().contains("(0,0,0) and (2,0,0) differ by 2 along i"), qPrintable(w.statusMessage()));
    QCOMPARE(m.cellsOf(lattice).size(), cells);
    // The context menu offers Make Cell.
    const QPoint at = toWidget(w, Eigen::Vector3d(0.5, 0.5, 0.5)) + QPoint(40, 0);
    sendMouse(w.view(), QEvent::MouseButtonPress, at, Qt::RightButton, Qt::RightButton);
    sendMouse(w.view(), QEvent::MouseButtonRelease, at, Qt::RightButton, Qt::NoButton);
    auto* menu = qobject_cast<QMenu*>(QApplication::activePopupWidget());
    QVERIFY(menu != nullptr && menu->objectName() == "editContextMenu");
    menu->close();
  }

  void aRotateWidgetOnAPointIsRefusedWithAMessage() {
    MainWindow& w = *window_;
    triggerWithDialog(w, "actionNewLattice");
    const WidgetId lattice = w.scene().widgets.roots().front();
    lookAtUnitBox(w);
    clickPoint(w, lattice, flat(1, 1, 2));
    QVERIFY(w.controller().pickedPoint().has_value());
    action(w, "actionAddRotate")->trigger();
    QVERIFY(w.scene().widgets.widgets(widgets::WidgetType::Affine).empty());
    QVERIFY2(w.statusMessage().contains("moves nothing"), qPrintable(w.statusMessage()));
  }

  void aGroupOfWidgetsTurnsAboutItsPivotAsOneUndoStep() {
    MainWindow& w = *window_;
    triggerWithDialog(w, "actionNewLattice");
    triggerWithDialog(w, "actionNewLattice");
    const auto roots = w.scene().widgets.roots();
    const auto& m = w.scene().widgets;
    w.controller().setLatticeFrame(roots[1], Eigen::Affine3d(Eigen::Translation3d(1.5, 0, 0)));
    lookAtUnitBox(w);
    clickRow(w, QString::fromStdString(m.name(roots[0])));
    clickRow(w, QString::fromStdString(m.name(roots[1])), Qt::ControlModifier);
    QCOMPARE(w.controller().selection().size(), std::size_t(2));
    QVERIFY(editOf(w).transformer().has_value());  // the group's transformer
    const Eigen::Affine3d a0 = m.latticeFrame(roots[0]), b0 = m.latticeFrame(roots[1]);
    const std::size_t steps = w.commands().position();
    hover(w, toWidget(w, Eigen::Vector3d(1, 0.5, 0.5)));
    pressKey(w, Qt::Key_R);
    pressKey(w, Qt::Key_Z);
    typeKeys(w, "90");
    pressKey(w, Qt::Key_Return);
    // About the median of the two centres (0.5, 0.5, 0.5) and (2, 0.5, 0.5): (1.25, 0.5, 0.5).
    const Eigen::Vector3d pivot(1.25, 0.5, 0.5);
    const Eigen::Affine3d turn =
        Eigen::Translation3d(pivot) * Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(-pivot);
    QVERIFY(m.latticeFrame(roots[0]).matrix().isApprox((turn * a0).matrix(), 1e-12));
    QVERIFY(m.latticeFrame(roots[1]).matrix().isApprox((turn * b0).matrix(), 1e-12));
    QCOMPARE(w.commands().position(), steps + 1);
    action(w, "actionUndo")->trigger();
    QVERIFY(m.latticeFrame(roots[0]).matrix().isApprox(a0.matrix(), 1e-15));
    QVERIFY(m.latticeFrame(roots[1]).matrix().isApprox(b0.matrix(), 1e-15));
  }

  // Fig. 6-2 (Kuriyama 1996, secs. 6.4, 6.5) from an empty scene with the GUI alone: a new 3x3x3
  // lattice; in its edit mode the face (0..1, 0..1, 2), the edge (0..1, 2, 0) and the point
  // (2, 2, 0) made cells; a rotate widget on the face, translate widgets on the edge and the
  // point; the point's arrow turned up with its transformer (-90 degrees about y, typed); the
  // ring dragged by a typed 5 degrees, the arrows by 0.5 and 0.25. Its control points equal the
  // scripted fixture's (thesis_examples.h) within 1e-12.
  void fig62IsBuiltFromAnEmptySceneThroughTheGuiAlone() {
    MainWindow& w = *window_;
    const auto& m = w.scene().widgets;
    const WidgetId lattice = newLatticeInEditMode(w);
    auto makeCell = [&](const std::vector<Eigen::Index>& points, const char* add) {
      return selectPoints(w, lattice, points) ? makeCellWithWidget(w, add) : WidgetId();  // invalid: a click missed
    };
    const WidgetId ring = makeCell(fig62FacePoints(), "actionAddRotate");
    const WidgetId edgeArrow = makeCell(fig62EdgePoints(), "actionAddTranslate");
    const WidgetId pointArrow = makeCell(fig62PointPoints(), "actionAddTranslate");
    // docs/app.md's picture (with FFDKIT_DOC_IMAGES=<folder>): the face's points selected again.
    if (const QString folder = qEnvironmentVariable("FFDKIT_DOC_IMAGES"); !folder.isEmpty()) {
      QVERIFY(selectPoints(w, lattice, fig62FacePoints()));
      QVERIFY(w.grab().save(folder + "/edit-mode.png"));
    }
    QVERIFY(ring.valid() && edgeArrow.valid() && pointArrow.valid());
    pressKey(w, Qt::Key_Tab);
    QCOMPARE(m.widgets(widgets::WidgetType::Affine).size(), std::size_t(3));

    // The point's arrow turned up: its transformer's y ring, dragged a little, then -90 typed.
    turnWithTransformerRingY(w, pointArrow, "-90");
    QVERIFY((m.affineFrame(pointArrow).frame.linear().col(0) - Eigen::Vector3d::UnitZ()).norm() < 1e-15);

    // Each widget dragged by its glyph, the amount typed while the button is down.
    dragTyped(w, ring, "5");
    dragTyped(w, edgeArrow, "0.5");
    dragTyped(w, pointArrow, "0.25");

    widgets::Fig62 fixture = widgets::buildFig62();
    fixture.model.applyVariation(fixture.faceRotate, 5.0 * std::numbers::pi / 180.0);
    fixture.model.applyVariation(fixture.edgeTranslate, 0.5);
    fixture.model.applyVariation(fixture.pointTranslate, 0.25);
    const Eigen::MatrixX3d expected = fixture.model.worldControlPoints(fixture.lattice);
    const double error = (m.worldControlPoints(lattice) - expected).cwiseAbs().maxCoeff();
    QVERIFY2(error <= 1e-12, qPrintable(QString("max |GUI - fixture| = %1").arg(error)));
    QVERIFY((m.worldControlPoints(lattice) - m.worldRestPoints(lattice)).cwiseAbs().maxCoeff() > 0.2);
  }

 private:
  static const app::EditController& editOf(MainWindow& w);
  std::unique_ptr<MainWindow> window_;
};

const app::EditController& EditModeGuiTest::editOf(MainWindow& w) { return w.editController(); }

int main(int argc, char** argv) { return runGuiTest<EditModeGuiTest>(argc, argv); }

#include "edit_mode_gui_test.moc"
