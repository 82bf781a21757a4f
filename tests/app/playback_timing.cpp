// What a user sees of a large mesh in the application window (issues 22 and 39): the real window,
// real mouse events through the event loop, and the time of each frame the view displayed (when Qt
// has swapped the view's native window to the screen, not the event that asked for it), with its
// stages: the evaluation and the view's arrays, VTK's render, and the rest (the swap).
//
//   playback_timing drag <sphere-resolution> [seconds] [--lod on|off] [--proxy N] [--trace file]
//     A sphere in a 4x4x4 cubic B-spline lattice with a translate widget on its top: the widget's
//     arrow is pressed, dragged back and forth by synthesised mouse moves every 16 ms (a pointer
//     at 60 Hz) for `seconds`, and released. Prints each displayed frame's time, the displayed
//     frames per second, and the time from the release to the displayed full-resolution exact mesh
//     (wall clock; the CPU of all threads and of the main thread, which a busy machine changes
//     less; how many times VTK rendered the view for it and after it).
//   playback_timing play <sphere-resolution> [seconds] [--lod on|off] [--proxy N] [--trace file]
//   playback_timing <sphere-resolution> [seconds]          (play, as before)
//   playback_timing still <sphere-resolution> [seconds] [--proxy-shown] [--actors all|none|objects|widgets]
//                         [--upload]
//     The view repainted as fast as it can, nothing changing: what a frame costs by itself (with
//     --upload, what VTK's upload of the shown objects' arrays adds).
//     The same sphere with the widget keyed (0 -> 0.3 -> 0 over 48 frames at 24 fps), played
//     through the timeline's Play action: frames shown per second, frames the view drew per
//     second, and how late a 50 ms timer fired (the event loop's responsiveness).
//
// --lod on|off sets the view's level of detail (SceneView::setLevelOfDetail; the window's default
// otherwise), --proxy N the proxies' size (LevelOfDetail::proxyVertices), --size WxH the window's
// size (default 1280x800), --finish makes VTK's render wait for the rasteriser at its end (so the
// stages are apart: Mesa's llvmpipe rasterises when the frame is flushed), --frames DIR saves the view as PNG three times during the drag and after
// the release (scripts/lod-drag-frames.sh); --trace FILE writes one line per displayed frame: when
// it was displayed, its frame time and its stages, in ms.
// Resolution 1414 is 998,286 vertices, 4472 about 10M. Not a test: scripts/window-timing.sh runs
// it under Xvfb (Mesa's software GL), e.g.
//   xvfb-run -a -s "-screen 0 1280x1024x24" build/tests/app/playback_timing drag 1414 5
#include <QAction>
#include <QApplication>
#include <QImage>
#include <QElapsedTimer>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QSurfaceFormat>
#include <QTest>
#include <QTimer>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <vtkCallbackCommand.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkMapper.h>
#include <vtkNew.h>
#include <vtkRenderer.h>

#include "ffdkit/gui/main_window.h"
#include "ffdkit/render/scene_view.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/scene_changes.h"
#include "ffdkit/viewhost/vtk_view_widget.h"
#include "timeline_widget.h"

using namespace ffdkit;

