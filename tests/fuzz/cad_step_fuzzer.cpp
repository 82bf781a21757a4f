// Fuzz target: the STEP reader (cad::readStep from a stream) on arbitrary bytes, and a tessellation
// of what it read. Errors are CadError; anything else (a crash, a sanitizer report, another
// exception) is a finding. The reader runs in a child process (its default), so a crash inside
// OpenCASCADE's reader is a CadError too (regressions/fuzz_cad_step holds one); a 20 s limit keeps
// a slow input from stalling the run.
//
// A child's coverage never reaches libFuzzer, so a campaign that should learn from OpenCASCADE's
// parser sets FFDKIT_FUZZ_CAD_IN_PROCESS=1: the reader then runs in this process, and libFuzzer's
// fork mode (-fork=1 -ignore_crashes=1) keeps going past the inputs that crash OpenCASCADE. Each
// such input is then kept in regressions/fuzz_cad_step, where the corpus test reads it the
// default way (in a child) and must get a CadError (docs/robustness.md).
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "ffdkit/cad/cad_error.h"
#include "ffdkit/cad/cad_io.h"
#include "ffdkit/cad/tessellation.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ffdkit::cad;
  static const bool inProcess = std::getenv("FFDKIT_FUZZ_CAD_IN_PROCESS") != nullptr;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  CadReadOptions options;
  options.maxSeconds = 20.0;
  options.isolate = !inProcess;
  try {
    const CadModel model = readStep(in, "fuzz.step", options);
    TessellationOptions mesh;
    mesh.linearDeflection = 0.1 * std::max(1e-3, model.bounds().diagonal().norm());
    tessellate(model, mesh);
  } catch (const CadError&) {
  }
  return 0;
}
