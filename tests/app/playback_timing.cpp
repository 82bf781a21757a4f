// What a user sees of a large mesh in the application window (issues 22 and 39): the real window,
// real mouse events through the event loop, and the time of each frame the view displayed (the
// render window's end of render, not the event that asked for it).
//
//   playback_timing drag <sphere-resolution> [seconds] [--lod on|off] [--proxy N] [--trace file]
//     A sphere in a 4x4x4 cubic B-spline lattice with a translate widget on its top: the widget's
//     arrow is pressed, dragged back and forth by synthesised mouse moves every 16 ms (a pointer
//     at 60 Hz) for `seconds`, and released. Prints each displayed frame's time, the displayed
//     frames per second, and the time from the release to the displayed full-resolution exact mesh.
//   playback_timing play <sphere-resolution> [seconds] [--lod on|off] [--proxy N] [--trace file]
//   playback_timing <sphere-resolution> [seconds]          (play, as before)
//     The same sphere with the widget keyed (0 -> 0.3 -> 0 over 48 frames at 24 fps), played
//     through the timeline's Play action: frames shown per second, frames the view drew per
//     second, and how late a 50 ms timer fired (the event loop's responsiveness).
//
// --lod on|off sets the view's level of detail (SceneView::setLevelOfDetail; the window's default
// otherwise), --proxy N the proxies' size (LevelOfDetail::proxyVertices), --frames DIR saves the
// view as PNG three times during the drag and after the release (scripts/lod-drag-frames.sh); --trace writes one line per displayed frame: its end time and its duration in ms.
// Resolution 1414 is 998,286 vertices, 4472 about 10M. Not a test: scripts/window-timing.sh runs
// it under Xvfb (Mesa's software GL), e.g.
//   xvfb-run -a -s "-screen 0 1280x1024x24" build/tests/app/playback_timing drag 1414 5
#include <QAction>
#include <QApplication>
#include <QImage>
#include <QElapsedTimer>
#include <QMouseEvent>
#include <QSurfaceFormat>
#include <QTest>
#include <QTimer>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <vtkCallbackCommand.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>

#include "ffdkit/gui/main_window.h"
#include "ffdkit/render/scene_view.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/scene_changes.h"
#include "ffdkit/viewhost/vtk_view_widget.h"
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

// The end time of every render of the view's window (ms on `clock`).
// and how long each render took (from the render window's start of render).
struct FrameClock {
  QElapsedTimer clock;
  std::vector<double> ends, renders;
  double started = 0.0;
  static void onStart(vtkObject*, unsigned long, void* self, void*) {
    auto* me = static_cast<FrameClock*>(self);
    me->started = me->clock.nsecsElapsed() * 1e-6;
  }
  static void onEnd(vtkObject*, unsigned long, void* self, void*) {
    auto* me = static_cast<FrameClock*>(self);
    me->ends.push_back(me->clock.nsecsElapsed() * 1e-6);
    me->renders.push_back(me->ends.back() - me->started);
  }
};

// The sphere, its lattice and the translate widget "pull" on its top; keyed when `keyed`.
scenes::Scene sphereScene(int resolution, bool keyed) {
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
  if (!keyed) return scene;
  scene.setFrameRange(scene.animation().firstFrame, 48);
  for (const auto& [frame, value] : {std::pair{0, 0.0}, {24, 0.3}, {48, 0.0}}) {
    scenes::Keyframe key;
    key.time = scenes::frameTime(scene.animation(), frame);
    key.variation = value;
    scenes::setKey(scene, pull, scenes::ChannelKind::Variation, key);
  }
  return scene;
}

void sendMouse(QWidget* widget, QEvent::Type type, QPointF at, Qt::MouseButton button, Qt::MouseButtons buttons) {
  QMouseEvent event(type, at, widget->mapToGlobal(at), button, buttons, Qt::NoModifier);
  QApplication::sendEvent(widget, &event);
}

