// Keep Volume, soft selection and the fold-over tint in the real window (Xvfb, real Qt mouse,
// wheel and key events): G with Keep Volume on holds the sphere's volume (summed here by the
// divergence theorem over the evaluated mesh) within 1e-12 through 20 pointer steps, as one undo
// step; Keep Volume on an open surface is refused with its reason; O, the wheel and PageDown set
// a soft selection whose points move by the falloff times the move; pushing a control point
// through its neighbour tints the cell red in the picture. With FFDKIT_SCREENSHOT_DIR set, the
// folding lattice's picture is written there (scripts/fold-tint-screenshot.sh: docs/images).
#include <QComboBox>
#include <QDialog>
#include <QStatusBar>
#include <QTest>
#include <QToolButton>
#include <QWheelEvent>

#include <cmath>

#include "divergence_volume.h"
#include "ffdkit/interaction/edit_controller.h"
#include "fig62_steps.h"
#include "gui_test_support.h"

using namespace ffdkit;
using app::MainWindow;
using widgets::WidgetId;
using namespace ffdkit::app::testing;

namespace {

// The volume a closed triangle mesh encloses: sum over triangles of a . (b x c) / 6.
using ffdkit::test::divergenceVolume;

// One notch of the wheel over the view (120 eighths of a degree; negative: towards the user).
void wheel(MainWindow& w, QPoint at, int notches) {
  QWheelEvent event(QPointF(at), w.view()->mapToGlobal(QPointF(at)), QPoint(), QPoint(0, 120 * notches), Qt::NoButton,
                    Qt::NoModifier, Qt::NoScrollPhase, false);
  QApplication::sendEvent(w.view(), &event);
}

// Pixels of the view's picture tinted as a folding cell is (clearly red).
int redPixels(MainWindow& w) {
  const QImage image = w.view()->grabFramebuffer();
  int count = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const QColor c = image.pixelColor(x, y);
      if (c.red() > 90 && c.red() > 2 * c.green() && c.red() > 2 * c.blue()) ++count;
    }
  return count;
}

}  // namespace

class EditGuardsGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = openWindow(QSize(1000, 760));
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  void gWithKeepVolumeOnHoldsTheVolumeThroughTwentyDragSteps() {
    MainWindow& w = *window_;
    triggerWithDialog(w, "actionAddPrimitive");  // sphere1
    triggerWithDialog(w, "actionNewLattice");
    action(w, "actionAttach")->trigger();  // the only lattice round the only object
    const WidgetId lattice = w.scene().widgets.roots().front();
    pressKey(w, Qt::Key_Home);  // frame everything
    pressKey(w, Qt::Key_Tab);
    QVERIFY(w.editController().editing());
    const scenes::ObjectId sphere = w.scene().objectId("sphere1");
    const Eigen::MatrixX3i triangles = w.scene().findObject(sphere)->mesh.triangles;
    const double v0 = divergenceVolume(w.deformer().points(sphere), triangles);

    auto* keep = w.findChild<QToolButton*>("keepVolumeButton");
    QVERIFY(keep != nullptr && keep->isVisible());
    QTest::mouseClick(keep, Qt::LeftButton);
    QVERIFY(action(w, "actionKeepVolume")->isChecked());
    QVERIFY2(w.statusMessage().contains("Keeping the volume of sphere1"), qPrintable(w.statusMessage()));

    clickPoint(w, lattice, flat(1, 1, 2));
    QCOMPARE(w.editController().points().indices(), std::vector<Eigen::Index>{flat(1, 1, 2)});
    const Eigen::MatrixX3d start = w.scene().widgets.controlPoints(lattice);
    const Eigen::Vector3d top = w.scene().widgets.worldControlPoints(lattice).row(flat(1, 1, 2));
    const std::size_t steps = w.commands().position();
    const QPoint from = toWidget(w, top);
    hover(w, from);
    pressKey(w, Qt::Key_G);
    QVERIFY(w.editController().transforming());
    double worst = 0.0;
    for (int step = 1; step <= 20; ++step) {
      hover(w, from + QPoint(step, -4 * step));
      const double v = divergenceVolume(w.deformer().points(sphere), triangles);
      worst = std::max(worst, std::abs(v - v0) / v0);
      QVERIFY2(w.statusMessage().contains("sphere1: volume change"), qPrintable(w.statusMessage()));
    }
    QVERIFY2(worst <= 1e-12, qPrintable(QString::number(worst)));
    const Eigen::MatrixX3d moved = w.scene().widgets.controlPoints(lattice);
    QVERIFY((moved.row(flat(1, 1, 2)) - start.row(flat(1, 1, 2))).norm() > 0.1);  // the point went up ...
    Eigen::MatrixX3d others = moved - start;
    others.row(flat(1, 1, 2)).setZero();
    QVERIFY(others.norm() > 1e-3);  // ... the others gave way
    click(w, from + QPoint(20, -80));  // confirms
    QVERIFY(!w.editController().transforming());
    QVERIFY(std::abs(divergenceVolume(w.deformer().points(sphere), triangles) - v0) / v0 <= 1e-12);
    QCOMPARE(w.commands().position(), steps + 1);
    action(w, "actionUndo")->trigger();
    QCOMPARE((w.scene().widgets.controlPoints(lattice) - start).cwiseAbs().maxCoeff(), 0.0);
    action(w, "actionRedo")->trigger();
    QCOMPARE((w.scene().widgets.controlPoints(lattice) - moved).cwiseAbs().maxCoeff(), 0.0);
  }

  void keepVolumeOnAnOpenSurfaceIsRefusedWithItsReason() {
    MainWindow& w = *window_;
    triggerWithDialog(w, "actionAddPrimitive", [](QDialog* dialog) {
      for (auto* combo : dialog->findChildren<QComboBox*>())
        if (const int plane = combo->findText("plane", Qt::MatchFixedString); plane >= 0) combo->setCurrentIndex(plane);
    });
    QCOMPARE(w.scene().objects().size(), std::size_t(1));
    const std::string name = w.scene().objects().front().name;
    clickRow(w, QString::fromStdString(name));
    QTest::mouseClick(w.findChild<QToolButton*>("keepVolumeButton"), Qt::LeftButton);
    QVERIFY(!action(w, "actionKeepVolume")->isChecked());
    QVERIFY2(w.statusMessage().contains(QString::fromStdString("'" + name + "' encloses no volume: it is not a closed surface")),
             qPrintable(w.statusMessage()));
    // Its centre (the mean of its points) can be kept.
    QTest::mouseClick(w.findChild<QToolButton*>("keepCentreButton"), Qt::LeftButton);
    QVERIFY(action(w, "actionKeepCentre")->isChecked());
  }

  void oTheWheelAndGMovePointsByTheFalloff() {
    MainWindow& w = *window_;
    const WidgetId lattice = newLatticeInEditMode(w);
    clickPoint(w, lattice, flat(1, 1, 2));
    pressKey(w, Qt::Key_O);
    QVERIFY(action(w, "actionSoftSelection")->isChecked());
    QVERIFY(w.editController().softSelection().enabled);
    QCOMPARE(w.editController().softSelection().falloff, app::Falloff::Smooth);
    pressKey(w, Qt::Key_O, Qt::AltModifier);  // connected only on and off again
    QVERIFY(w.editController().softSelection().connectedOnly);
    pressKey(w, Qt::Key_O, Qt::AltModifier);
    QVERIFY(!w.editController().softSelection().connectedOnly);
    const double r0 = w.editController().softSelection().radius;
    const Eigen::MatrixX3d start = w.scene().widgets.worldControlPoints(lattice);
    const std::size_t steps = w.commands().position();
    const QPoint at = toWidget(w, start.row(flat(1, 1, 2)).transpose());
    hover(w, at);
    pressKey(w, Qt::Key_G);
    pressKey(w, Qt::Key_Z);
    wheel(w, at, -2);  // two notches towards the user: x1.1 twice
    QVERIFY(std::abs(w.editController().softSelection().radius - 1.21 * r0) < 1e-12);
    QVERIFY2(w.statusMessage().contains("Soft selection radius"), qPrintable(w.statusMessage()));
    pressKey(w, Qt::Key_PageDown);  // one step smaller
    const double radius = w.editController().softSelection().radius;
    QVERIFY(std::abs(radius - 1.1 * r0) < 1e-12);
    typeKeys(w, "0.5");
    pressKey(w, Qt::Key_Return);
    QCOMPARE(w.commands().position(), steps + 1);
    const Eigen::MatrixX3d moved = w.scene().widgets.worldControlPoints(lattice);
    int softlyMoved = 0;
    for (Eigen::Index i = 0; i < start.rows(); ++i) {
      const double d = (start.row(i) - start.row(flat(1, 1, 2))).norm();
      const double f = d <= radius ? (radius - d) / radius : 0.0;
      const double expected = 0.5 * (3.0 * f * f - 2.0 * f * f * f);  // Blender's smooth falloff
      QVERIFY2(std::abs(moved(i, 2) - start(i, 2) - expected) < 1e-14, qPrintable(QString("point %1").arg(i)));
      QCOMPARE(moved(i, 0), start(i, 0));
      if (expected > 0.0 && expected < 0.5) ++softlyMoved;
    }
    QVERIFY(softlyMoved >= 8);
    pressKey(w, Qt::Key_O);
    QVERIFY(!w.editController().softSelection().enabled);
  }

  void pushingAPointThroughItsNeighbourTintsTheCellRed() {
    MainWindow& w = *window_;
    const WidgetId lattice = newLatticeInEditMode(w);
    QVERIFY(w.editController().foldTints().empty());
    clickPoint(w, lattice, flat(1, 1, 2));
    const int redBefore = redPixels(w);  // with the selection's transformer (its x arrow is red)
    const Eigen::Vector3d top = w.scene().widgets.worldControlPoints(lattice).row(flat(1, 1, 2));
    hover(w, toWidget(w, top));
    pressKey(w, Qt::Key_G);
    pressKey(w, Qt::Key_Z);
    // Down through (1,1,1) at z = 0.5 and below the bottom: the pointer in ten steps.
    for (int step = 1; step <= 10; ++step) hover(w, toWidget(w, top - 0.25 * step * Eigen::Vector3d::UnitZ()));
    QVERIFY(w.scene().widgets.worldControlPoints(lattice)(flat(1, 1, 2), 2) < -1.2);
    QCOMPARE(w.editController().foldTints().size(), std::size_t(1));
    QCOMPARE(w.editController().foldTints()[0].cells, std::vector<ffd::CellFolding>{ffd::CellFolding::Folds});
    const int redAfter = redPixels(w);
    QVERIFY2(redAfter > redBefore + 2000, qPrintable(QString("%1 red pixels, %2 before").arg(redAfter).arg(redBefore)));
    if (const QString folder = qEnvironmentVariable("FFDKIT_SCREENSHOT_DIR"); !folder.isEmpty())
      QVERIFY(w.grab().save(folder + "/fold-tint.png"));
    pressKey(w, Qt::Key_Escape);  // back: the tint goes
    QVERIFY(w.editController().foldTints().empty());
    QVERIFY(redPixels(w) < redBefore + 200);
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<EditGuardsGuiTest>(argc, argv); }

#include "edit_guards_gui_test.moc"
