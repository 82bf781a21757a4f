// A drag step of a translate widget's glyph through InteractionController at 1M vertices (a
// sphere in a 4x4x4 cubic lattice, the widget on one inner control point of the top layer), with
// the shape guard off, with Keep Volume, with Keep Centre and with both. The step is the
// gesture's model step, the guard's correction of the 63 control points the drag leaves free
// (ShapeGuard::correct: ffd::ShapeConstraints, the volume by its precomputed polynomial, the
// centroid of the closed surface by passes over the vertices and triangles per Newton step) and
// the deformer's evaluation (the gesture's delta step over every vertex). Readers:
//   reads:none   the controller's step, its evaluation included;
//   reads:points and a read of the deformed points (SceneDeformer::points, a pure read: about
//                the cost of reads:none);
//   reads:view   and the view's point and normal arrays (SceneView::refresh, level of detail off,
//                no GL draw), as the window's frame does.
// Each run checks its result on the evaluated mesh: the volume within 1e-12 of the kept one (Keep
// Volume), the centroid within 1e-12 of the sphere's size of the kept one (Keep Centre), and
// without a guard that the drag changed the volume. Run:
//   OMP_WAIT_POLICY=passive bench_guarded_drag --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <vtkNew.h>
#include <vtkRenderer.h>

#include <cmath>
#include <memory>

#include "ffdkit/ffd/closed_surface.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/render/scene_view.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "viewed_sphere.h"

namespace {

using namespace ffdkit;

void require(bool ok, const char* what) { bench::require(ok, "bench_guarded_drag", what); }

enum class Reader { None, Points, View };

// The sphere, its lattice, widget and view, made once for every benchmark of the run (a keep's
// precompute is made again only when a benchmark keeps something else); the whole mesh follows
// every step (level of detail off).
struct Session : bench::ViewedSphere {
  std::unique_ptr<ffd::ClosedSurface> surface;
  double volume = 0.0;                                 // at rest
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // at rest

  explicit Session(int resolution) : ViewedSphere(resolution, app::LevelOfDetail{.enabled = false}) {
    const scenes::MeshData& mesh = scene.objects().front().mesh;
    surface = std::make_unique<ffd::ClosedSurface>(ffd::TriangleMatrix(mesh.triangles), mesh.points.rows());
    volume = ffd::enclosedVolume(deformer.points(sphere), *surface);
    centroid = ffd::enclosedCentroid(deformer.points(sphere), *surface);
  }
};

Session& session(int resolution) {
  static std::unique_ptr<Session> s;
  if (!s) s = std::make_unique<Session>(resolution);
  return *s;
}

void BM_GuardedDragStep(benchmark::State& state, app::ShapeKeep keep, Reader reader) {
  Session& s = session(static_cast<int>(state.range(0)));
  // The keep is taken at rest (every run ends with its drag undone).
  if (!(s.controller.shapeGuard().keep(s.sphere) == keep)) s.controller.setKeep(s.sphere, keep);
  if (reader == Reader::View)
    s.controller.onChanged = [&s] {
      s.view->setHighlights(s.controller.highlights());
      s.view->refresh(s.scene, s.deformer);
    };
  const widgets::Ray grab = s.ray(0.5);
  require(s.controller.press(grab, s.tolerance()) == app::InteractionController::PressResult::Widget,
          "the press missed the widget");
  const Eigen::Vector3d axis = s.scene.widgets.affineFrame(s.widget).frame.linear().col(0);
  const double size = s.scene.widgets.affineFrame(s.widget).size;
  // Along the arrow: the widget moves by 0.01 .. 0.1 of its size, back and forth.
  int step = 0;
  const auto next = [&] {
    widgets::Ray r = grab;
    r.origin += (0.01 * (1 + step++ % 10)) * size * axis;
    return r;
  };
  // The gesture's first step (its setup) untimed.
  s.controller.drag(next());
  if (reader == Reader::Points) benchmark::DoNotOptimize(s.deformer.points(s.sphere).data());
  const int viewUpdates = s.view->stats().pointUpdates;
  for (auto _ : state) {
    s.controller.drag(next());
    if (reader == Reader::Points) benchmark::DoNotOptimize(s.deformer.points(s.sphere).data());
  }
  if (reader == Reader::View)
    require(s.view->stats().pointUpdates >= viewUpdates + int(state.iterations()), "the view did not follow the drag");

  const Eigen::MatrixX3d& points = s.deformer.points(s.sphere);
  const double volume = ffd::enclosedVolume(points, *s.surface);
  const Eigen::Vector3d centroid = ffd::enclosedCentroid(points, *s.surface);
  for (const app::ShapeGuardStep& guarded : s.controller.guardSteps())
    require(guarded.problem.empty(), "the guard did not correct the step");
  if (keep.any()) require(!s.controller.guardSteps().empty(), "no guard step was reported");
  if (keep.volume)
    require(std::abs(volume - s.volume) <= 1e-12 * std::abs(s.volume), "the volume was not kept to 1e-12");
  if (keep.centre) {
    const double extent = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
    require((centroid - s.centroid).norm() <= 1e-12 * extent, "the centroid was not kept to 1e-12 of the size");
  }
  if (!keep.any()) require(std::abs(volume - s.volume) > 1e-6 * std::abs(s.volume), "the drag did not change the volume");
  state.counters["points"] = static_cast<double>(points.rows());
  if (keep.any()) state.counters["newtonSteps"] = s.controller.guardSteps().front().iterations;
  s.controller.release();
  s.commands.undo();
  s.controller.onChanged = nullptr;
}

// Registers the step with `keep` for every reader.
void registerGuard(const char* guard, app::ShapeKeep keep) {
  const std::pair<const char*, Reader> readers[] = {{"none", Reader::None}, {"points", Reader::Points}, {"view", Reader::View}};
  for (const auto& [name, reader] : readers) {
    const Reader r = reader;
    benchmark::RegisterBenchmark(
        (std::string("BM_GuardedDragStep/guard:") + guard + "/reads:" + name + "/points:1M/lattice:4x4x4-cubic").c_str(),
        [keep, r](benchmark::State& state) { BM_GuardedDragStep(state, keep, r); })
        ->Arg(1414)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
}

}  // namespace

int main(int argc, char** argv) {
  registerGuard("off", {});
  registerGuard("keep-volume", {.volume = true});
  registerGuard("keep-centre", {.centre = true});
  registerGuard("keep-volume-and-centre", {.volume = true, .centre = true});
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
