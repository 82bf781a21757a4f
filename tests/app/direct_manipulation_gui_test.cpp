// Direct manipulation in the real window (Xvfb, real Qt mouse events): with Widgets > Direct
// Manipulation on, dragging a point of the sphere moves that point under the pointer (the
// lattice gets the least-norm change); with it off the same drag orbits the camera.
#include <QAction>
#include <QTest>

#include "ffdkit/app/interaction_controller.h"
#include "gui_test_support.h"

using namespace ffdkit;
using app::MainWindow;
using namespace ffdkit::app::testing;

class DirectManipulationGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = openWindow(QSize(1000, 760));
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

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<DirectManipulationGuiTest>(argc, argv); }

#include "direct_manipulation_gui_test.moc"
