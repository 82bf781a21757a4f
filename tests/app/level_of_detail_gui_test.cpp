// The view's level of detail in the window, with real mouse events (View > Simplify While Moving,
// LevelOfDetail in scene_view.h): a drag draws the sphere's proxy, evaluating the proxy's points
// only, and the release the exact full mesh, and leaves the same document and files as a drag with
// it off; the proxy is built with the
// scene (and when the menu turns the level of detail on), not by the first drag; a widget clicked
// while playback draws the proxy is picked as without it.
#include <QAction>

#include <filesystem>
#include <map>
#include <string>

#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/scene_changes.h"
#include "gui_test_support.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;

namespace {

// A sphere of about 10k vertices in a 4x4x4 cubic B-spline lattice with a translate widget "pull"
// on its top; keyed (0 -> 0.3 -> 0 over 48 frames) when `keyed`.
scenes::Scene sphereScene(bool keyed) {
  scenes::Scene scene;
  scenes::SceneObject sphere;
  sphere.name = "sphere";
  sphere.source = scenes::PrimitiveOptions{.kind = scenes::PrimitiveKind::Sphere, .resolution = 100};
  sphere.mesh = scenes::buildObjectMesh(sphere.source, ".");
  scene.addObject(std::move(sphere));
  scenes::AttachOptions attach;
  attach.latticeName = "lattice";
  attach.counts = Eigen::Vector3i::Constant(4);
  attach.settings.basis = {ffd::AxisBasis::bspline(3), ffd::AxisBasis::bspline(3), ffd::AxisBasis::bspline(3)};
  const auto lattice = scenes::attachNewLattice(scene, {"sphere"}, attach);
  const auto cell = scene.widgets.addCell(lattice, widgets::CellSpec::point(1, 1, 3), "top");
  const auto pull = scene.widgets.addAffine(cell, widgets::AffineKind::Translate, "pull");
  if (keyed) {
    scene.setFrameRange(scene.animation().firstFrame, 48);
    for (const auto& [frame, value] : {std::pair{0, 0.0}, {24, 0.3}, {48, 0.0}}) {
      scenes::Keyframe key;
      key.time = scenes::frameTime(scene.animation(), frame);
      key.variation = value;
      scenes::setKey(scene, pull, scenes::ChannelKind::Variation, key);
    }
  }
  return scene;
}

// Proxies from 1000 vertices, of about 500, when the window's level of detail is on.
void smallProxies(app::MainWindow& w) {
  app::LevelOfDetail lod = w.sceneView().levelOfDetail();
  lod.minVertices = 1000;
  lod.proxyVertices = 500;
  w.sceneView().setLevelOfDetail(lod);
}

// Where the arrow of "pull" is drawn now, `along` of its length from its base.
QPoint arrowPixel(app::MainWindow& w, double along) {
  const widgets::WidgetFrame f = w.scene().widgets.affineFrame(w.scene().widgets.find("pull"));
  return toWidget(w, f.frame.translation() + along * f.size * f.frame.linear().col(0));
}

}  // namespace

class LevelOfDetailGuiTest : public QObject {
  Q_OBJECT

