#pragma once

#include <vector>

#include "args.h"

namespace ffdkit::cli {

/// deform's options for STEP and IGES inputs (--cad-method, --cad-degree-limit, --cad-tolerance,
/// --cad-exact-only, --cad-check) after `options`.
std::vector<OptionSpec> withCadOptions(std::vector<OptionSpec> options);

/// True when deform's INPUT is a STEP or IGES file (.step .stp .iges .igs).
bool isCadDeform(const Args& args);

/// True when deform writes a scene's CAD object as STEP or IGES: a scene (--scene or the one
/// INPUT) and -o OUTPUT.step (.stp .iges .igs), no widget file.
bool isCadSceneDeform(const Args& args);

/// ffdkit-cli deform --widgets TOOL part.step -o out.step: the tool's one lattice composed exactly
/// with the part's surfaces where it is a polynomial of low enough degree, approximated to a
/// tolerance elsewhere (or its poles moved, --cad-method poles), written as STEP or IGES
/// (docs/cad.md). Returns the exit code; throws UsageError for a wrong command line.
int runCadDeform(const Args& args);

/// ffdkit-cli deform --scene SCENE -o out.step: the scene's CAD object (the only one, or --object
/// NAME) read again from its file and deformed by the one lattice attached to it (after --frame
/// and --set), exactly as cad::deformCad does with the --cad-* options, written as STEP or IGES.
/// Returns the exit code; throws UsageError for a wrong command line.
int runCadSceneDeform(const Args& args);

}  // namespace ffdkit::cli
