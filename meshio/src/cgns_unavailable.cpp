// A build without the CGNS library (FFDKIT_WITH_CGNS=OFF): CGNS files are refused with a message
// that says so.
#include <cctype>

#include "ffdkit/meshio/cgns.h"
#include "ffdkit/meshio/mesh_data.h"

namespace ffdkit::meshio {

namespace fs = std::filesystem;

namespace {
[[noreturn]] void unavailable(const fs::path& path) {
  throw MeshIoError(path.string() + ": this build of ffdkit reads no CGNS files (built without the CGNS library: "
                    "install libcgns-dev and configure with FFDKIT_WITH_CGNS=ON)");
}
}  // namespace

bool cgnsSupported() { return false; }

bool isCgnsPath(const fs::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".cgns";
}

CgnsMesh readCgnsMesh(const fs::path& path, const CgnsReadOptions&) { unavailable(path); }

void writeCgnsMesh(const CgnsMesh&, const Eigen::MatrixX3d&, const fs::path& output, const CgnsWriteOptions&) {
  unavailable(output);
}

}  // namespace ffdkit::meshio