namespace {

// Each frame the view displayed, timed at its stages: the view's frame event, the end of
// MainWindow's frame work (the evaluation and the view's arrays, VtkViewWidget::aboutToRender),
// VTK's render (the render window's StartEvent and EndEvent) and the swap of the view's window
// (VtkViewWidget::frameSwapped: the frame is on the screen). Each stage in
// wall-clock ms and in the process's CPU ms (all threads: Mesa's rasteriser threads too), which a
// busy machine changes less than the wall clock.
struct FrameClock {
  struct Stamp {
    double wall = 0.0, cpu = 0.0;
  };
  struct Stage {
    double wall = 0.0, cpu = 0.0;
  };
  QElapsedTimer clock;
  Stamp paintAt, preparedAt, renderStart, renderEnd, lastShown;
  std::vector<double> ends;  // when each frame was displayed (frameSwapped), wall-clock ms
  std::vector<Stage> prepares;    // the paint event to the end of the frame's evaluation and arrays
  std::vector<Stage> renders;     // VTK's render, start to end
  std::vector<Stage> composites;  // the end of VTK's render to the frame displayed
  std::vector<double> frameCpu;   // CPU ms from the previous frame displayed to this one
  double now() const { return clock.nsecsElapsed() * 1e-6; }
  Stamp stamp() const {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return {now(), t.tv_sec * 1e3 + t.tv_nsec * 1e-6};
  }
  static Stage between(const Stamp& from, const Stamp& to) { return {to.wall - from.wall, to.cpu - from.cpu}; }
  void clear() {
    ends.clear();
    prepares.clear();
    renders.clear();
    composites.clear();
    frameCpu.clear();
    lastShown = stamp();
  }
  static void onStart(vtkObject*, unsigned long, void* self, void*) {
    auto* me = static_cast<FrameClock*>(self);
    me->renderStart = me->stamp();
  }
  bool finish = false;  // --finish: VTK's render waits for the rasteriser (glFinish) before its end is taken
  static void onEnd(vtkObject*, unsigned long, void* self, void*) {
    auto* me = static_cast<FrameClock*>(self);
    if (me->finish)
      if (QOpenGLContext* context = QOpenGLContext::currentContext()) context->functions()->glFinish();
    me->renderEnd = me->stamp();
    me->rendered = true;
    ++me->renderCount;
  }
  bool rendered = false;  // VTK rendered since the last swap: the next one displays a new frame
  int renderCount = 0;    // VTK's renders of the view
  void onSwapped() {
    // The view's window is swapped when it was exposed again too (its last frame shown again): only
    // a swap after a render of the view displays a new frame of it.
    if (!rendered) return;
    rendered = false;
    const Stamp shown = stamp();
    ends.push_back(shown.wall);
    prepares.push_back(between(paintAt, preparedAt));
    renders.push_back(between(renderStart, renderEnd));
    composites.push_back(between(renderEnd, shown));
    frameCpu.push_back(shown.cpu - lastShown.cpu);
    lastShown = shown;
  }
};

// The view's frame events (VtkViewWidget::frameEventType, each one a frame pass) on the frame
// clock, and how many there were.
class PaintCounter : public QObject {
 public:
  explicit PaintCounter(FrameClock& frames) : frames_(frames) {}
  int paints = 0;
  bool eventFilter(QObject*, QEvent* event) override {
    if (event->type() == app::VtkViewWidget::frameEventType()) {
      ++paints;
      frames_.paintAt = frames_.stamp();
    }
    return false;
  }

