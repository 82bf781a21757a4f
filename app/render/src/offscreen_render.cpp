#include "ffdkit/app/offscreen_render.h"

#include <stdexcept>

#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include "ffdkit/app/scene_view.h"
#include "ffdkit/scenes/atomic_write.h"

namespace ffdkit::app {

void renderSceneToPng(const scenes::Scene& scene, const std::filesystem::path& png,
                      const OffscreenRenderOptions& options) {
  if (options.width < 1 || options.height < 1 || options.width > 16384 || options.height > 16384) {
    throw std::invalid_argument("render size must be 1..16384 pixels per side, got " + std::to_string(options.width) +
                                "x" + std::to_string(options.height));
  }
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(true);
  window->SetSize(options.width, options.height);
  window->AddRenderer(renderer);
  SceneView view(renderer);
  scenes::SceneDeformer deformed;
  deformed.update(scene);
  deformed.finishGesture(scene);
  view.show(scene, deformed);
  window->Render();

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->WriteToMemoryOn();
  writer->Write();
  vtkUnsignedCharArray* bytes = writer->GetResult();
  if (bytes == nullptr || bytes->GetNumberOfValues() == 0) {
    throw std::runtime_error(png.string() + ": rendering produced no image");
  }
  scenes::writeFileAtomically(
      png, std::string_view(reinterpret_cast<const char*>(bytes->GetPointer(0)),
                            static_cast<std::size_t>(bytes->GetNumberOfValues())));
}

}  // namespace ffdkit::app
