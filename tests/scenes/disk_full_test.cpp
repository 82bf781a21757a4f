// A disk that is really full (ENOSPC, not a file-size limit) during the writes File > Save and
// File > Export make (scenes::writeScene, meshio::writeMesh): the write fails with an error naming
// the file and "No space left on device", the file that was there keeps its bytes, and no
// temporary is left beside it. The disk is a tmpfs of 256 KiB mounted for this test process
// alone (a mount namespace of its own: directly as root, else inside a user namespace of its
// own), filled up before the write. CTest runs each test in its own process.
#include <sched.h>
#include <sys/mount.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ffdkit/meshio/mesh_io.h"
#include "ffdkit/scenes/primitive.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::scenes {
namespace {

namespace fs = std::filesystem;

const fs::path kExamples = fs::path(FFDKIT_SOURCE_DIR) / "scenes" / "examples";

bool writeText(const char* path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  return static_cast<bool>(out.flush());
}

// Mounts a tmpfs of `bytes` at `dir`, seen by this process alone. "" when mounted, else why not.
std::string mountSmallDisk(const fs::path& dir, std::size_t bytes) {
  const auto failed = [](const std::string& step) { return step + ": " + std::strerror(errno); };
  const uid_t uid = ::getuid();
  const gid_t gid = ::getgid();
  if (::unshare(CLONE_NEWNS) != 0) {
    // Without the right to mount: a user namespace of its own, where this user is root.
    if (::unshare(CLONE_NEWUSER | CLONE_NEWNS) != 0) return failed("unshare (mount and user namespaces)");
    if (!writeText("/proc/self/setgroups", "deny") ||
        !writeText("/proc/self/uid_map", "0 " + std::to_string(uid) + " 1\n") ||
        !writeText("/proc/self/gid_map", "0 " + std::to_string(gid) + " 1\n"))
      return "cannot map this user into its user namespace";
  }
  if (::mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0) return failed("make the mounts private");
  const std::string options = "size=" + std::to_string(bytes);
  if (::mount("ffdkit-disk-full", dir.c_str(), "tmpfs", 0, options.c_str()) != 0) return failed("mount a tmpfs");
  return "";
}

// Fills the filesystem of `dir` up with one file, until a write says ENOSPC.
void fill(const fs::path& dir) {
  std::FILE* filler = std::fopen((dir / "filler").c_str(), "wb");
  ASSERT_NE(filler, nullptr);
  std::setvbuf(filler, nullptr, _IONBF, 0);
  const std::string block(4096, 'x');
  while (std::fwrite(block.data(), 1, block.size(), filler) == block.size()) {
  }
  while (std::fwrite("x", 1, 1, filler) == 1) {
  }
  EXPECT_EQ(errno, ENOSPC);
  std::fclose(filler);
}

std::string fileText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// The entries of `dir` other than the named files.
std::vector<std::string> othersIn(const fs::path& dir, const std::vector<std::string>& named) {
  std::vector<std::string> others;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (std::find(named.begin(), named.end(), name) == named.end()) others.push_back(name);
  }
  return others;
}

class DiskFull : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ffdkit-disk-full-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    const std::string why = mountSmallDisk(dir_, 256 * 1024);
    if (!why.empty()) GTEST_SKIP() << "no small filesystem can be mounted here (" << why << "): ENOSPC not tested";
    mounted_ = true;
  }
  void TearDown() override {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  fs::path dir_;
  bool mounted_ = false;
};

TEST_F(DiskFull, ASaveOntoAFullDiskFailsKeepsTheOldFileAndLeavesNoTemporary) {
  Scene scene = readScene(kExamples / "default");
  const fs::path path = dir_ / "scene.json";
  writeScene(path, scene);
  const std::string old = fileText(path);
  ASSERT_FALSE(old.empty());
  fill(dir_);
  scene.description = "edited";
  try {
    writeScene(path, scene);
    FAIL() << "a scene was written onto a full disk";
  } catch (const SceneFileError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(std::strerror(ENOSPC)), std::string::npos) << message;
  }
  EXPECT_EQ(fileText(path), old);
  EXPECT_EQ(othersIn(dir_, {"scene.json", "filler"}), std::vector<std::string>{});
}

TEST_F(DiskFull, AnExportOntoAFullDiskFailsKeepsTheOldFileAndLeavesNoTemporary) {
  const auto sphere = makePrimitive({.kind = PrimitiveKind::Sphere, .resolution = 16});
  const meshio::MeshData mesh{sphere.vertices, sphere.triangles, {}, false};
  for (const std::string name : {"sphere.ply", "sphere.obj", "sphere.npy"}) {
    SCOPED_TRACE(name);
    meshio::writeMesh(dir_ / name, mesh);
  }
  std::vector<std::string> old;
  for (const std::string name : {"sphere.ply", "sphere.obj", "sphere.npy"}) old.push_back(fileText(dir_ / name));
  fill(dir_);
  meshio::MeshData moved = mesh;
  moved.points.col(2).array() += 1.0;
  for (const std::string name : {"sphere.ply", "sphere.obj", "sphere.npy", "new.stl"}) {
    SCOPED_TRACE(name);
    try {
      meshio::writeMesh(dir_ / name, moved);
      ADD_FAILURE() << "a mesh was written onto a full disk";
    } catch (const meshio::MeshIoError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find((dir_ / name).string()), std::string::npos) << message;
      EXPECT_NE(message.find(std::strerror(ENOSPC)), std::string::npos) << message;
    }
  }
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_EQ(fileText(dir_ / std::vector<std::string>{"sphere.ply", "sphere.obj", "sphere.npy"}[i]), old[i]);
  EXPECT_EQ(othersIn(dir_, {"sphere.ply", "sphere.obj", "sphere.npy", "filler"}), std::vector<std::string>{});
}

}  // namespace
}  // namespace ffdkit::scenes
