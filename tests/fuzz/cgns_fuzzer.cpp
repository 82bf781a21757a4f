// Fuzz target: the CGNS reader (meshio/cgns.h) on arbitrary bytes, written to a file first (the
// CGNS library, and HDF5 under it, read files only). Errors are MeshIoError (or the budget's
// ReadLimitError); anything else (a crash, a sanitizer report, another exception) is a finding,
// and so is a cell check that throws, or a file written with moved points that does not read
// back with those points (in its own precision).
//
// The reader runs the CGNS library in a child process (its default), so a crash inside the library
// is a MeshIoError too (regressions/fuzz_cgns holds such inputs). A child's coverage never reaches
// libFuzzer, so a campaign sets FFDKIT_FUZZ_CGNS_IN_PROCESS=1: the library then runs in this
// process, and libFuzzer's fork mode (-fork=1 -ignore_crashes=1) keeps going past the inputs that
// crash it; each is then kept in regressions/fuzz_cgns, where the corpus test reads it the default
// way and must get a MeshIoError.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "ffdkit/meshio/cgns.h"
#include "ffdkit/meshio/element_cells.h"
#include "ffdkit/meshio/mesh_data.h"

namespace {

namespace fs = std::filesystem;

// A folder of this process for the input and the written file, removed at exit.
struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("ffdkit-fuzz-cgns-" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() {
    std::error_code ignored;
    fs::remove_all(dir, ignored);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ffdkit::meshio;
  static const Scratch scratch;
  const fs::path in = scratch.dir / "in.cgns", out = scratch.dir / "out.cgns";
  std::ofstream(in, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  static const bool inProcess = std::getenv("FFDKIT_FUZZ_CGNS_IN_PROCESS") != nullptr;
  CgnsReadOptions options;
  options.isolate = !inProcess;
  options.maxSeconds = 20.0;
  options.limits.maxMemoryBytes = std::uint64_t(64) << 20;  // an input may ask for no more than this
  options.limits.maxPoints = 1'000'000;
  CgnsMesh mesh;
  try {
    mesh = readCgnsMesh(in, options);
  } catch (const MeshIoError&) {
    return 0;
  } catch (const ReadLimitError&) {
    return 0;
  }
  (void)checkElementCells(mesh.points, mesh.cells);
  const Eigen::MatrixX3d moved = mesh.points * 0.5;
  try {
    writeCgnsMesh(mesh, moved, out, CgnsWriteOptions{.durable = false, .isolate = !inProcess});
  } catch (const MeshIoError&) {
    // A file the library reads but will not open for modification (its own checks on open).
    return 0;
  }
  try {
    const CgnsMesh again = readCgnsMesh(out, options);
    if (again.points.rows() != moved.rows()) std::abort();
    for (int c = 0; c < mesh.physicalDimension && c < 3; ++c) {
      const Eigen::VectorXd expected =
          mesh.singlePrecision[std::size_t(c)] ? Eigen::VectorXd(moved.col(c).cast<float>().cast<double>()) : Eigen::VectorXd(moved.col(c));
      if (again.points.col(c) != expected) std::abort();
    }
  } catch (const MeshIoError&) {
    std::abort();
  }
  return 0;
}