// Where the view draws world point p, in the view widget's (logical) coordinates.
QPointF toWidget(app::MainWindow& w, const Eigen::Vector3d& p) {
  const Eigen::Vector2d d = w.sceneView().displayPoint(p);
  const double ratio = w.view()->devicePixelRatioF();
  return {d.x() / ratio, (w.view()->height() * ratio - 1.0 - d.y()) / ratio};
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void writeTrace(const char* path, const std::vector<double>& ends, double start) {
  if (path == nullptr) return;
  std::FILE* out = std::fopen(path, "w");
  if (out == nullptr) {
    std::fprintf(stderr, "cannot write %s\n", path);
    return;
  }
  std::fprintf(out, "# frame end (ms after the press or Play)  frame time (ms since the previous end)\n");
  double previous = start;
  for (double end : ends) {
    std::fprintf(out, "%.1f %.1f\n", end - start, end - previous);
    previous = end;
  }
  std::fclose(out);
}

struct Options {
  std::string mode = "play";
  int resolution = 1414;
  double seconds = 5.0;
  int lod = -1;  // -1: the window's default
  long proxyVertices = 0;  // 0: the default
  const char* frames = nullptr;  // a folder for PNG frames of the drag (not timed then)
  const char* trace = nullptr;
};

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--lod") == 0 && i + 1 < argc)
      o.lod = std::strcmp(argv[++i], "off") != 0;
    else if (std::strcmp(argv[i], "--proxy") == 0 && i + 1 < argc)
      o.proxyVertices = std::atol(argv[++i]);
    else if (std::strcmp(argv[i], "--frames") == 0 && i + 1 < argc)
      o.frames = argv[++i];
    else if (std::strcmp(argv[i], "--trace") == 0 && i + 1 < argc)
      o.trace = argv[++i];
    else
      positional.push_back(argv[i]);
  }
  std::size_t next = 0;
  if (!positional.empty() && (positional[0] == "drag" || positional[0] == "play")) o.mode = positional[next++];
  if (next < positional.size()) o.resolution = std::atoi(positional[next++].c_str());
  if (next < positional.size()) o.seconds = std::atof(positional[next++].c_str());
  return o;
}

int play(app::MainWindow& window, const Options& o, FrameClock& frames) {
  auto* timeline = window.findChild<app::TimelineWidget*>("timeline");
  PaintCounter paints;
  window.view()->installEventFilter(&paints);

  // A 50 ms probe timer: how late it fires says how long the event loop was busy.
  double lastProbe = 0.0, worstLate = 0.0, sumLate = 0.0;
  int probes = 0;
  QTimer probe;
  probe.setTimerType(Qt::PreciseTimer);
  QObject::connect(&probe, &QTimer::timeout, [&] {
    const double now = frames.clock.nsecsElapsed() * 1e-6;
    if (probes > 0) {
      const double late = std::max(0.0, now - lastProbe - 50.0);
      worstLate = std::max(worstLate, late);
      sumLate += late;
    }
    lastProbe = now;
    ++probes;
  });

  frames.ends.clear();
  const double start = frames.clock.nsecsElapsed() * 1e-6;
  window.findChild<QAction*>("actionPlayPause")->trigger();
  const int paintsBefore = paints.paints;
  probe.start(50);
  QTest::qWait(static_cast<int>(o.seconds * 1000));
  window.findChild<QAction*>("actionPlayPause")->trigger();
  probe.stop();
  const double elapsed = (frames.clock.nsecsElapsed() * 1e-6 - start) * 1e-3;
  const std::vector<double> shown = frames.ends;
  QTest::qWait(300);  // the frame after Pause
  const auto& stats = window.deformer().lastStats();
  std::printf("play: %lld points, %.1f s at %g fps: %d timeline frames (%.1f fps), %d view paints (%.1f fps), "
              "%zu renders (%.1f fps)\n",
              static_cast<long long>(window.scene().objects().front().mesh.points.rows()), elapsed,
              window.scene().animation().framesPerSecond, timeline->playedFrames(), timeline->playedFrames() / elapsed,
              paints.paints - paintsBefore, (paints.paints - paintsBefore) / elapsed, shown.size(),
              shown.size() / elapsed);
  std::printf("event loop: a 50 ms timer fired late by %.0f ms on average, %.0f ms at worst (%d ticks)\n",
              probes > 1 ? sumLate / (probes - 1) : 0.0, worstLate, probes);
  std::printf("last deform: %.1f ms engine\n", stats.seconds * 1e3);
  writeTrace(o.trace, shown, start);
  return 0;
}

