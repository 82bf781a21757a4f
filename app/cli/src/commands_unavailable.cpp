// ffdkit-cli render and plot in a build without VTK (FFDKIT_WITH_VTK=OFF): both draw through
// VTK's off-screen rendering (ffdkit::render), so here they only say why they cannot run.
#include <stdexcept>

#include "commands.h"

namespace ffdkit::cli {

namespace {

Command unavailable(const std::string& name, const std::string& what) {
  return {name,
          what + " (not in this build: it needs VTK)",
          "ffdkit-cli " + name + " ...   (unavailable: this ffdkit-cli was built without VTK)",
          "This ffdkit-cli was built with FFDKIT_WITH_VTK=OFF; '" + name +
              "' draws through VTK. Rebuild ffdkit with VTK 9.1 or newer installed.\n",
          {},
          [](const Args&) -> int {
            throw std::runtime_error("this ffdkit-cli was built without VTK (FFDKIT_WITH_VTK=OFF), which this command needs");
          }};
}

}  // namespace

Command renderCommand() { return unavailable("render", "render a scene to PNG off screen"); }
Command plotCommand() { return unavailable("plot", "plot curvature (and torsion) against arc length of a generated curve to PNG"); }

}  // namespace ffdkit::cli
