// Measures playback in the application window (issue 22): a sphere of ~1M vertices in a 4x4x4
// cubic B-spline lattice, one keyed translate widget (0 -> 0.3 -> 0 over 48 frames at 24 fps),
// played for a few seconds through the timeline's Play action. Reports the frames the timeline
// showed per second, the frames the view drew per second, and how late a 50 ms timer fired
// (the event loop's responsiveness while playing). Not a test: run by hand under Xvfb, e.g.
//   xvfb-run -a -s "-screen 0 1280x1024x24" build/tests/app/playback_timing 1414 5
#include <QAction>
#include <QApplication>
#include <QElapsedTimer>
#include <QSurfaceFormat>
#include <QTest>
#include <QTimer>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "ffdkit/gui/main_window.h"
#include "ffdkit/viewhost/vtk_view_widget.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/scene_changes.h"
#include "timeline_widget.h"

using namespace ffdkit;

namespace {

// Counts the view's paints (each one a VTK render of the frame).
class PaintCounter : public QObject {
 public:
  int paints = 0;
  bool eventFilter(QObject*, QEvent* event) override {
    if (event->type() == QEvent::Paint) ++paints;
    return false;
  }
};

scenes::Scene keyedSphere(int resolution) {
  scenes::Scene scene;
  scenes::SceneObject sphere;
  sphere.name = "sphere";
  sphere.source = scenes::PrimitiveOptions{.kind = scenes::PrimitiveKind::Sphere, .resolution = resolution};
  sphere.mesh = scenes::buildObjectMesh(sphere.source, ".");
  scene.addObject(std::move(sphere));
  scenes::AttachOptions attach;
  attach.latticeName = "lattice";
  attach.counts = Eigen::Vector3i::Constant(4);
  attach.settings.basis = {ffd::AxisBasis::bspline(3), ffd::AxisBasis::bspline(3), ffd::AxisBasis::bspline(3)};
  const auto lattice = scenes::attachNewLattice(scene, {"sphere"}, attach);
  const auto cell = scene.widgets.addCell(lattice, widgets::CellSpec::point(1, 1, 3), "top");
  const auto pull = scene.widgets.addAffine(cell, widgets::AffineKind::Translate, "pull");
  scene.setFrameRange(scene.animation().firstFrame, 48);
  for (const auto& [frame, value] : {std::pair{0, 0.0}, {24, 0.3}, {48, 0.0}}) {
    scenes::Keyframe key;
    key.time = scenes::frameTime(scene.animation(), frame);
    key.variation = value;
    scenes::setKey(scene, pull, scenes::ChannelKind::Variation, key);
  }
  return scene;
}

}  // namespace

int main(int argc, char** argv) {
  QSurfaceFormat::setDefaultFormat(app::VtkViewWidget::defaultFormat());
  QApplication application(argc, argv);
  const int resolution = argc > 1 ? std::atoi(argv[1]) : 1414;
  const double seconds = argc > 2 ? std::atof(argv[2]) : 5.0;
  app::MainWindow window;
  window.setLayoutRemembered(false);
  window.resize(1280, 800);
  window.show();
  if (!QTest::qWaitForWindowExposed(&window)) return 1;
  window.setScene(keyedSphere(resolution));
  QTest::qWait(500);
  auto* timeline = window.findChild<app::TimelineWidget*>("timeline");
  PaintCounter paints;
  window.view()->installEventFilter(&paints);

  // A 50 ms probe timer: how late it fires says how long the event loop was busy.
  QElapsedTimer probeClock;
  double lastProbe = 0.0, worstLate = 0.0, sumLate = 0.0;
  int probes = 0;
  QTimer probe;
  probe.setTimerType(Qt::PreciseTimer);
  QObject::connect(&probe, &QTimer::timeout, [&] {
    const double now = probeClock.nsecsElapsed() * 1e-6;
    if (probes > 0) {
      const double late = std::max(0.0, now - lastProbe - 50.0);
      worstLate = std::max(worstLate, late);
      sumLate += late;
    }
    lastProbe = now;
    ++probes;
  });

  window.findChild<QAction*>("actionPlayPause")->trigger();
  const int paintsBefore = paints.paints;
  probeClock.start();
  probe.start(50);
  QElapsedTimer wall;
  wall.start();
  QTest::qWait(static_cast<int>(seconds * 1000));
  window.findChild<QAction*>("actionPlayPause")->trigger();
  probe.stop();
  const double elapsed = wall.nsecsElapsed() * 1e-9;
  const auto& stats = window.deformer().lastStats();
  std::printf("points %lld, played %.1f s at %g fps: %d timeline frames (%.1f fps), %d view paints (%.1f fps)\n",
              static_cast<long long>(window.scene().objects().front().mesh.points.rows()), elapsed,
              window.scene().animation().framesPerSecond, timeline->playedFrames(), timeline->playedFrames() / elapsed,
              paints.paints - paintsBefore, (paints.paints - paintsBefore) / elapsed);
  std::printf("event loop: a 50 ms timer fired late by %.0f ms on average, %.0f ms at worst (%d ticks)\n",
              probes > 1 ? sumLate / (probes - 1) : 0.0, worstLate, probes);
  std::printf("last deform: %.1f ms engine\n", stats.seconds * 1e3);
  return 0;
}
