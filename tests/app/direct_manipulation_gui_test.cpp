// Direct manipulation in the real window (Xvfb, real Qt mouse events): with Widgets > Direct
// Manipulation on, dragging a point of the sphere moves that point under the pointer (the
// lattice gets the least-norm change); with it off the same drag orbits the camera. Pinned points
// keep their place while another is dragged, or move along with Shift.
#include <QAction>
#include <QTest>

#include "ffdkit/interaction/interaction_controller.h"
#include "gui_test_support.h"

using namespace ffdkit;
using app::MainWindow;
using namespace ffdkit::app::testing;

class DirectManipulationGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = startWindow();
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  void aDraggedPointOfTheSphereEndsUnderThePointer() {
    MainWindow& w = *window_;
    auto& c = w.controller();
    const std::string sphere = c.addPrimitive({});
    const auto lattice = c.newLattice({});
    c.attachLattice(lattice, sphere);
    c.clearSelection();
    scenes::Camera camera;
    camera.position = {2.6, -3.4, 2.2};
    w.sceneView().applyCamera(camera);
    w.view()->grabFramebuffer();
    const Eigen::MatrixX3d before = w.deformer().points(sphere);
    // A point of the sphere facing the camera, away from the lattice's points.
    Eigen::Index facing = 0;
    (before * (camera.position.normalized() + Eigen::Vector3d(0.0, 0.0, -0.5)).normalized()).maxCoeff(&facing);
    const QPoint from = toWidget(w, before.row(facing).transpose()), to = from + QPoint(40, -25);

    // Off: the drag orbits the camera, the sphere stays.
    const scenes::Camera orbitStart = w.sceneView().camera();
    dragPixels(w, from, to);
    QVERIFY((w.sceneView().camera().position - orbitStart.position).norm() > 1e-3);
    QCOMPARE(w.deformer().points(sphere), before);
    w.sceneView().applyCamera(camera);
    w.view()->grabFramebuffer();

    // On: the drag moves the grabbed point (the sphere's vertex nearest the hit) under the pointer.
    QAction* mode = w.findChild<QAction*>("actionDirectManipulation");
    QVERIFY(mode != nullptr);
    mode->trigger();
    QVERIFY(mode->isChecked());
    const std::size_t commands = w.commands().position();
    dragPixels(w, from, to);
    const Eigen::MatrixX3d after = w.deformer().points(sphere);
    Eigen::Index moved = 0;
    const double most = (after - before).rowwise().norm().maxCoeff(&moved);
    QVERIFY2(most > 0.05, qPrintable(QString("moved %1").arg(most)));
    // It lies on the release pixel's ray; its start was within a pixel or two of the press.
    const QPoint end = toWidget(w, after.row(moved).transpose());
    QVERIFY2((end - to).manhattanLength() <= 2, qPrintable(QString("ends at %1,%2, released at %3,%4")
                                                              .arg(end.x()).arg(end.y()).arg(to.x()).arg(to.y())));
    QVERIFY((toWidget(w, before.row(moved).transpose()) - from).manhattanLength() <= 20);
    QVERIFY((w.sceneView().camera().position - camera.position).norm() < 1e-12);  // no orbit
    QCOMPARE(w.commands().position(), commands + 1);
    w.findChild<QAction*>("actionUndo")->trigger();
    QVERIFY((w.deformer().points(sphere) - before).cwiseAbs().maxCoeff() < 1e-12);
  }

  // Clicked object points are pinned (drawn red) and keep their place within 1e-9 while another
  // point is dragged; Shift+drag carries them along by the dragged point's displacement; Alt+D
  // clears them.
  void pinnedPointsStayWhileAnotherIsDragged() {
    MainWindow& w = *window_;
    auto& c = w.controller();
    const std::string sphere = c.addPrimitive({});
    c.attachLattice(c.newLattice({}), sphere);
    c.clearSelection();
    scenes::Camera camera;
    camera.position = {2.6, -3.4, 2.2};
    w.sceneView().applyCamera(camera);
    w.view()->grabFramebuffer();
    pressKey(w, Qt::Key_D);
    QVERIFY(action(w, "actionDirectManipulation")->isChecked());
    const Eigen::MatrixX3d before = w.deformer().points(sphere);
    // Three points facing the camera, apart: two pins and the one dragged.
    const Eigen::Vector3d toCamera = camera.position.normalized();
    const Eigen::Vector3d side = toCamera.cross(Eigen::Vector3d::UnitZ()).normalized();
    auto facing = [&](const Eigen::Vector3d& lean) {
      Eigen::Index best = 0;
      (before * (toCamera + lean).normalized()).maxCoeff(&best);
      return best;
    };
    const Eigen::Index a = facing(0.8 * side), b = facing(-0.8 * side), dragged = facing(Eigen::Vector3d(0, 0, -0.6));
    click(w, toWidget(w, before.row(a).transpose()));
    click(w, toWidget(w, before.row(b).transpose()));
    QCOMPARE(c.pins().size(), std::size_t{2});
    QCOMPARE(w.commands().position(), std::size_t{3});  // a click pins: no edit (3 = the setup)
    std::vector<Eigen::Vector3d> pinned;
    for (const auto& pin : c.pins()) {
      QVERIFY(pin.object == w.scene().objectId(sphere));
      pinned.push_back(w.deformer().points(sphere).row(pin.vertex).transpose());
    }
    // The pins are drawn: a red dot where each is.
    const QImage image = w.view()->grabFramebuffer();
    for (const Eigen::Vector3d& p : pinned) {
      const QColor pixel = image.pixelColor(toWidget(w, p) * w.view()->devicePixelRatioF());
      QVERIFY2(pixel.red() > 200 && pixel.green() < 80 && pixel.blue() < 80, qPrintable(pixel.name()));
    }

    // A drag of a third point: the pins stay within 1e-9 at every step.
    const QPoint from = toWidget(w, before.row(dragged).transpose()), to = from + QPoint(30, -40);
    sendMouse(w.view(), QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
    QVERIFY(c.grabbedPoint().has_value());
    const Eigen::Index grabbed = c.grabbedPoint()->second;
    for (int step = 1; step <= 10; ++step) {
      sendMouse(w.view(), QEvent::MouseMove, from + (to - from) * step / 10, Qt::NoButton, Qt::LeftButton);
      for (std::size_t i = 0; i < pinned.size(); ++i) {
        const double off = (w.deformer().points(sphere).row(c.pins()[i].vertex).transpose() - pinned[i]).norm();
        QVERIFY2(off < 1e-9, qPrintable(QString("pin %1 moved %2 at step %3").arg(i).arg(off).arg(step)));
      }
    }
    sendMouse(w.view(), QEvent::MouseButtonRelease, to, Qt::LeftButton, Qt::NoButton);
    const Eigen::MatrixX3d afterDrag = w.deformer().points(sphere);
    QVERIFY2((afterDrag.row(grabbed) - before.row(grabbed)).norm() > 0.05, "the dragged point did not move");
    QVERIFY((toWidget(w, afterDrag.row(grabbed).transpose()) - to).manhattanLength() <= 2);  // under the pointer
    for (std::size_t i = 0; i < pinned.size(); ++i)
      QVERIFY((afterDrag.row(c.pins()[i].vertex).transpose() - pinned[i]).norm() < 1e-9);
    QCOMPARE(w.commands().position(), std::size_t{4});  // one drag, one step

    // Shift+drag: the pins move with the dragged point, by the same displacement.
    const QPoint from2 = toWidget(w, afterDrag.row(grabbed).transpose()), to2 = from2 + QPoint(-25, 20);
    sendMouse(w.view(), QEvent::MouseButtonPress, from2, Qt::LeftButton, Qt::LeftButton, Qt::ShiftModifier);
    QVERIFY(c.grabbedPoint().has_value());
    const Eigen::Index carrier = c.grabbedPoint()->second;
    for (int step = 1; step <= 10; ++step)
      sendMouse(w.view(), QEvent::MouseMove, from2 + (to2 - from2) * step / 10, Qt::NoButton, Qt::LeftButton,
                Qt::ShiftModifier);
    sendMouse(w.view(), QEvent::MouseButtonRelease, to2, Qt::LeftButton, Qt::NoButton, Qt::ShiftModifier);
    const Eigen::MatrixX3d carried = w.deformer().points(sphere);
    const Eigen::Vector3d moved = (carried.row(carrier) - afterDrag.row(carrier)).transpose();
    QVERIFY(moved.norm() > 0.05);
    for (std::size_t i = 0; i < pinned.size(); ++i) {
      const Eigen::Vector3d pinMoved = (carried.row(c.pins()[i].vertex) - afterDrag.row(c.pins()[i].vertex)).transpose();
      QVERIFY2((pinMoved - moved).norm() < 1e-9, qPrintable(QString("pin %1 moved %2 off").arg(i).arg((pinMoved - moved).norm())));
    }

    // A click on a pin unpins it; Alt+D clears the rest (and their dots go).
    click(w, toWidget(w, carried.row(c.pins()[0].vertex).transpose()));
    QCOMPARE(c.pins().size(), std::size_t{1});
    pressKey(w, Qt::Key_D, Qt::AltModifier);
    QVERIFY(c.pins().empty());
    const QImage cleared = w.view()->grabFramebuffer();
    const QColor pixel = cleared.pixelColor(toWidget(w, carried.row(b).transpose()) * w.view()->devicePixelRatioF());
    QVERIFY2(!(pixel.red() > 200 && pixel.green() < 80 && pixel.blue() < 80), qPrintable(pixel.name()));
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<DirectManipulationGuiTest>(argc, argv); }

#include "direct_manipulation_gui_test.moc"
