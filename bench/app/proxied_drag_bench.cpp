// A drag step as the window runs it with its level of detail on (View > Simplify While Moving):
// the view asks the deformer for the large sphere at its proxy's vertices only
// (SceneView::evaluationRequest, scenes::EvaluationRequest), the deformer evaluates those ~10k
// points and the view redraws the proxy; the full mesh is evaluated once, at the release
// (BM_ProxiedDragRelease). The same sphere in a 4x4x4 cubic B-spline lattice with one point
// widget as bench_interaction's BM_DragStep, at 1M and 10M vertices. No GL draw. Run:
//   bench_proxied_drag --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// Each benchmark checks that its work did what it should (the full mesh untouched during the
// steps, the proxy redrawn, the release exact) and aborts otherwise.
#include <map>
#include <memory>

#include <benchmark/benchmark.h>
#include <vtkNew.h>
#include <vtkRenderer.h>

#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/render/scene_view.h"
#include "viewed_sphere.h"

using namespace ffdkit;

namespace {

void require(bool ok, const char* what) { bench::require(ok, "bench_proxied_drag", what); }

// The view's default level of detail: on.
struct Session : bench::ViewedSphere {
  explicit Session(int resolution) : ViewedSphere(resolution, app::LevelOfDetail{}) {
    // As MainWindow::drawFrame: one evaluation per change with the view's request, then a refresh.
    controller.requestEvaluation = [this] { deformer.evaluate(scene, view->evaluationRequest(scene, deformer)); };
    refreshViewOnEveryChange();
  }
};

Session& session(int resolution) { return bench::sessionAt<Session>(resolution); }

// A step after the first: the proxy's points evaluated and drawn.
void BM_ProxiedDragStep(benchmark::State& state) {
  Session& s = session(static_cast<int>(state.range(0)));
  require(s.controller.press(s.ray(0.5), s.tolerance()) == app::InteractionController::PressResult::Widget,
          "the press missed the widget");
  int step = 0;
  const auto next = [&] { return s.ray(0.5 + 0.01 * (1 + step++ % 10)); };
  s.controller.drag(next());  // the first step untimed (BM_ProxiedDragFirstStep)
  const std::uint64_t fullBefore = s.deformer.totals().deformedPoints;
  const int drawnBefore = s.view->stats().proxyUpdates;
  for (auto _ : state) s.controller.drag(next());
  require(s.deformer.totals().deformedPoints == fullBefore, "a drag step evaluated the full mesh");
  require(s.deformer.coverage(s.sphere) == scenes::PointCoverage::Subset, "the sphere was not evaluated at its proxy");
  require(s.view->stats().proxyUpdates >= drawnBefore + int(state.iterations()), "the proxy was not redrawn");
  state.counters["proxyPoints"] = double(s.deformer.lastStats().subsetPoints);
  state.counters["points"] = double(s.deformer.pointCount(s.sphere));
  s.controller.release();
}

// The first step of a drag (press and release untimed): the subset's pipeline is kept from the
// drags before, so this step embeds nothing either.
void BM_ProxiedDragFirstStep(benchmark::State& state) {
  Session& s = session(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    state.PauseTiming();
    require(s.controller.press(s.ray(0.5), s.tolerance()) == app::InteractionController::PressResult::Widget,
            "the press missed the widget");
    state.ResumeTiming();
    s.controller.drag(s.ray(0.55));
    state.PauseTiming();
    require(s.deformer.lastStats().deformedPoints == 0, "the first step evaluated the full mesh");
    s.controller.release();
    s.commands.undo();
    state.ResumeTiming();
  }
}

// The release of a proxied drag: the full mesh evaluated exactly once and the view's full arrays
// (press and one step untimed).
void BM_ProxiedDragRelease(benchmark::State& state) {
  Session& s = session(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    state.PauseTiming();
    require(s.controller.press(s.ray(0.5), s.tolerance()) == app::InteractionController::PressResult::Widget,
            "the press missed the widget");
    s.controller.drag(s.ray(0.55));
    state.ResumeTiming();
    s.controller.release();
    state.PauseTiming();
    require(s.deformer.coverage(s.sphere) == scenes::PointCoverage::Full, "the release left the full mesh waiting");
    s.commands.undo();
    state.ResumeTiming();
  }
}

}  // namespace

BENCHMARK(BM_ProxiedDragStep)->Name("BM_ProxiedDragStep/points:10M/lattice:4x4x4-cubic")->Arg(4472)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ProxiedDragStep)->Name("BM_ProxiedDragStep/points:1M/lattice:4x4x4-cubic")->Arg(1414)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ProxiedDragFirstStep)->Name("BM_ProxiedDragFirstStep/points:10M/lattice:4x4x4-cubic")->Arg(4472)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);
BENCHMARK(BM_ProxiedDragFirstStep)->Name("BM_ProxiedDragFirstStep/points:1M/lattice:4x4x4-cubic")->Arg(1414)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(10);
BENCHMARK(BM_ProxiedDragRelease)->Name("BM_ProxiedDragRelease/points:10M/lattice:4x4x4-cubic")->Arg(4472)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_ProxiedDragRelease)->Name("BM_ProxiedDragRelease/points:1M/lattice:4x4x4-cubic")->Arg(1414)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);
