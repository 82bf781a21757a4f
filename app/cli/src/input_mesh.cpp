#include "input_mesh.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

namespace ffdkit::cli {

namespace {

// scenes' .xyz reader takes a line whose first field does not parse (e.g. "1e999", "nan")
// for a comment and drops it; a point cloud must not lose points silently.
void checkXyzLines(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const char* cursor = line.c_str();
    bool ok = true;
    for (int k = 0; k < 3 && ok; ++k) {
      char* end = nullptr;
      const double value = std::strtod(cursor, &end);
      ok = end != cursor && std::isfinite(value);
      cursor = end;
    }
    ok = ok && std::string(cursor).find_first_not_of(" \t\r") == std::string::npos;
    if (!ok)
      throw scenes::MeshIoError(path.string() + ":" + std::to_string(number) +
                                ": expected three finite numbers \"x y z\", got '" + line + "'");
  }
}

}  // namespace

scenes::MeshData readInputMesh(const std::filesystem::path& path) {
  scenes::MeshData mesh = scenes::readMesh(path);
  std::string ext = path.extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext == ".xyz") checkXyzLines(path);
  return mesh;
}

}  // namespace ffdkit::cli
