#pragma once
// Test support shared by the meshio tests that write files: a scratch folder per test, and the
// message of a MeshIoError.

#include <filesystem>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "ffdkit/meshio/mesh_io.h"

namespace ffdkit::meshio::testing {

/// The error message of `action`, or "" when it does not throw a MeshIoError.
template <class Action>
std::string meshIoErrorOf(Action action) {
  try {
    action();
  } catch (const MeshIoError& e) {
    return e.what();
  }
  return "";
}

/// A fixture with an empty folder of its own per test (temp/ffdkit-<kind>-<pid>-<test name>),
/// removed afterwards.
class ScratchFolderTest : public ::testing::Test {
 protected:
  explicit ScratchFolderTest(std::string kind) : kind_(std::move(kind)) {}
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("ffdkit-" + kind_ + "-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path dir_;  ///< the test's folder

 private:
  std::string kind_;
};

}  // namespace ffdkit::meshio::testing