 private:
  FrameClock& frames_;
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

// CPU ms of the calling thread (the main thread: the evaluation, VTK, and Mesa's vertex processing
// and triangle setup, which its rasteriser threads wait for).
double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// One line per displayed frame: when it was displayed and its frame time, then its stages.
void writeTrace(const char* path, const FrameClock& frames, std::size_t count, double start) {
  if (path == nullptr) return;
  std::FILE* out = std::fopen(path, "w");
  if (out == nullptr) {
    std::fprintf(stderr, "cannot write %s\n", path);
    return;
  }
  std::fprintf(out,
               "# displayed (ms after the press or Play), frame time (ms since the previous), then wall-clock ms of "
               "the stages: evaluation and arrays, VTK render, render end to displayed; CPU ms of the frame\n");
  double previous = start;
  for (std::size_t i = 0; i < count; ++i) {
    const double end = frames.ends[i];
    std::fprintf(out, "%.1f %.1f %.1f %.1f %.1f %.1f\n", end - start, end - previous, frames.prepares[i].wall,
                 frames.renders[i].wall, frames.composites[i].wall, frames.frameCpu[i]);
    previous = end;
  }
  std::fclose(out);
}

// The medians of the frames' stages [first, first + count), wall clock and CPU.
void printStages(const FrameClock& frames, std::size_t first, std::size_t count) {
  const std::size_t last = std::min(frames.ends.size(), first + count);
  auto stage = [&](const std::vector<FrameClock::Stage>& v, bool cpu) {
    std::vector<double> values;
    for (std::size_t i = first; i < last; ++i) values.push_back(cpu ? v[i].cpu : v[i].wall);
    return median(values);
  };
  std::printf("  per frame, medians (wall ms / CPU ms): evaluation and arrays %.1f / %.1f, VTK render %.1f / %.1f, "
              "render end to displayed %.1f / %.1f; CPU per frame %.1f ms\n",
              stage(frames.prepares, false), stage(frames.prepares, true), stage(frames.renders, false),
              stage(frames.renders, true), stage(frames.composites, false), stage(frames.composites, true),
              median(std::vector<double>(frames.frameCpu.begin() + long(first), frames.frameCpu.begin() + long(last))));
}

struct Options {
  std::string mode = "play";
  int resolution = 1414;
  double seconds = 5.0;
  int lod = -1;  // -1: the window's default
  long proxyVertices = 0;  // 0: the default
  const char* frames = nullptr;  // a folder for PNG frames of the drag (not timed then)
  const char* trace = nullptr;
  int width = 1280, height = 800;  // the window's size
  bool finish = false;             // glFinish at the end of VTK's render (the stages apart)
  bool proxyShown = false;         // still: the proxies drawn
  std::string actors = "all";      // still: all, none, objects or widgets shown
  bool upload = false;             // still: the objects' arrays uploaded again before each frame
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
    else if (std::strcmp(argv[i], "--upload") == 0)
      o.upload = true;
    else if (std::strcmp(argv[i], "--proxy-shown") == 0)
      o.proxyShown = true;
    else if (std::strcmp(argv[i], "--actors") == 0 && i + 1 < argc)
      o.actors = argv[++i];
    else if (std::strcmp(argv[i], "--finish") == 0)
      o.finish = true;
    else if (std::strcmp(argv[i], "--size") == 0 && i + 1 < argc)
      std::sscanf(argv[++i], "%dx%d", &o.width, &o.height);
    else
      positional.push_back(argv[i]);
  }
  std::size_t next = 0;
  if (!positional.empty() && (positional[0] == "drag" || positional[0] == "play" || positional[0] == "still")) o.mode = positional[next++];
  if (next < positional.size()) o.resolution = std::atoi(positional[next++].c_str());
  if (next < positional.size()) o.seconds = std::atof(positional[next++].c_str());
  return o;
}

int play(app::MainWindow& window, const Options& o, FrameClock& frames, const PaintCounter& paints) {
  auto* timeline = window.findChild<app::TimelineWidget*>("timeline");

  // A 50 ms probe timer: how late it fires says how long the event loop was busy.
  double lastProbe = 0.0, worstLate = 0.0, sumLate = 0.0;
  int probes = 0;
  QTimer probe;
  probe.setTimerType(Qt::PreciseTimer);
  QObject::connect(&probe, &QTimer::timeout, [&] {
    const double now = frames.now();
    if (probes > 0) {
      const double late = std::max(0.0, now - lastProbe - 50.0);
      worstLate = std::max(worstLate, late);
      sumLate += late;
    }
    lastProbe = now;
    ++probes;
  });

  frames.clear();
  const double start = frames.now();
  window.findChild<QAction*>("actionPlayPause")->trigger();
  const int paintsBefore = paints.paints;
  probe.start(50);
  QTest::qWait(static_cast<int>(o.seconds * 1000));
  window.findChild<QAction*>("actionPlayPause")->trigger();
  probe.stop();
  const double elapsed = (frames.now() - start) * 1e-3;
  const std::size_t shown = frames.ends.size();
  QTest::qWait(300);  // the frame after Pause
  const auto& stats = window.deformer().lastStats();
  std::printf("play: %lld points, %.1f s at %g fps: %d timeline frames (%.1f fps), %d view paints (%.1f fps), "
              "%zu frames displayed (%.1f fps)\n",
              static_cast<long long>(window.scene().objects().front().mesh.points.rows()), elapsed,
              window.scene().animation().framesPerSecond, timeline->playedFrames(), timeline->playedFrames() / elapsed,
              paints.paints - paintsBefore, (paints.paints - paintsBefore) / elapsed, shown, shown / elapsed);
  printStages(frames, 0, shown);
  std::printf("event loop: a 50 ms timer fired late by %.0f ms on average, %.0f ms at worst (%d ticks)\n",
              probes > 1 ? sumLate / (probes - 1) : 0.0, worstLate, probes);
  std::printf("last deform: %.1f ms engine\n", stats.seconds * 1e3);
  writeTrace(o.trace, frames, shown, start);
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

  frames.clear();
  const double start = frames.now();
  sendMouse(view, QEvent::MouseButtonPress, press, Qt::LeftButton, Qt::LeftButton);
  const auto pressed = window.sceneView().stats();
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
    const double t = (frames.now() - start) * 1e-3;
    const double offset = 40.0 * std::sin(t * 2.0);  // px; about 0.3 back-and-forth per second
    const double before = frames.now();
    sendMouse(view, QEvent::MouseMove, press + offset * unit, Qt::NoButton, Qt::LeftButton);
    handling.push_back(frames.now() - before);
    if (o.frames != nullptr && captured < 3 && t > (captured + 1) * o.seconds / 4.0)
      capture("lod-drag-" + std::to_string(++captured));
  });
  mover.start(16);
  QTest::qWait(static_cast<int>(o.seconds * 1000));
  mover.stop();
  const double releaseAt = frames.now();
  const FrameClock::Stamp releaseStamp = frames.stamp();
  const double releaseThreadCpu = threadCpuMs();
  const std::size_t during = frames.ends.size();
  const auto before = window.sceneView().stats();
  const int rendersBefore = frames.renderCount;
  sendMouse(view, QEvent::MouseButtonRelease, press, Qt::LeftButton, Qt::NoButton);
  const double handled = frames.now();
  // The first frame displayed after the release was handled shows the exact mesh (the release ends
  // the gesture; the next frame evaluates exactly and draws the full mesh).
  QElapsedTimer wait;
  wait.start();
  while (frames.ends.size() == during || frames.ends.back() < handled) {
    QApplication::processEvents(QEventLoop::AllEvents, 5);
    if (wait.elapsed() > 20000) break;
  }
  const double exactShown = frames.ends.empty() ? 0.0 : frames.ends.back();
  const double exactCpu = frames.ends.size() > during ? frames.lastShown.cpu - releaseStamp.cpu : 0.0;
  const double exactThreadCpu = threadCpuMs() - releaseThreadCpu;
  const int rendersToExact = frames.renderCount - rendersBefore;
  const auto after = window.sceneView().stats();
  capture("lod-drag-released");
  QTest::qWait(300);  // renders the release asks for after the exact frame
  const int rendersAfterExact = frames.renderCount - rendersBefore - rendersToExact;

  std::vector<double> frameTimes;
  for (std::size_t i = 1; i < during; ++i) frameTimes.push_back(frames.ends[i] - frames.ends[i - 1]);
  const double dragSeconds = (releaseAt - start) * 1e-3;
  const double spanSeconds = during > 1 ? (frames.ends[during - 1] - frames.ends[0]) * 1e-3 : 0.0;
  std::printf("drag: %lld points, %.1f s, %d moves, %zu displayed frames: %.1f frames/s (%.1f between the first "
              "and last), frame time median %.0f ms, worst %.0f ms\n",
              static_cast<long long>(window.scene().objects().front().mesh.points.rows()), dragSeconds, moves, during,
              during / dragSeconds, spanSeconds > 0 ? (during - 1) / spanSeconds : 0.0, median(frameTimes),
              frameTimes.empty() ? 0.0 : *std::max_element(frameTimes.begin(), frameTimes.end()));
  printStages(frames, 0, during);
  std::printf("  actors built during the drag: the transformer's %d times, widgets' %d times\n",
              before.overlayBuilds - pressed.overlayBuilds, before.widgetActorBuilds - pressed.widgetActorBuilds);
  std::printf("  a move's handling median %.1f ms, worst %.1f ms\n", median(handling),
              handling.empty() ? 0.0 : *std::max_element(handling.begin(), handling.end()));
  const std::size_t last = frames.ends.size() - 1;
  std::printf("release: handled in %.0f ms, exact mesh displayed %.0f ms after the release (%d full point updates "
              "at release, gesture %s); that frame: evaluation and arrays %.0f ms, VTK render %.0f ms, render end "
              "to displayed %.0f ms\n",
              handled - releaseAt, exactShown - releaseAt, after.pointUpdates - before.pointUpdates,
              window.deformer().inGesture() ? "still open" : "ended", frames.prepares[last].wall,
              frames.renders[last].wall, frames.composites[last].wall);
  std::printf("  release to the exact mesh displayed: %.0f ms of CPU (all threads), %.0f ms of the main thread's; "
              "VTK renders: %d to the exact mesh, %d in the 300 ms after it\n",
              exactCpu, exactThreadCpu, rendersToExact, rendersAfterExact);
  writeTrace(o.trace, frames, during, start);
  return 0;
}

