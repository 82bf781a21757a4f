#pragma once

#include <filesystem>
#include <string>

#include "ffdkit/scenes/generator.h"

namespace ffdkit::app {

struct CurvePlotOptions {
  int width = 900;    ///< pixels, 1..16384
  int height = 520;   ///< pixels, 1..16384
  std::string title;  ///< shown above the chart; "" -> none
};

/// Plots curvature (and torsion, when the profile has it) against arc length with VTK's charts
/// (vtkChartXY in a vtkContextView rendered off screen; needs an X display or Xvfb) and writes
/// a PNG atomically. Curvature is drawn in orange, torsion in blue; x is arc length, y is
/// 1/length (the curve's length units).
/// @param profile arcLength, curvature: #samples each (>= 2), finite, arc length ascending;
///        torsion: #samples or empty.
/// @throws std::invalid_argument for a malformed profile or size; std::runtime_error if
///         rendering or writing fails (nothing is written then).
void plotCurvatureToPng(const scenes::CurvatureProfile& profile, const std::filesystem::path& png,
                        const CurvePlotOptions& options = {});

}  // namespace ffdkit::app
