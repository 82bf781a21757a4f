// ffdkit-cli: scripted, batch use of ffdkit (docs/cli.md). Exit codes: 0 success, 1 failure,
// 2 usage error. The commands live in src/; main only maps what escapes them to an exit code.
#include <cstdio>
#include <exception>

#include "src/commands.h"
#include "src/memory_reuse.h"
#include "src/module_loader.h"

int main(int argc, char** argv) {
  ffdkit::cli::keepFreedMemoryForReuse();
  ffdkit::cli::installCadMeshReader();  // scenes naming STEP or IGES parts, with OpenCASCADE
  try {
    return ffdkit::cli::runCli(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ffdkit-cli: error: %s\n", e.what());
    return 1;
  }
}
