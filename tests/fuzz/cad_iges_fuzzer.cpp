// Fuzz target: the IGES reader (cad::readIges) on arbitrary bytes, and a tessellation of what it
// read, as cad_step_fuzzer.cpp does for STEP. OpenCASCADE's IGES reader takes a file name only, so
// each input is written to a file of this process first (in $TMPDIR, removed at exit). Errors are
// CadError; anything else is a finding. The reader runs in a child process with a 20 s limit
// (its default), so an input that crashes OpenCASCADE is a CadError; FFDKIT_FUZZ_CAD_IN_PROCESS=1
// reads in this process instead, for a campaign that learns from the parser's coverage under
// libFuzzer's fork mode (docs/cad.md). The seed corpus is the sample parts written by writeIges.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "ffdkit/cad/cad_error.h"
#include "ffdkit/cad/cad_io.h"
#include "ffdkit/cad/tessellation.h"

namespace {

/// This process's input file, removed when the process ends normally.
struct InputFile {
  std::filesystem::path path = std::filesystem::temp_directory_path() /
                               ("ffdkit-fuzz-iges-" + std::to_string(::getpid()) + ".igs");
  ~InputFile() {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ffdkit::cad;
  static const bool inProcess = std::getenv("FFDKIT_FUZZ_CAD_IN_PROCESS") != nullptr;
  static const InputFile file;
  {
    std::ofstream out(file.path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) std::abort();  // the fuzzer's own file: a full disk is not a finding of the reader
  }
  CadReadOptions options;
  options.maxSeconds = 20.0;
  options.isolate = !inProcess;
  try {
    const CadModel model = readIges(file.path, options);
    TessellationOptions mesh;
    mesh.linearDeflection = 0.1 * std::max(1e-3, model.bounds().diagonal().norm());
    tessellate(model, mesh);
  } catch (const CadError&) {
  }
  return 0;
}