int drag(app::MainWindow& window, const Options& o, FrameClock& frames) {
  const widgets::WidgetModel& model = window.scene().widgets;
  const widgets::WidgetId pull = model.find("pull");
  const widgets::WidgetFrame f = model.affineFrame(pull);
  const Eigen::Vector3d axis = f.frame.linear().col(0);
  const QPointF press = toWidget(window, f.frame.translation() + 0.5 * f.size * axis);
  const QPointF along = toWidget(window, f.frame.translation() + 1.5 * f.size * axis) - press;
  const double length = std::hypot(along.x(), along.y());
  const QPointF unit = length > 0 ? along / length : QPointF(1, 0);
  QWidget* view = window.view();
  // --frames: the view as drawn, 480 pixels wide, three times during the drag and after the release.
  int captured = 0;
  auto capture = [&](const std::string& name) {
    if (o.frames == nullptr) return;
    const std::string path = std::string(o.frames) + "/" + name + ".png";
    if (!window.view()->grabFramebuffer().scaledToWidth(480, Qt::SmoothTransformation).save(QString::fromStdString(path)))
      std::fprintf(stderr, "cannot write %s\n", path.c_str());
  };

  frames.ends.clear();
  frames.renders.clear();
  const double start = frames.clock.nsecsElapsed() * 1e-6;
  sendMouse(view, QEvent::MouseButtonPress, press, Qt::LeftButton, Qt::LeftButton);
  if (window.sceneView().stats().pointUpdates < 0 || !window.deformer().inGesture())
    std::printf("warning: the press did not start a gesture (missed the arrow at %.0f, %.0f)\n", press.x(), press.y());
  // The pointer moves 40 px out and back along the arrow, a move every 16 ms (QTimer events, so
  // the event loop renders between them as it does for a real pointer).
  int moves = 0;
  std::vector<double> handling;  // ms each move took to handle (the model, the deformer, the view's arrays)
  QTimer mover;
  mover.setTimerType(Qt::PreciseTimer);
  QObject::connect(&mover, &QTimer::timeout, [&] {
    ++moves;
    const double t = (frames.clock.nsecsElapsed() * 1e-6 - start) * 1e-3;
    const double offset = 40.0 * std::sin(t * 2.0);  // px; about 0.3 back-and-forth per second
    const double before = frames.clock.nsecsElapsed() * 1e-6;
    sendMouse(view, QEvent::MouseMove, press + offset * unit, Qt::NoButton, Qt::LeftButton);
    handling.push_back(frames.clock.nsecsElapsed() * 1e-6 - before);
    if (o.frames != nullptr && captured < 3 && t > (captured + 1) * o.seconds / 4.0)
      capture("lod-drag-" + std::to_string(++captured));
  });
  mover.start(16);
  QTest::qWait(static_cast<int>(o.seconds * 1000));
  mover.stop();
  const double releaseAt = frames.clock.nsecsElapsed() * 1e-6;
  const std::size_t during = frames.ends.size();
  const auto before = window.sceneView().stats();
  sendMouse(view, QEvent::MouseButtonRelease, press, Qt::LeftButton, Qt::NoButton);
  const double handled = frames.clock.nsecsElapsed() * 1e-6;
  // The first render that ends after the release was handled shows the exact mesh (the release
  // evaluates exactly and refreshes the view before it returns).
  QElapsedTimer wait;
  wait.start();
  while (frames.ends.size() == during || frames.ends.back() < handled) {
    QApplication::processEvents(QEventLoop::AllEvents, 5);
    if (wait.elapsed() > 20000) break;
  }
  const double exactShown = frames.ends.empty() ? 0.0 : frames.ends.back();
  const auto after = window.sceneView().stats();
  capture("lod-drag-released");

  std::vector<double> frameTimes;
  for (std::size_t i = 1; i < during; ++i) frameTimes.push_back(frames.ends[i] - frames.ends[i - 1]);
  const double dragSeconds = (releaseAt - start) * 1e-3;
  const double spanSeconds = during > 1 ? (frames.ends[during - 1] - frames.ends[0]) * 1e-3 : 0.0;
  std::printf("drag: %lld points, %.1f s, %d moves, %zu displayed frames: %.1f frames/s (%.1f between the first "
              "and last), frame time median %.0f ms, worst %.0f ms\n",
              static_cast<long long>(window.scene().objects().front().mesh.points.rows()), dragSeconds, moves, during,
              during / dragSeconds, spanSeconds > 0 ? (during - 1) / spanSeconds : 0.0, median(frameTimes),
              frameTimes.empty() ? 0.0 : *std::max_element(frameTimes.begin(), frameTimes.end()));
  std::printf("  of which: render (start to end) median %.0f ms, a move's handling median %.0f ms, worst %.0f ms\n",
              median(std::vector<double>(frames.renders.begin(), frames.renders.begin() + long(during))), median(handling),
              handling.empty() ? 0.0 : *std::max_element(handling.begin(), handling.end()));
  std::printf("release: handled in %.0f ms, exact mesh displayed %.0f ms after the release (%d full point updates "
              "at release, gesture %s)\n",
              handled - releaseAt, exactShown - releaseAt, after.pointUpdates - before.pointUpdates,
              window.deformer().inGesture() ? "still open" : "ended");
  writeTrace(o.trace, std::vector<double>(frames.ends.begin(), frames.ends.begin() + long(during)), start);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  QSurfaceFormat::setDefaultFormat(app::VtkViewWidget::defaultFormat());
  QApplication application(argc, argv);
  const Options o = parse(argc, argv);
  app::MainWindow window;
  window.setLayoutRemembered(false);
  window.resize(1280, 800);
  window.show();
  if (!QTest::qWaitForWindowExposed(&window)) return 1;
  QElapsedTimer setup;
  setup.start();
  window.setScene(sphereScene(o.resolution, o.mode == "play"));
  std::printf("scene of %lld points set in %.1f s\n",
              static_cast<long long>(window.scene().objects().front().mesh.points.rows()), setup.elapsed() * 1e-3);
  app::LevelOfDetail lod = window.sceneView().levelOfDetail();
  if (o.lod >= 0) lod.enabled = o.lod == 1;
  if (o.proxyVertices > 0) lod.proxyVertices = o.proxyVertices;
  window.sceneView().setLevelOfDetail(lod);
  std::printf("level of detail: %s (a proxy of about %lld vertices for objects from %lld vertices)\n",
              lod.enabled ? "on" : "off", static_cast<long long>(lod.proxyVertices),
              static_cast<long long>(lod.minVertices));
  QTest::qWait(1000);

  FrameClock frames;
  frames.clock.start();
  vtkNew<vtkCallbackCommand> onEnd;
  onEnd->SetCallback(&FrameClock::onEnd);
  onEnd->SetClientData(&frames);
  window.view()->renderWindow()->AddObserver(vtkCommand::EndEvent, onEnd);
  vtkNew<vtkCallbackCommand> onStart;
  onStart->SetCallback(&FrameClock::onStart);
  onStart->SetClientData(&frames);
  window.view()->renderWindow()->AddObserver(vtkCommand::StartEvent, onStart);
  return o.mode == "drag" ? drag(window, o, frames) : play(window, o, frames);
}
