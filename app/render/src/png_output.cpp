#include "png_output.h"

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>

#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include "ffdkit/meshio/atomic_write.h"

namespace ffdkit::app::detail {

void requireDisplay(const char* what) {
  const char* display = std::getenv("DISPLAY");
  if (display == nullptr || *display == '\0')
    throw std::runtime_error(std::string(what) + " needs an X display (OpenGL through X): set DISPLAY or run under xvfb-run");
}

void writeWindowPng(vtkRenderWindow* window, const std::filesystem::path& png) {
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->WriteToMemoryOn();  // encode in memory, then write the file atomically
  writer->Write();
  vtkUnsignedCharArray* bytes = writer->GetResult();
  if (bytes == nullptr || bytes->GetNumberOfValues() == 0) throw std::runtime_error(png.string() + ": rendering produced no image");
  meshio::writeFileAtomically(png, std::string_view(reinterpret_cast<const char*>(bytes->GetPointer(0)),
                                                    static_cast<std::size_t>(bytes->GetNumberOfValues())));
}

}  // namespace ffdkit::app::detail
