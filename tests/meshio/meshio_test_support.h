#pragma once

// Helpers the meshio tests share, each defined once. The test programs are unity builds (several
// test files compiled as one translation unit, tests/CMakeLists.txt), so two files of one program
// may not each define a helper of the same name in their anonymous namespaces.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace ffdkit::meshio::test_support {

/// PyGeM's own test data sets (tests/data/pygem).
inline const std::filesystem::path kPygem = std::filesystem::path(FFDKIT_SOURCE_DIR) / "tests/data/pygem";

/// The bytes of a file ("" if it cannot be read).
inline std::string fileText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace ffdkit::meshio::test_support
