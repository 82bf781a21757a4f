// A G step in the lattice edit mode at 1M vertices (4x4x4 cubic lattice), with and without Keep
// Volume: the step's model edit, the shape guard's correction of the free control points
// (ffd::ShapeConstraints with the volume polynomial) and the deformer's evaluation. Each run
// checks that the volume of the evaluated mesh stayed within 1e-12 of the kept one.
#include <benchmark/benchmark.h>

#include <cmath>

#include "ffdkit/ffd/closed_surface.h"
#include "ffdkit/interaction/edit_controller.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "sphere_session.h"

namespace {

using namespace ffdkit;

struct Session {
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  app::InteractionController controller{scene, deformer, commands};
  app::EditController edit{scene, deformer, commands, controller};
};

// A ray looking along +y through p.
widgets::Ray alongY(const Eigen::Vector3d& p) {
  widgets::Ray r;
  r.origin = p - Eigen::Vector3d(0, 10, 0);
  r.direction = {0, 1, 0};
  return r;
}

void BM_EditStep(benchmark::State& state, bool keepVolume) {
  Session s;
  const bench::SphereWidget made = bench::addSphereInCubicLattice(s.controller, static_cast<int>(state.range(0)));
  const scenes::ObjectId sphere = s.scene.objects().front().id;
  s.edit.enter(made.lattice);
  const Eigen::Index top = 1 + 4 * (1 + 4 * 3);
  s.edit.pickMany({top}, app::SelectMode::Replace);
  if (keepVolume) s.edit.setKeep(sphere, {true, false});  // the precompute, outside the timing
  const Eigen::Vector3d pivot = s.scene.widgets.worldControlPoints(made.lattice).row(top);
  s.edit.beginModal(app::TransformMode::Move, alongY(pivot), {0, 1, 0});
  int step = 0;
  for (auto _ : state) {
    ++step;
    s.edit.update(alongY(pivot + Eigen::Vector3d(0.0, 0.0, 0.002 * (step % 50))), false);
  }
  const ffd::ClosedSurface surface(ffd::TriangleMatrix(s.scene.objects().front().mesh.triangles),
                                   s.scene.objects().front().mesh.points.rows());
  if (keepVolume) {
    const double v = ffd::enclosedVolume(s.deformer.points(sphere), surface), v0 = s.edit.shapeGuard().keptVolume(sphere);
    bench::require(std::abs(v - v0) <= 1e-12 * std::abs(v0), "bench_keep_volume", "the volume was not kept to 1e-12");
  }
  state.counters["points"] = static_cast<double>(s.scene.objects().front().mesh.points.rows());
}

}  // namespace

BENCHMARK_CAPTURE(BM_EditStep, keepVolume, true)
    ->Name("BM_EditStep/keep-volume/points:1M/lattice:4x4x4-cubic")
    ->Arg(1414)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_EditStep, plain, false)
    ->Name("BM_EditStep/plain/points:1M/lattice:4x4x4-cubic")
    ->Arg(1414)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
