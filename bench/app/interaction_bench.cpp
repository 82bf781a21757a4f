// The interactive path (issue 16): a drag step (model gesture, in-place deformation, the view's
// point and normal arrays; the normals followed along the motion after its first step, which
// BM_DragFirstStep times), a hover (highlights only), an undo of a drag (model and deformer:
// the document core; the view then updates as in a drag step) and of adding a widget, on a sphere of
// 1M (10M) vertices in a 4x4x4 cubic B-spline lattice with one point widget. No GL draw: the
// view's renderer has no window, and it draws every object in full (no level of detail). BM_DragStep's counter viewBytesPerVertex is the view's memory
// per vertex during the drag (SceneView::objectMemory). The CPU column is the process's (both
// cores' work, not the calling thread's alone): on a shared machine it moves less than the wall
// time, which waits for a core. Run:
//   bench_interaction --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// Each benchmark checks once that its work did what it should (the view updated the points, the
// hover built nothing, the undo embedded nothing, the first drag step updated by deltas and the
// next ones left their delta pass waiting while the view followed them) and aborts otherwise.
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

void require(bool ok, const char* what) { bench::require(ok, "bench_interaction", what); }

// The full-resolution data path: the view follows the whole mesh at every step (a level-of-
// detail proxy would draw a decimated copy during the gesture and leave the mesh's arrays). As
// MainWindow::drawFrame: one evaluation per change with the view's request (after a drag's first
// step it names the sphere as followed: the deformer's delta pass over its points waits), then a
// refresh.
struct Session : bench::ViewedSphere {
  explicit Session(int resolution) : ViewedSphere(resolution, app::LevelOfDetail{.enabled = false}) {
    controller.requestEvaluation = [this] { deformer.evaluate(scene, view->evaluationRequest(scene, deformer)); };
    refreshViewOnEveryChange();
  }
};

Session& session(int resolution) { return bench::sessionAt<Session>(resolution); }

void dragStep(benchmark::State& state, Session& s) {
  const widgets::Ray grab = s.ray(0.5);
  require(s.controller.press(grab, s.tolerance()) == app::InteractionController::PressResult::Widget,
          "the press missed the widget");
  const Eigen::Vector3d axis = s.scene.widgets.affineFrame(s.widget).frame.linear().col(0);
  // Along the arrow: the widget moves by 0.01 .. 0.1 of its size, back and forth.
  int step = 0;
  const auto next = [&] {
    widgets::Ray r = grab;
    r.origin += (0.01 * (1 + step++ % 10)) * s.scene.widgets.affineFrame(s.widget).size * axis;
    return r;
  };
  // The first step (BM_DragFirstStep's) untimed: at 10M a repetition may time a single step.
  s.controller.drag(next());
  const int before = s.view->stats().pointUpdates;
  const int followedBefore = s.view->stats().followedNormals;
  for (auto _ : state) s.controller.drag(next());
  require(s.view->stats().pointUpdates >= before + int(state.iterations()), "the view did not follow the drag");
  require(s.deformer.lastStats().reembeddedStages == 0, "a drag step re-embedded");
  // The view follows the drag without reading the deformer's points: their delta pass waits.
  require(s.deformer.lastStats().waitingObjects == 1 && s.deformer.lastStats().deltaStages == 0,
          "a drag step deformed the points the view follows");
  // Every timed step followed the normals along the motion (gesture_normals.h).
  require(s.view->stats().followedNormals >= followedBefore + int(state.iterations()),
          "the view recomputed the normals during the drag");
  // Measured before the release, while the view holds what it follows the drag with.
  state.counters["viewBytesPerVertex"] = s.view->objectMemory().bytesPerVertex();
  s.controller.release();
  state.counters["points"] = double(s.scene.objects().front().mesh.points.rows());
}

void BM_DragStep(benchmark::State& state) { dragStep(state, session(static_cast<int>(state.range(0)))); }

// The first step of a drag: the deformer's delta step, and the view's weights of the moved control
// point and W (what the next steps follow the normals with), its normals as the sums it kept from
// the undo before plus D x W, and its float points (gesture_normals.h). Press before and release
// and undo after each step are not timed.
void BM_DragFirstStep(benchmark::State& state) {
  Session& s = session(static_cast<int>(state.range(0)));
  const widgets::Ray grab = s.ray(0.5);
  const Eigen::Vector3d axis = s.scene.widgets.affineFrame(s.widget).frame.linear().col(0);
  const int followedBefore = s.view->stats().followedNormals;
  for (auto _ : state) {
    state.PauseTiming();
    require(s.controller.press(grab, s.tolerance()) == app::InteractionController::PressResult::Widget,
            "the press missed the widget");
    widgets::Ray r = grab;
    r.origin += 0.05 * s.scene.widgets.affineFrame(s.widget).size * axis;
    state.ResumeTiming();
    s.controller.drag(r);
    state.PauseTiming();
    require(s.deformer.lastStats().deltaStages == 1, "a drag step did not update by deltas");
    s.controller.release();
    s.commands.undo();
    state.ResumeTiming();
  }
  require(s.view->stats().followedNormals == followedBefore, "a first drag step followed normals it had not computed");
}