// The view repainted as fast as it can with nothing changing (the scene evaluated once): the cost of
// a frame itself. --proxy-shown draws the large objects' proxies (SceneView::setMoving), --actors
// none hides every actor of the view (the fixed cost of a frame: clearing, VTK's copies and the
// swap), objects hides the widgets', widgets the objects'.
int still(app::MainWindow& window, const Options& o, FrameClock& frames) {
  app::SceneView& view = window.sceneView();
  if (o.proxyShown) {
    view.setMoving(true);
    view.refresh(window.scene(), window.deformer());
  }
  vtkRenderer* renderer = window.view()->renderer();
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  int hidden = 0, shown = 0;
  while (vtkActor* actor = actors->GetNextActor()) {
    vtkDataSet* input = actor->GetMapper() != nullptr ? actor->GetMapper()->GetInput() : nullptr;
    const bool object = input != nullptr && input->GetNumberOfPoints() >= 1000;  // the sphere or its proxy
    const bool hide = o.actors == "none" || (o.actors == "objects" && !object) || (o.actors == "widgets" && object);
    if (hide && actor->GetVisibility()) {
      actor->SetVisibility(false);
      ++hidden;
    }
    shown += actor->GetVisibility();
  }
  std::printf("still: %d actors hidden, %d shown (%s)\n", hidden, shown, o.actors.c_str());
  // --upload: the shown objects' point and normal arrays marked modified before each frame, so VTK
  // uploads them again (what a frame after a change of the points pays).
  std::vector<vtkDataSet*> uploaded;
  if (o.upload) {
    actors->InitTraversal();
    while (vtkActor* actor = actors->GetNextActor()) {
      vtkDataSet* input = actor->GetMapper() != nullptr ? actor->GetMapper()->GetInput() : nullptr;
      if (actor->GetVisibility() && input != nullptr && input->GetNumberOfPoints() >= 1000) uploaded.push_back(input);
    }
  }
  QTimer repaint;
  QObject::connect(&repaint, &QTimer::timeout, [&] {
    for (vtkDataSet* input : uploaded) {
      if (auto* poly = vtkPolyData::SafeDownCast(input)) poly->GetPoints()->Modified();
      if (vtkDataArray* normals = input->GetPointData()->GetNormals()) normals->Modified();
      input->Modified();
    }
    window.view()->requestRender();
  });
  frames.clear();
  const double start = frames.now();
  repaint.start(0);
  QTest::qWait(static_cast<int>(o.seconds * 1000));
  repaint.stop();
  const std::size_t shownFrames = frames.ends.size();
  std::vector<double> frameTimes;
  for (std::size_t i = 1; i < shownFrames; ++i) frameTimes.push_back(frames.ends[i] - frames.ends[i - 1]);
  std::printf("still: %zu frames displayed in %.1f s, frame time median %.1f ms\n", shownFrames,
              (frames.now() - start) * 1e-3, median(frameTimes));
  printStages(frames, 0, shownFrames);
  writeTrace(o.trace, frames, shownFrames, start);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  QSurfaceFormat::setDefaultFormat(app::VtkViewWidget::defaultFormat());
  QApplication application(argc, argv);
  const Options o = parse(argc, argv);
  app::MainWindow window;
  window.setLayoutRemembered(false);
  window.resize(o.width, o.height);
  window.show();
  if (!QTest::qWaitForWindowExposed(&window)) return 1;
  // The level of detail before the scene, as the window sets it at its start: the scene's proxies
  // are built with the scene (SceneView::show), not at the first drag.
  app::LevelOfDetail lod = window.sceneView().levelOfDetail();
  if (o.lod >= 0) lod.enabled = o.lod == 1;
  if (o.proxyVertices > 0) lod.proxyVertices = o.proxyVertices;
  window.sceneView().setLevelOfDetail(lod);
  QElapsedTimer setup;
  setup.start();
  window.setScene(sphereScene(o.resolution, o.mode == "play"));
  std::printf("scene of %lld points set in %.1f s\n",
              static_cast<long long>(window.scene().objects().front().mesh.points.rows()), setup.elapsed() * 1e-3);
  const QSize viewSize = window.view()->size() * window.view()->devicePixelRatioF();
  std::printf("level of detail: %s (a proxy of about %lld vertices for objects from %lld vertices); window %dx%d, "
              "view %dx%d pixels\n",
              lod.enabled ? "on" : "off", static_cast<long long>(lod.proxyVertices),
              static_cast<long long>(lod.minVertices), window.width(), window.height(), viewSize.width(),
              viewSize.height());
  QTest::qWait(1000);

  FrameClock frames;
  frames.clock.start();
  frames.finish = o.finish;
  PaintCounter paints(frames);
  window.view()->installEventFilter(&paints);
  // After MainWindow's own handler (connected first): the frame's evaluation and arrays are done.
  QObject::connect(window.view(), &app::VtkViewWidget::aboutToRender, [&] { frames.preparedAt = frames.stamp(); });
  QObject::connect(window.view(), &app::VtkViewWidget::frameSwapped, [&] { frames.onSwapped(); });
  vtkNew<vtkCallbackCommand> onEnd;
  onEnd->SetCallback(&FrameClock::onEnd);
  onEnd->SetClientData(&frames);
  window.view()->renderWindow()->AddObserver(vtkCommand::EndEvent, onEnd);
  vtkNew<vtkCallbackCommand> onStart;
  onStart->SetCallback(&FrameClock::onStart);
  onStart->SetClientData(&frames);
  window.view()->renderWindow()->AddObserver(vtkCommand::StartEvent, onStart);
  if (o.mode == "still") return still(window, o, frames);
  return o.mode == "drag" ? drag(window, o, frames) : play(window, o, frames, paints);
}
