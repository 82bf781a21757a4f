// Playback (issue 22): one frame of an animation on a sphere of ~1M vertices in a 4x4x4 cubic
// B-spline lattice with one keyed point widget (0 -> 0.3 -> 0 over 48 frames, smooth):
//   BM_AnimationFrame:  the engine's work per frame, app::Timeline::advance by one frame without a
//                       view: scenes::applyAnimation (a gesture) and the deformer's update;
//   BM_PlaybackFrame:   the same plus the view's data (SceneView::refresh: points, normals), no GL
//                       draw (the renderer has no window).
// Run: bench_animation --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// Each checks once that the frame did what it should (the widget at the keyed curve's value, the
// deformer and the view updated, nothing re-embedded) and aborts otherwise.
#include <cmath>
#include <memory>

#include <benchmark/benchmark.h>
#include <vtkNew.h>
#include <vtkRenderer.h>

#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/render/scene_view.h"
#include "ffdkit/interaction/timeline.h"
#include "sphere_session.h"

using namespace ffdkit;

namespace {

void require(bool ok, const char* what) { bench::require(ok, "bench_animation", what); }

struct Session {
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  app::InteractionController controller{scene, deformer, commands};
  app::Timeline timeline{scene, commands, controller};
  vtkNew<vtkRenderer> renderer;
  std::unique_ptr<app::SceneView> view;
  widgets::WidgetId widget;

  explicit Session(int resolution) {
    widget = bench::addSphereInCubicLattice(controller, resolution).widget;
    scene.setFrameRange(scene.animation().firstFrame, 48);
    for (const auto& [frame, value] : {std::pair{0, 0.0}, {24, 0.3}, {48, 0.0}}) {
      scenes::Keyframe key;
      key.time = scenes::frameTime(scene.animation(), frame);
      key.variation = value;
      scenes::setKey(scene, widget, scenes::ChannelKind::Variation, key);
    }
    timeline.setFrame(0);
    timeline.setPlaying(true);
  }
  void withView() {
    if (view) return;
    view = std::make_unique<app::SceneView>(renderer);
    view->show(scene, deformer);
    controller.onChanged = [this] { view->refresh(scene, deformer); };
  }
};

Session& session(int resolution) {
  static std::unique_ptr<Session> s;
  if (!s) s = std::make_unique<Session>(resolution);
  return *s;
}

// One frame: the clock moves on by one frame period. The keyed value changes every frame except at
// the peak; a frame whose value did not change costs nothing, so skip those few.
void playFrames(benchmark::State& state, Session& s) {
  const double period = 1.0 / s.scene.animation().framesPerSecond;
  const std::uint64_t before = s.deformer.revision(s.scene.objects().front().name);
  std::int64_t frames = 0;
  for (auto _ : state) {
    require(s.timeline.advance(period), "the clock did not reach the next frame");
    ++frames;
  }
  const double seconds = scenes::frameTime(s.scene.animation(), s.timeline.frame());
  const double expected = scenes::evaluateVariation(s.scene.animation().channels.front().keys, seconds);
  require(std::abs(s.scene.widgets.variation(s.widget) - expected) < 1e-12, "the widget is not at the keyed value");
  require(s.deformer.revision(s.scene.objects().front().name) > before, "the deformer did not follow");
  require(s.deformer.lastStats().reembeddedStages == 0, "a frame re-embedded");
  state.counters["points"] = double(s.scene.objects().front().mesh.points.rows());
  state.counters["frames"] = double(frames);
}

void BM_AnimationFrame(benchmark::State& state) {
  Session& s = session(static_cast<int>(state.range(0)));
  require(!s.view, "BM_AnimationFrame runs before the view exists");
  playFrames(state, s);
}

void BM_PlaybackFrame(benchmark::State& state) {
  Session& s = session(static_cast<int>(state.range(0)));
  s.withView();
  const int updates = s.view->stats().pointUpdates;
  playFrames(state, s);
  // Every frame but the loop's seam (frame 48 -> 0, both at 0) moves the points.
  require(s.view->stats().pointUpdates >= updates + int(state.iterations()) - int(state.iterations()) / 48 - 1,
          "the view did not follow");
}

}  // namespace

// Sphere resolution 1414: ~1M vertices.
BENCHMARK(BM_AnimationFrame)->Name("BM_AnimationFrame/points:1M/lattice:4x4x4-cubic")->Arg(1414)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PlaybackFrame)->Name("BM_PlaybackFrame/points:1M/lattice:4x4x4-cubic")->Arg(1414)->Unit(benchmark::kMillisecond)->UseRealTime();
