// Measures one drag step of the application with a large object attached (issue 6, item 4):
// the time the FFD engine spends (SceneDeformer::lastStats().seconds) against the whole step
// in our code (ray drag, deformation, VTK point update) and the frame's render, off screen.
// Not a test: run by hand, e.g.  drag_step_timing 1414  (sphere resolution; ~1M vertices);
// drag_step_timing 1414 10 zebra  draws the sphere in zebra stripes.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/render/scene_view.h"

using namespace ffdkit;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  const int resolution = argc > 1 ? std::atoi(argv[1]) : 1414;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 10;
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  app::InteractionController controller(scene, deformer, commands);
  scenes::PrimitiveOptions sphere;
  sphere.resolution = resolution;
  const std::string name = controller.addPrimitive(sphere);
  const auto lattice = controller.newLattice({});
  const auto widget = controller.addAffineAtPoint({lattice, 1 + 3 * (1 + 3 * 2)}, widgets::AffineKind::Translate);
  // The application's path for large objects: embed on a copy (a worker thread in the GUI),
  // adopt that deformer, then apply the same edit, which should find nothing left to embed.
  auto t0 = Clock::now();
  scenes::Scene copy = scene;
  app::fitAndAttachLattice(copy, lattice, name);
  scenes::SceneDeformer worker;
  worker.update(copy);
  worker.finishGesture(copy);
  const double workerSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
  controller.adoptDeformer(std::move(worker));
  t0 = Clock::now();
  controller.attachLattice(lattice, name);
  const double attachSeconds = std::chrono::duration<double>(Clock::now() - t0).count();

  if (argc > 3 && std::string(argv[3]) == "zebra") {
    scenes::DisplaySettings look = scene.findObject(name)->display;
    look.surfaceStyle = scenes::SurfaceStyle::Zebra;
    scene.setObjectDisplay(name, look);
  }

  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(true);
  window->SetSize(800, 600);
  window->AddRenderer(renderer);
  app::SceneView view(renderer);
  view.show(scene, deformer);
  window->Render();
  double refreshSeconds = 0.0;
  controller.onChanged = [&] {
    const auto start = Clock::now();
    view.refresh(scene, deformer);
    refreshSeconds += std::chrono::duration<double>(Clock::now() - start).count();
  };

  const widgets::WidgetFrame f = scene.widgets.affineFrame(widget);
  const Eigen::Vector3d x = f.frame.linear().col(0);
  auto ray = [&](double s) {
    widgets::Ray r;
    r.origin = f.frame.translation() + s * x + Eigen::Vector3d(0, -5, 0);
    r.direction = Eigen::Vector3d(0, 1, 0);
    return r;
  };
  controller.press(ray(0.5 * f.size), 0.01);
  double stepSeconds = 0.0, engineSeconds = 0.0, renderSeconds = 0.0, viewSeconds = 0.0;
  for (int i = 1; i <= steps; ++i) {
    refreshSeconds = 0.0;
    const auto start = Clock::now();
    controller.drag(ray(0.5 * f.size + 0.02 * i));
    stepSeconds += std::chrono::duration<double>(Clock::now() - start).count();
    engineSeconds += deformer.lastStats().seconds;
    viewSeconds += refreshSeconds;
    const auto renderStart = Clock::now();
    window->Render();
    renderSeconds += std::chrono::duration<double>(Clock::now() - renderStart).count();
  }
  controller.release();
  std::printf("points %ld, embedding on a copy (worker) %.3f s, attach after adopting it %.3f s\n",
              static_cast<long>(deformer.points(name).rows()), workerSeconds, attachSeconds);
  std::printf("per drag step: whole step %.2f ms = engine (SceneDeformer) %.2f ms + view update %.2f ms + rest of "
              "ours %.2f ms; render %.2f ms\n",
              1e3 * stepSeconds / steps, 1e3 * engineSeconds / steps, 1e3 * viewSeconds / steps,
              1e3 * (stepSeconds - engineSeconds - viewSeconds) / steps, 1e3 * renderSeconds / steps);
  return 0;
}
