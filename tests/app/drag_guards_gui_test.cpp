// Keep Volume / Keep Centre and the fold-over tint during widget drags in the real window (Xvfb,
// real Qt mouse events), outside the edit mode: a translate widget's arrow dragged in 20 pointer
// steps keeps the sphere's volume (summed here by the divergence theorem over the evaluated mesh)
// or its solid centroid (summed here over the tetrahedra the triangles make with the origin)
// within 1e-12 at every step, the status bar shows the volume change, the drag is one undo step
// and its undo restores the start; an arrow dragged past the neighbouring points folds the lattice
// and tints its cells red in the picture.
#include <QStatusBar>
#include <QTest>
#include <QToolButton>

#include <cmath>

#include "divergence_volume.h"
#include "fig62_steps.h"
#include "gui_test_support.h"

using namespace ffdkit;
using app::MainWindow;
using widgets::WidgetId;
using namespace ffdkit::app::testing;

namespace {

const Eigen::Index kSide = flat(2, 1, 1);  // the centre point of the lattice's +x face

// The volume a closed triangle mesh encloses: sum over triangles of a . (b x c) / 6.
using ffdkit::test::divergenceVolume;

// The centroid of the solid a closed triangle mesh bounds: the tetrahedra (0, a, b, c), each at
// (a + b + c) / 4 weighted by its signed volume.
Eigen::Vector3d solidCentroid(const Eigen::MatrixX3d& p, const Eigen::MatrixX3i& t) {
  double v = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < t.rows(); ++i) {
    const Eigen::Vector3d a = p.row(t(i, 0)), b = p.row(t(i, 1)), c = p.row(t(i, 2));
    const double tet = a.dot(b.cross(c)) / 6.0;
    v += tet;
    moment += tet * (a + b + c) / 4.0;
  }
  return moment / v;
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

// A sphere in a 3 x 3 x 3 lattice with a translate widget on lattice point `point` (clicked, Add
// Translate: its arrow along the lattice's u axis), the lattice attached; the view framed.
// @return the translate widget.
WidgetId sphereWithTranslate(MainWindow& w, Eigen::Index point) {
  triggerWithDialog(w, "actionAddPrimitive");  // sphere1
  triggerWithDialog(w, "actionNewLattice");
  action(w, "actionAttach")->trigger();  // the only lattice round the only object
  pressKey(w, Qt::Key_Home);            // frame everything
  const WidgetId lattice = w.scene().widgets.roots().front();
  click(w, toWidget(w, w.scene().widgets.worldControlPoints(lattice).row(point).transpose()));
  const auto picked = w.controller().pickedPoint();
  if (!picked || picked->index != point) return {};
  action(w, "actionAddTranslate")->trigger();
  return w.scene().widgets.widgets(widgets::WidgetType::Affine).back();
}

// Where the translate widget's arrow is grabbed, and where the pointer is `distance` world units
// along it.
struct ArrowDrag {
  Eigen::Vector3d grab, axis;
};
ArrowDrag arrowOf(MainWindow& w, WidgetId affine) {
  const widgets::WidgetFrame f = w.scene().widgets.affineFrame(affine);
  const Eigen::Vector3d x = f.frame.linear().col(0);
  return {f.frame.translation() + 0.6 * f.size * x, x};
}

}  // namespace

class DragGuardsGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = openWindow(QSize(1000, 760));
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  void aGlyphDragWithKeepVolumeHoldsTheVolumeThroughTwentySteps() {
    MainWindow& w = *window_;
    const WidgetId translate = sphereWithTranslate(w, kSide);
    QVERIFY(translate.valid());
    const WidgetId lattice = w.scene().widgets.roots().front();
    const scenes::ObjectId sphere = w.scene().objectId("sphere1");
    const Eigen::MatrixX3i triangles = w.scene().findObject(sphere)->mesh.triangles;
    const double v0 = divergenceVolume(w.deformer().points(sphere), triangles);

    auto* keep = w.findChild<QToolButton*>("keepVolumeButton");
    QVERIFY(keep != nullptr && keep->isVisible());
    QTest::mouseClick(keep, Qt::LeftButton);  // not in the edit mode: the scene's only object
    QVERIFY(action(w, "actionKeepVolume")->isChecked());
    QVERIFY2(w.statusMessage().contains("Keeping the volume of sphere1"), qPrintable(w.statusMessage()));

    const Eigen::MatrixX3d start = w.scene().widgets.controlPoints(lattice);
    const std::size_t steps = w.commands().position();
    const ArrowDrag arrow = arrowOf(w, translate);
    const QPoint from = toWidget(w, arrow.grab);
    sendMouse(w.view(), QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
    QVERIFY(w.controller().dragging());
    double worst = 0.0;
    for (int step = 1; step <= 20; ++step) {
      sendMouse(w.view(), QEvent::MouseMove, toWidget(w, arrow.grab + 0.02 * step * arrow.axis), Qt::NoButton, Qt::LeftButton);
      const double v = divergenceVolume(w.deformer().points(sphere), triangles);
      worst = std::max(worst, std::abs(v - v0) / v0);
      QVERIFY2(w.statusMessage().contains("sphere1: volume change"), qPrintable(w.statusMessage()));
    }
    const QPoint to = toWidget(w, arrow.grab + 0.4 * arrow.axis);
    sendMouse(w.view(), QEvent::MouseButtonRelease, to, Qt::LeftButton, Qt::NoButton);
    QVERIFY(!w.controller().dragging());
    QVERIFY2(worst <= 1e-12, qPrintable(QString::number(worst)));
    const Eigen::MatrixX3d moved = w.scene().widgets.controlPoints(lattice);
    QVERIFY((moved.row(kSide) - start.row(kSide)).norm() > 0.2);  // the widget's point went ...
    Eigen::MatrixX3d others = moved - start;
    others.row(kSide).setZero();
    QVERIFY(others.norm() > 1e-3);  // ... the others gave way
    QVERIFY(std::abs(divergenceVolume(w.deformer().points(sphere), triangles) - v0) / v0 <= 1e-12);
    QCOMPARE(w.commands().position(), steps + 1);  // one undo step
    action(w, "actionUndo")->trigger();
    QCOMPARE((w.scene().widgets.controlPoints(lattice) - start).cwiseAbs().maxCoeff(), 0.0);
    QVERIFY(std::abs(divergenceVolume(w.deformer().points(sphere), triangles) - v0) / v0 <= 1e-14);
    action(w, "actionRedo")->trigger();
    QCOMPARE((w.scene().widgets.controlPoints(lattice) - moved).cwiseAbs().maxCoeff(), 0.0);
  }

  void aGlyphDragWithKeepCentreHoldsTheCentroidThroughTwentySteps() {
    MainWindow& w = *window_;
    const WidgetId translate = sphereWithTranslate(w, kSide);
    QVERIFY(translate.valid());
    const WidgetId lattice = w.scene().widgets.roots().front();
    const scenes::ObjectId sphere = w.scene().objectId("sphere1");
    const Eigen::MatrixX3i triangles = w.scene().findObject(sphere)->mesh.triangles;
    const Eigen::Vector3d c0 = solidCentroid(w.deformer().points(sphere), triangles);

    QTest::mouseClick(w.findChild<QToolButton*>("keepCentreButton"), Qt::LeftButton);
    QVERIFY(action(w, "actionKeepCentre")->isChecked());
    const Eigen::MatrixX3d start = w.scene().widgets.controlPoints(lattice);
    const std::size_t steps = w.commands().position();
    const ArrowDrag arrow = arrowOf(w, translate);
    sendMouse(w.view(), QEvent::MouseButtonPress, toWidget(w, arrow.grab), Qt::LeftButton, Qt::LeftButton);
    QVERIFY(w.controller().dragging());
    double worst = 0.0;
    for (int step = 1; step <= 20; ++step) {
      sendMouse(w.view(), QEvent::MouseMove, toWidget(w, arrow.grab + 0.02 * step * arrow.axis), Qt::NoButton, Qt::LeftButton);
      worst = std::max(worst, (solidCentroid(w.deformer().points(sphere), triangles) - c0).norm());
      QVERIFY2(w.statusMessage().contains("sphere1: centre kept"), qPrintable(w.statusMessage()));
    }
    sendMouse(w.view(), QEvent::MouseButtonRelease, toWidget(w, arrow.grab + 0.4 * arrow.axis), Qt::LeftButton, Qt::NoButton);
    // The sphere's radius is about 1: 1e-12 relative to its size.
    QVERIFY2(worst <= 1e-12, qPrintable(QString::number(worst)));
    const Eigen::MatrixX3d moved = w.scene().widgets.controlPoints(lattice);
    QVERIFY((moved.row(kSide) - start.row(kSide)).norm() > 0.2);
    QCOMPARE(w.commands().position(), steps + 1);
    action(w, "actionUndo")->trigger();
    QCOMPARE((w.scene().widgets.controlPoints(lattice) - start).cwiseAbs().maxCoeff(), 0.0);
  }

  void aGlyphDragThatFoldsTheLatticeTintsItsCellsRed() {
    MainWindow& w = *window_;
    const WidgetId translate = sphereWithTranslate(w, flat(1, 1, 2));
    QVERIFY(translate.valid());
    const WidgetId lattice = w.scene().widgets.roots().front();
    QVERIFY(w.controller().foldTints().empty());
    click(w, QPoint(5, 5));  // nothing selected: no transformer in the picture
    const int redBefore = redPixels(w);
    // The top face's centre point dragged along u by 1.5 times the lattice's size, past the
    // face's edge: at that edge's middle dx/du = size - 2 (1/2) 1.5 size < 0, the map folds.
    const ArrowDrag arrow = arrowOf(w, translate);
    const Eigen::MatrixX3d world = w.scene().widgets.worldControlPoints(lattice);
    const double size = (world.colwise().maxCoeff() - world.colwise().minCoeff()).maxCoeff();
    sendMouse(w.view(), QEvent::MouseButtonPress, toWidget(w, arrow.grab), Qt::LeftButton, Qt::LeftButton);
    QVERIFY(w.controller().dragging());
    for (int step = 1; step <= 10; ++step)
      sendMouse(w.view(), QEvent::MouseMove, toWidget(w, arrow.grab + 0.15 * step * size * arrow.axis), Qt::NoButton,
                Qt::LeftButton);
    // Live: during the drag, before the release.
    QVERIFY(!w.controller().foldTints().empty());
    const app::FoldTint& tint = w.controller().foldTints().front();
    QVERIFY(tint.lattice == lattice);
    QVERIFY(std::count(tint.cells.begin(), tint.cells.end(), ffd::CellFolding::Folds) >= 1);
    const int redDuring = redPixels(w);
    QVERIFY2(redDuring > redBefore + 2000, qPrintable(QString("%1 red pixels, %2 before").arg(redDuring).arg(redBefore)));
    sendMouse(w.view(), QEvent::MouseButtonRelease, toWidget(w, arrow.grab + 1.5 * size * arrow.axis), Qt::LeftButton,
              Qt::NoButton);
    QVERIFY(!w.controller().foldTints().empty());  // the verdict stands after the release
    action(w, "actionUndo")->trigger();            // and goes with the fold
    QVERIFY(w.controller().foldTints().empty());
    click(w, QPoint(5, 5));  // the dragged widget deselected, as before
    QVERIFY(redPixels(w) < redBefore + 200);
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<DragGuardsGuiTest>(argc, argv); }

#include "drag_guards_gui_test.moc"
