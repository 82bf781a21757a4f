#pragma once

#include <vector>

#include "args.h"

namespace ffdkit::cli {

/// deform's options for STEP and IGES inputs (--cad-method, --cad-degree-limit, --cad-tolerance,
/// --cad-exact-only, --cad-check) after `options`.
std::vector<OptionSpec> withCadOptions(std::vector<OptionSpec> options);

/// True when deform's INPUT is a STEP or IGES file (.step .stp .iges .igs).
bool isCadDeform(const Args& args);

/// ffdkit-cli deform --widgets TOOL part.step -o out.step: the tool's one lattice composed exactly
/// with the part's surfaces where it is a polynomial of low enough degree, approximated to a
/// tolerance elsewhere (or its poles moved, --cad-method poles), written as STEP or IGES
/// (docs/cad.md). Returns the exit code; throws UsageError for a wrong command line.
int runCadDeform(const Args& args);

}  // namespace ffdkit::cli
