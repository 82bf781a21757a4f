#include "ffdkit/render/offscreen_render.h"

#include <stdexcept>

#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include "ffdkit/render/scene_view.h"
#include "png_output.h"

namespace ffdkit::app {

void renderSceneToPng(const scenes::Scene& scene, const std::filesystem::path& png,
                      const OffscreenRenderOptions& options) {
  if (options.width < 1 || options.height < 1 || options.width > 16384 || options.height > 16384) {
    throw std::invalid_argument("render size must be 1..16384 pixels per side, got " + std::to_string(options.width) +
                                "x" + std::to_string(options.height));
  }
  detail::requireDisplay("rendering");
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(true);
  window->SetSize(options.width, options.height);
  window->AddRenderer(renderer);
  SceneView view(renderer);
  scenes::SceneDeformer deformed;
  deformed.evaluate(scene);  // syncs and runs the exact pipeline in one pass
  view.show(scene, deformed);
  window->Render();

  detail::writeWindowPng(window, png);
}

}  // namespace ffdkit::app