 private slots:
  // The same drag with View > Simplify While Moving on and off (unchecked with the mouse): the
  // proxy during the drag only when on, and the full mesh evaluated then only once, at the release
  // (counted); then the same exact points drawn, and the same scene file and exported mesh, byte
  // for byte.
  void aDragWithTheProxyLeavesTheSameDocumentAndFilesAsWithout() {
    QTemporaryDir dir;
    std::map<bool, Eigen::MatrixX3d> drawn;
    // One window (the same view size, so the same pixels make the same drag), the scene set anew.
    auto window = openWindow(QSize(1000, 700));
    QVERIFY(window != nullptr);
    app::MainWindow& w = *window;
    QAction* simplify = action(w, "actionSimplifyWhileMoving");
    QVERIFY(simplify->isChecked());  // the default
    for (const bool lod : {true, false}) {
      w.setScene(sphereScene(false));
      QTest::qWait(50);
      if (!lod) {
        clickMenuItem(w, simplify);
        QTRY_VERIFY(!simplify->isChecked());
      }
      QCOMPARE(w.sceneView().levelOfDetail().enabled, lod);
      smallProxies(w);
      QVERIFY(w.scene().objects().front().mesh.points.rows() > 1000);

      const QPoint from = arrowPixel(w, 0.6);
      const QPoint to = from + QPoint(40, -25);
      sendMouse(w.view(), QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
      QVERIFY(w.deformer().inGesture());
      const scenes::SceneDeformer::Totals pressed = w.deformer().totals();  // every object in full now
      for (int step = 1; step <= 8; ++step) {
        sendMouse(w.view(), QEvent::MouseMove, from + (to - from) * step / 8, Qt::NoButton, Qt::LeftButton);
        QTest::qWait(20);  // the view draws between moves
        QCOMPARE(w.sceneView().showsProxy("sphere"), lod);
      }
      const auto dragged = w.sceneView().stats();
      sendMouse(w.view(), QEvent::MouseButtonRelease, to, Qt::LeftButton, Qt::NoButton);
      QVERIFY(!w.deformer().inGesture());
      const scenes::SceneDeformer::Totals released = w.deformer().totals();
      const auto n = std::uint64_t(w.scene().objects().front().mesh.points.rows());
      if (lod) {
        QCOMPARE(released.deformedPoints - pressed.deformedPoints, n);  // once, at the release
        QVERIFY(released.subsetPoints > pressed.subsetPoints);          // the steps: the proxy's points
      } else {
        QVERIFY(released.deformedPoints - pressed.deformedPoints >= 2 * n);  // every frame
        QCOMPARE(released.subsetPoints, pressed.subsetPoints);
      }
      QVERIFY(!w.sceneView().showsProxy("sphere"));
      if (lod) QCOMPARE(w.sceneView().stats().pointUpdates, dragged.pointUpdates + 1);  // the full mesh at release
      QTest::qWait(50);
      drawn[lod] = w.sceneView().objectPoints("sphere");
      const Eigen::MatrixX3d& exact = w.deformer().points("sphere");
      QCOMPARE(drawn[lod].rows(), exact.rows());
      QVERIFY((drawn[lod] - exact).cwiseAbs().maxCoeff() < 1e-6);
      QVERIFY((exact - w.scene().objects().front().mesh.points).cwiseAbs().maxCoeff() > 1e-3);  // it moved
      const std::string tag = lod ? "on" : "off";
      w.saveScene(std::filesystem::path(dir.path().toStdString()) / ("scene-" + tag + ".json"));
      w.exportMesh(std::filesystem::path(dir.path().toStdString()) / ("sphere-" + tag + ".ply"));
    }
    QVERIFY2(drawn[true] == drawn[false], qPrintable(QString("the drawn points differ by up to %1")
                                                         .arg((drawn[true] - drawn[false]).cwiseAbs().maxCoeff())));
    const std::filesystem::path d = dir.path().toStdString();
    const std::string sceneOn = slurp(d / "scene-on.json"), meshOn = slurp(d / "sphere-on.ply");
    QVERIFY(!sceneOn.empty() && meshOn.size() > 100000);
    QVERIFY(sceneOn == slurp(d / "scene-off.json"));
    QVERIFY(meshOn == slurp(d / "sphere-off.ply"));
  }

  // The proxy is built with the scene, not by the first drag: a drag with real mouse events draws
  // it without building one, and View > Simplify While Moving turned off and on again (clicked)
  // builds it at the next frame, before anything moves.
  void theProxyIsBuiltBeforeTheFirstDrag() {
    auto window = openWindow(QSize(1000, 700));
    QVERIFY(window != nullptr);
    app::MainWindow& w = *window;
    QAction* simplify = action(w, "actionSimplifyWhileMoving");
    if (!simplify->isChecked()) clickMenuItem(w, simplify);  // the preference an earlier test left
    QTRY_VERIFY(simplify->isChecked());
    smallProxies(w);  // before the scene, as the window's own level of detail is
    w.setScene(sphereScene(false));
    QTest::qWait(50);
    QCOMPARE(w.sceneView().stats().proxyBuilds, 1);
    QVERIFY(!w.sceneView().showsProxy("sphere"));

    const QPoint from = arrowPixel(w, 0.6);
    sendMouse(w.view(), QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
    for (int step = 1; step <= 4; ++step) {
      sendMouse(w.view(), QEvent::MouseMove, from + QPoint(10 * step, -6 * step), Qt::NoButton, Qt::LeftButton);
      QTest::qWait(20);
      QVERIFY(w.sceneView().showsProxy("sphere"));
    }
    QCOMPARE(w.sceneView().stats().proxyBuilds, 1);
    sendMouse(w.view(), QEvent::MouseButtonRelease, from + QPoint(40, -24), Qt::LeftButton, Qt::NoButton);
    QVERIFY(!w.sceneView().showsProxy("sphere"));

    clickMenuItem(w, simplify);  // off: the proxy goes at the next frame
    QTRY_VERIFY(!simplify->isChecked());
    QTest::qWait(50);  // that frame
    clickMenuItem(w, simplify);  // on again: built at the next frame
    QTRY_VERIFY(simplify->isChecked());
    QTRY_COMPARE(w.sceneView().stats().proxyBuilds, 2);
    QVERIFY(!w.sceneView().showsProxy("sphere"));
  }

  // While playback draws the sphere's proxy, a click on the widget's arrow selects the widget, as
  // it does with the level of detail off; the pause draws the full mesh at the frame shown.
  void aClickWhileThePlaybackDrawsTheProxyPicksTheWidget() {
    for (const bool lod : {true, false}) {
      auto window = openWindow(QSize(1000, 700));
      QVERIFY(window != nullptr);
      app::MainWindow& w = *window;
      w.setScene(sphereScene(true));
      smallProxies(w);
      app::LevelOfDetail options = w.sceneView().levelOfDetail();
      options.enabled = lod;  // the preference may have been turned off by the test before
      w.sceneView().setLevelOfDetail(options);
      action(w, "actionPlayPause")->trigger();
      QTest::qWait(300);
      QTRY_COMPARE(w.sceneView().showsProxy("sphere"), lod);
      QVERIFY(w.controller().selection().empty());
      click(w, arrowPixel(w, 0.6));
      const widgets::WidgetId pull = w.scene().widgets.find("pull");
      QCOMPARE(w.controller().selection(), std::vector<widgets::WidgetId>{pull});
      action(w, "actionPlayPause")->trigger();
      QVERIFY(!w.sceneView().showsProxy("sphere"));
      QVERIFY((w.sceneView().objectPoints("sphere") - w.deformer().points("sphere")).cwiseAbs().maxCoeff() < 1e-6);
    }
  }
};

int main(int argc, char** argv) { return runGuiTest<LevelOfDetailGuiTest>(argc, argv); }

#include "level_of_detail_gui_test.moc"
