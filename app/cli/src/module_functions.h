#pragma once
// The commands' work that the modules hold (modules.h): what their tables point to.

#include "args.h"

namespace ffdkit::cli {

/// ffdkit-cli render (render_command.cpp, VTK module).
int runRender(const Args& args);
/// ffdkit-cli plot (plot_command.cpp, VTK module).
int runPlot(const Args& args);
/// deform with a STEP or IGES input (cad_deform.cpp, OpenCASCADE module; cad_input.h).
int deformCadInput(const Args& args);
/// deform writing a scene's CAD object as STEP or IGES (cad_deform.cpp, OpenCASCADE module).
int deformSceneCadObject(const Args& args);

}  // namespace ffdkit::cli
