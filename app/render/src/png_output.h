#pragma once
// Private to the render library: a rendered window as a PNG file.

#include <filesystem>

class vtkRenderWindow;

namespace ffdkit::app::detail {

/// Debian's VTK renders through X even off screen: without a display it would crash, so
/// say what is missing instead. @throws std::runtime_error naming `what` when $DISPLAY is unset.
void requireDisplay(const char* what);

/// Reads back `window`'s last frame (RGB, back buffer) and writes it as PNG, atomically.
/// @throws std::runtime_error naming `png` if there is no image or the file cannot be written.
void writeWindowPng(vtkRenderWindow* window, const std::filesystem::path& png);

}  // namespace ffdkit::app::detail
