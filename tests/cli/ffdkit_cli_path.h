#pragma once
// The ffdkit-cli binary that end-to-end tests run. Its path comes from the build as a path
// relative to the test program's own folder (FFDKIT_CLI_FROM_TEST, set by
// ffdkit_test_runs_cli in tests/CMakeLists.txt), not as an absolute one: the compile line is
// then the same in every build folder of a checkout, and the compiler cache serves one build
// folder's test objects to the next (scripts/test.sh builds several).
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

#ifndef FFDKIT_CLI_FROM_TEST
#error "FFDKIT_CLI_FROM_TEST is not defined: register the test program with ffdkit_test_runs_cli"
#endif

namespace ffdkit::test {

/// The absolute path of the ffdkit-cli this build made, found beside the running test program.
inline const std::string& ffdkitCli() {
  static const std::string path = [] {
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error) throw std::runtime_error("ffdkitCli: cannot read /proc/self/exe: " + error.message());
    return (self.parent_path() / FFDKIT_CLI_FROM_TEST).lexically_normal().string();
  }();
  return path;
}

}  // namespace ffdkit::test