void BM_Hover(benchmark::State& state) {
  Session& s = session(static_cast<int>(state.range(0)));
  s.controller.clearSelection();  // no transformer: the pointer meets the widget or nothing
  const widgets::Ray on = s.ray(0.5), off = s.ray(0.5, 3.0);
  const app::SceneViewStats before = s.view->stats();
  bool over = false;
  for (auto _ : state) {
    over = !over;
    s.controller.hover(over ? on : off, s.tolerance());
  }
  const app::SceneViewStats after = s.view->stats();
  require(after.pointUpdates == before.pointUpdates && after.normalUpdates == before.normalUpdates &&
              after.objectBuilds == before.objectBuilds && after.widgetBuilds == before.widgetBuilds,
          "a hover built or updated geometry");
  require(s.controller.hovered().has_value() == over, "the hover did not find the widget");
}

// Undoes and redoes the last command alternately, one step per iteration (ending redone),
// requiring that no step re-embeds or builds a lattice; returns the steps taken.
std::int64_t alternateUndoRedo(benchmark::State& state, Session& s, const char* failure) {
  bool undone = false;
  std::int64_t steps = 0;
  for (auto _ : state) {
    if (undone) s.commands.redo();
    else s.commands.undo();
    undone = !undone;
    ++steps;
    require(s.deformer.lastStats().reembeddedStages == 0 && s.deformer.lastStats().latticesBuilt == 0, failure);
  }
  if (undone) {
    s.commands.redo();
    ++steps;
  }
  return steps;
}

void BM_UndoDrag(benchmark::State& state) {
  Session& s = session(static_cast<int>(state.range(0)));
  // One drag gesture to undo and redo.
  require(s.controller.press(s.ray(0.5), s.tolerance()) == app::InteractionController::PressResult::Widget,
          "the press missed the widget");
  s.controller.drag(s.ray(0.6));
  s.controller.release();
  // The document core's part: model and deformer (the view's share is BM_DragStep's).
  auto redraw = std::move(s.controller.onChanged);
  s.controller.onChanged = nullptr;
  alternateUndoRedo(state, s, "an undo or redo of a drag re-embedded or built a lattice");
  s.controller.onChanged = std::move(redraw);
  state.counters["points"] = double(s.scene.objects().front().mesh.points.rows());
}

// Undo and redo of a structural edit (adding a point widget) in a scene of 1 + 8 lattices with
// a widget each and 60 more point widgets on the first (148 widgets): the model takes the patch in place
// (WidgetModel::assignData) and the view redraws the added cell and widget only. Model, deformer
// and view.
void BM_UndoAddWidget(benchmark::State& state) {
  static std::unique_ptr<Session> made;
  if (!made) {
    made = std::make_unique<Session>(static_cast<int>(state.range(0)));
    app::InteractionController& c = made->controller;
    for (int i = 0; i < 8; ++i) {
      app::NewLatticeOptions options;
      options.counts = Eigen::Vector3i::Constant(3);
      const widgets::WidgetId lattice = c.newLattice(options);
      c.addAffineAtPoint({lattice, 13}, widgets::AffineKind::Translate);
    }
    for (Eigen::Index p = 0; p < 60; ++p) c.addAffineAtPoint({made->lattice, p}, widgets::AffineKind::Translate);
    c.addAffineAtPoint({made->lattice, 63}, widgets::AffineKind::Translate);  // the edit undone and redone
    c.clearSelection();
  }
  Session& s = *made;
  const int builtBefore = s.view->stats().widgetActorBuilds;
  const std::int64_t steps = alternateUndoRedo(state, s, "an undo or redo of adding a widget re-embedded or built a lattice");
  state.counters["widgets"] = double(s.scene.widgets.widgets().size());
  state.counters["actorsBuiltPerStep"] = double(s.view->stats().widgetActorBuilds - builtBefore) / double(steps);
}

}  // namespace

// Sphere resolution 1414: ~1M vertices; 4472: ~10M. The drag step also at 10K and 100K vertices
// (how its cost grows with the mesh).
BENCHMARK(BM_DragStep)->Name("BM_DragStep/points:10M/lattice:4x4x4-cubic")->Arg(4472)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_DragStep)->Name("BM_DragStep/points:1M/lattice:4x4x4-cubic")->Arg(1414)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_DragStep)->Name("BM_DragStep/points:100K/lattice:4x4x4-cubic")->Arg(447)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_DragStep)->Name("BM_DragStep/points:10K/lattice:4x4x4-cubic")->Arg(141)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_DragFirstStep)->Name("BM_DragFirstStep/points:1M/lattice:4x4x4-cubic")->Arg(1414)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_DragFirstStep)->Name("BM_DragFirstStep/points:10M/lattice:4x4x4-cubic")->Arg(4472)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_Hover)->Name("BM_Hover/points:1M/lattice:4x4x4-cubic")->Arg(1414)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_UndoAddWidget)->Name("BM_UndoAddWidget/points:100K/lattices:9/widgets:148")->Arg(447)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_UndoDrag)->Name("BM_UndoDrag/points:10M/lattice:4x4x4-cubic")->Arg(4472)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->Iterations(10);
