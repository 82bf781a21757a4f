// The transformer manipulator in the real window (Xvfb, real Qt mouse events): picking an
// affine widget or a lattice widget brings it up, drawn over the object; dragging its handles
// moves, turns and sizes the widget; clicking empty space dismisses it; undo puts things back.
#include <QAction>
#include <QStatusBar>
#include <QTest>

#include <cmath>

#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/interaction/transformer.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "gui_test_support.h"

using namespace ffdkit;
using app::MainWindow;
using widgets::WidgetId;
using namespace ffdkit::app::testing;

namespace {

double maxDifference(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) { return (a - b).cwiseAbs().maxCoeff(); }

// A sphere with a 3x3x3 lattice and a translate widget on the lattice's top centre point,
// built through the controller (the UI paths of these operations have their own tests).
struct SphereScene {
  std::string sphere;
  WidgetId lattice, widget;
};

SphereScene build(MainWindow& w) {
  SphereScene s;
  auto& c = w.controller();
  s.sphere = c.addPrimitive({});
  s.lattice = c.newLattice({});
  s.widget = c.addAffineAtPoint({s.lattice, 1 + 3 * (1 + 3 * 2)}, widgets::AffineKind::Translate);
  c.attachLattice(s.lattice, s.sphere);
  c.clearSelection();
  scenes::Camera camera;
  camera.position = {2.6, -3.4, 2.2};
  w.sceneView().applyCamera(camera);
  w.view()->grabFramebuffer();
  return s;
}

}  // namespace

class TransformerGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = startWindow();
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  void pickingAnAffineWidgetBringsUpItsTransformerAndItsHandlesMoveIt() {
    MainWindow& w = *window_;
    const SphereScene s = build(w);
    auto& c = w.controller();
    const auto& m = w.scene().widgets;
    QVERIFY(!c.transformer());

    // Click the arrow: the widget is selected and its transformer shows.
    widgets::WidgetFrame f = m.affineFrame(s.widget);
    click(w, toWidget(w, f.frame * Eigen::Vector3d(0.6 * f.size, 0, 0)));
    QCOMPARE(c.selection(), std::vector{s.widget});
    QVERIFY(c.transformer().has_value());
    const app::Transformer t = *c.transformer();
    const Eigen::Vector3d o = t.frame.translation(), z = t.frame.linear().col(2);

    // It is drawn, over everything: the z shaft is blue where it crosses the sphere's outline.
    const Eigen::Vector3d shaft = o + 0.65 * t.size * z;
    const QPoint shaftPixel = toWidget(w, shaft);
    const QColor colour = w.view()->grabFramebuffer().pixelColor(shaftPixel);
    QVERIFY2(colour.blue() > colour.red() + 60 && colour.blue() > colour.green() + 20,
             qPrintable(QString("pixel at the z shaft: %1").arg(colour.name())));
    // Hovering a handle highlights it in the selection colour.
    hover(w, shaftPixel);
    QCOMPARE(c.transformerHandle(), std::optional(app::TransformerHandle::MoveZ));
    const QColor hovered = w.view()->grabFramebuffer().pixelColor(shaftPixel);
    QVERIFY2(hovered.red() > 200 && hovered.green() > 170 && hovered.blue() < 120, qPrintable(hovered.name()));

    // Drag the z shaft 0.2 up: the widget moves, the lattice and the sphere do not.
    const Eigen::MatrixX3d points = m.controlPoints(s.lattice);
    const Eigen::MatrixX3d sphere = w.deformer().points(s.sphere);
    const std::size_t position = w.commands().position();
    const QPoint from = toWidget(w, shaft), to = toWidget(w, shaft + 0.2 * z);
    sendMouse(w.view(), QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
    for (int step = 1; step <= 10; ++step)
      sendMouse(w.view(), QEvent::MouseMove, from + (to - from) * step / 10, Qt::NoButton, Qt::LeftButton);
    // While dragging, the status line says what the drag does so far; the release ends that.
    QVERIFY2(w.statusMessage().startsWith("move z 0.19") || w.statusMessage().startsWith("move z 0.20"),
             qPrintable(w.statusMessage()));
    sendMouse(w.view(), QEvent::MouseButtonRelease, to, Qt::LeftButton, Qt::NoButton);
    QCOMPARE(w.statusMessage(), QString());
    f = m.affineFrame(s.widget);
    QVERIFY2((f.frame.translation() - (o + 0.2 * z)).norm() < 0.01,
             qPrintable(QString("moved by %1").arg((f.frame.translation() - o).dot(z))));
    QVERIFY(f.frame.linear().isApprox(t.frame.linear(), 1e-12));
    QCOMPARE(m.controlPoints(s.lattice), points);
    QCOMPARE(w.deformer().points(s.sphere), sphere);
    QCOMPARE(w.commands().position(), position + 1);

    // The arrow still works where it is now: dragging it deforms the sphere.
    const Eigen::Vector3d x = f.frame.linear().col(0);
    const Eigen::Vector3d grab = f.frame * Eigen::Vector3d(0.6 * f.size, 0, 0);
    dragWorld(w, grab, grab + 0.15 * x);
    QVERIFY(std::abs(m.variation(s.widget) - 0.15) < 0.01);
    QVERIFY(maxDifference(w.deformer().points(s.sphere), sphere) > 0.02);

    // A click on empty space dismisses the transformer.
    click(w, QPoint(8, 8));
    QVERIFY(c.selection().empty());
    QVERIFY(!c.transformer());

    // Undo (the arrow drag, then the move): the widget is back where it was.
    w.findChild<QAction*>("actionUndo")->trigger();
    w.findChild<QAction*>("actionUndo")->trigger();
    QVERIFY((m.affineFrame(s.widget).frame.translation() - o).norm() < 1e-12);
    QCOMPARE(w.deformer().points(s.sphere), sphere);
  }

  void aLatticesTransformerTurnsItAboutItsCentreAndTheSphereIsReEmbedded() {
    MainWindow& w = *window_;
    const SphereScene s = build(w);
    auto& c = w.controller();
    const auto& m = w.scene().widgets;
    c.setVariation(s.widget, 0.3);  // a deformed lattice: turning it moves the bump
    const Eigen::MatrixX3d bumped = w.deformer().points(s.sphere);
    const Eigen::Affine3d frame = m.latticeFrame(s.lattice);

    // Alt+click selects the lattice.
    const Eigen::MatrixX3d corners = m.worldControlPoints(s.lattice);
    const Eigen::Vector3d edgeMiddle = 0.5 * (corners.row(0) + corners.row(1)).transpose();
    click(w, toWidget(w, edgeMiddle + Eigen::Vector3d(0.0, 0.0, 0.02)), Qt::AltModifier);
    QCOMPARE(c.selection(), std::vector{s.lattice});
    const app::Transformer t = *c.transformer();
    const Eigen::Vector3d o = t.frame.translation();
    const Eigen::Vector3d x = t.frame.linear().col(0), y = t.frame.linear().col(1), z = t.frame.linear().col(2);
    const double r = app::TransformerLayout::turnRadius * t.size;
    auto onRing = [&](double a) { return o + r * (std::cos(a) * x + std::sin(a) * y); };

    // A grab point on the z ring that nothing else covers on screen.
    double start = -1.0;
    for (double a = 0.2; a < 6.2 && start < 0.0; a += 0.1) {
      hover(w, toWidget(w, onRing(a)));
      if (c.transformerHandle() == app::TransformerHandle::TurnZ) start = a;
    }
    QVERIFY2(start >= 0.0, "no free spot on the z ring");
    dragWorld(w, onRing(start), onRing(start + 0.5));
    const Eigen::Affine3d now = m.latticeFrame(s.lattice);
    const Eigen::Vector3d turnedX = now.linear().col(0).normalized();
    const double angle = std::atan2(turnedX.dot(y), turnedX.dot(x));
    QVERIFY2(std::abs(angle - 0.5) < 0.03, qPrintable(QString("turned by %1 rad").arg(angle)));
    // About the centre: the transformer did not move.
    QVERIFY((c.transformer()->frame.translation() - o).norm() < 1e-9);
    QVERIFY(std::abs(now.linear().col(2).normalized().dot(z) - 1.0) < 1e-12);

    // The sphere: what a lattice set to that frame directly gives, computed on a copy.
    scenes::Scene expected = w.scene();
    expected.widgets.setLatticeFrame(s.lattice, now);
    scenes::SceneDeformer independent;
    independent.finishGesture(expected);
    QVERIFY(maxDifference(w.deformer().points(s.sphere), independent.points(s.sphere)) < 1e-12);
    QVERIFY(maxDifference(w.deformer().points(s.sphere), bumped) > 0.01);

    // Undo: the lattice and the sphere as before.
    w.findChild<QAction*>("actionUndo")->trigger();
    QVERIFY(m.latticeFrame(s.lattice).isApprox(frame, 1e-14));
    QVERIFY(maxDifference(w.deformer().points(s.sphere), bumped) < 1e-12);
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<TransformerGuiTest>(argc, argv); }

#include "transformer_gui_test.moc"
