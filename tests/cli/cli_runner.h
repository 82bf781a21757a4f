#pragma once
// Runs the ffdkit-cli binary (the build's, found by ffdkit_cli_path.h) and captures what it did.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit_cli_path.h"

namespace ffdkit::cli::test {

struct CliResult {
  int exitCode = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

/// The source tree and its sample widget files. Each global path here and in the tests is built
/// from FFDKIT_SOURCE_DIR alone, never from another global: the order in which globals of
/// different files are initialized is not one a test may rely on.
inline const std::filesystem::path kSource = FFDKIT_SOURCE_DIR;
inline const std::filesystem::path kWidgetExamples = FFDKIT_SOURCE_DIR "/widgets/examples";

/// The largest coordinate difference of two point sets (infinity when their counts differ).
inline double maxDifference(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  if (a.rows() != b.rows()) return std::numeric_limits<double>::infinity();
  return (a - b).cwiseAbs().maxCoeff();
}

inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

inline std::string shellQuote(const std::string& arg) {
  std::string quoted = "'";
  for (char ch : arg) quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return quoted + "'";
}

/// A fresh folder under the system temp folder, removed on destruction.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "ffdkit-cli-test-XXXXXX").string();
    path_ = ::mkdtemp(pattern.data()) ? std::filesystem::path(pattern) : std::filesystem::path();
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  /// Names of the entries, sorted.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(path_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  std::filesystem::path path_;
};

/// Runs `ffdkit-cli args...` with stdout and stderr captured into files of `scratch`.
inline CliResult runCli(const std::vector<std::string>& args) {
  const std::filesystem::path scratch = std::filesystem::temp_directory_path();
  const std::string stem = "ffdkit-cli-run-" + std::to_string(::getpid());
  const auto outPath = scratch / (stem + ".out");
  const auto errPath = scratch / (stem + ".err");
  std::string command = shellQuote(ffdkit::test::ffdkitCli());
  // Appended piece by piece: GCC 12 warns (-Wrestrict, falsely) on "literal" + std::string&&.
  for (const auto& arg : args) command.append(" ").append(shellQuote(arg));
  command.append(" >").append(shellQuote(outPath.string()));
  command.append(" 2>").append(shellQuote(errPath.string()));
  command.append(" </dev/null");
  const int status = std::system(command.c_str());
  CliResult result;
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = readText(outPath);
  result.err = readText(errPath);
  std::filesystem::remove(outPath);
  std::filesystem::remove(errPath);
  return result;
}

inline std::string describe(const CliResult& r) {
  return "exit " + std::to_string(r.exitCode) + "\n--- stdout:\n" + r.out + "--- stderr:\n" + r.err;
}

}  // namespace ffdkit::cli::test
