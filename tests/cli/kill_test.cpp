// Atomic writes proven by killing: `ffdkit-cli deform` is killed with SIGKILL at random moments
// while it writes a large PLY and a large VTP (and a process saving a scene, as the app's Save
// does, likewise). After every kill the destination is either the old file or the complete
// new one, byte for byte; the next complete run leaves no temporary file behind.
#include <gtest/gtest.h>
#include <signal.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <random>
#include <thread>

#include "cli_runner.h"
#include "ffdkit/meshio/mesh_io.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::cli::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A sheet of side x side points (two triangles per square) inside fig6-8's unit box.
meshio::MeshData sheet(int side) {
  meshio::MeshData mesh;
  mesh.points.resize(Eigen::Index(side) * side, 3);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) mesh.points.row(Eigen::Index(j) * side + i) << 0.1 + 0.8 * i / side, 0.1 + 0.8 * j / side, 0.5;
  mesh.triangles.resize(2 * Eigen::Index(side - 1) * (side - 1), 3);
  Eigen::Index t = 0;
  for (int j = 0; j + 1 < side; ++j)
    for (int i = 0; i + 1 < side; ++i) {
      const int a = j * side + i;
      mesh.triangles.row(t++) << a, a + 1, a + side + 1;
      mesh.triangles.row(t++) << a, a + side + 1, a + side;
    }
  return mesh;
}

// posix_spawn, not fork: the child shares the parent's memory until it execs (a fork of this
// test program under ASan copied its page tables for each of the 52 runs, then tore them down).
pid_t spawn(const std::vector<std::string>& args) {
  std::string program = ffdkit::test::ffdkitCli();
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  argv.push_back(program.data());
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t quiet;
  ::posix_spawn_file_actions_init(&quiet);
  ::posix_spawn_file_actions_addopen(&quiet, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  ::posix_spawn_file_actions_adddup2(&quiet, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = -1;
  const int failed = ::posix_spawn(&pid, program.c_str(), &quiet, nullptr, argv.data(), environ);
  ::posix_spawn_file_actions_destroy(&quiet);
  EXPECT_EQ(failed, 0) << program;
  return pid;
}

// Whether process `pid` has a temporary file in `dir` (".<name>.tmp-<pid>-<n>"): it is writing.
bool temporaryPresent(const fs::path& dir, pid_t pid) {
  const std::string mark = ".tmp-" + std::to_string(pid) + "-";
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(mark) != std::string::npos) return true;
  return false;
}

int temporaries(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().find(".tmp-") != std::string::npos;
  return n;
}

struct KillCounts {
  int kills = 0;
  int whileWriting = 0;  ///< a temporary file existed when the kill came
  int old = 0, complete = 0;
};

// Kills `deform ... -o out` 2 * `rounds` times: half right after its temporary output appears
// plus a random delay of a few milliseconds, half at a random moment of the whole run.
KillCounts killWhileWriting(const TempDir& dir, const std::string& ext, int rounds, std::mt19937& random) {
  const fs::path out = dir / ("out" + ext);
  const std::vector<std::string> args = {"deform", "-w", (kSource / "widgets" / "examples" / "fig6-8.json").string(),
                                         (dir / "in.ply").string(), "-o", out.string(), "--set", "push-front=0.1"};
  // The complete result, and how long a run and its write take.
  auto start = Clock::now();
  pid_t pid = spawn(args);
  Clock::time_point writeStart{};
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (writeStart == Clock::time_point{} && temporaryPresent(dir.path(), pid)) writeStart = Clock::now();
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  const auto total = Clock::now() - start;
  const auto writing = writeStart == Clock::time_point{} ? total / 10 : Clock::now() - writeStart;
  const std::string complete = readText(out);
  EXPECT_GT(complete.size(), 1000000u);

  const std::string old = "the old file\n";
  KillCounts counts;
  for (int k = 0; k < 2 * rounds; ++k) {
    {
      std::ofstream(out, std::ios::binary | std::ios::trunc) << old;
    }
    pid = spawn(args);
    if (k % 2 == 0) {
      while (!temporaryPresent(dir.path(), pid) && ::waitpid(pid, &status, WNOHANG) == 0)
        std::this_thread::sleep_for(std::chrono::microseconds(100));
      // Within the write (its length varies with the machine's load: at most 5 ms into it, or a
      // fifth of the reference run's write when that is shorter).
      const auto window = std::min<Clock::duration>(writing / 5, std::chrono::milliseconds(5));
      std::this_thread::sleep_for(std::uniform_real_distribution<double>(0.0, 1.0)(random) * window);
    } else {
      std::this_thread::sleep_for(std::uniform_real_distribution<double>(0.0, 1.0)(random) * total);
    }
    counts.whileWriting += temporaryPresent(dir.path(), pid);
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    ++counts.kills;
    const std::string now = readText(out);
    EXPECT_TRUE(now == old || now == complete) << "kill " << k << ": a destination of " << now.size() << " bytes";
    counts.old += now == old;
    counts.complete += now == complete;
  }
  // The next complete run removes every temporary the killed runs left.
  spawn(args);
  ::wait(&status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(readText(out), complete);
  EXPECT_EQ(temporaries(dir.path()), 0);
  return counts;
}

TEST(CliKill, ADeformKilledWhileWritingLeavesTheOldOrTheCompleteFile) {
  TempDir dir;
  meshio::writeMesh(dir / "in.ply", sheet(500));  // 250,000 points, 498,002 triangles
  std::mt19937 random(20261125);
  for (const char* ext : {".ply", ".vtp"}) {
    SCOPED_TRACE(ext);
    const KillCounts c = killWhileWriting(dir, ext, 12, random);
    std::fflush(stdout);
    std::printf("%s: %d kills, %d while a temporary existed; destination old %d, complete %d\n", ext, c.kills, c.whileWriting,
                c.old, c.complete);
    EXPECT_GE(c.kills, 20);
    EXPECT_GE(c.whileWriting, 8);  // the kills did land while writing
  }
}

TEST(CliKill, ASceneSaveKilledLeavesTheOldOrTheCompleteFile) {
  // What the app's File > Save calls (scenes::writeScene), in a child process killed at random.
  TempDir dir;
  const fs::path path = dir / "scene.json";
  scenes::Scene scene = scenes::readScene(kSource / "scenes" / "examples" / "hierarchy");
  scene.description = std::string(4 << 20, 'x');  // a 4 MB scene: the write takes a while
  const std::string complete = scenes::sceneFileText(scene);
  std::mt19937 random(7);
  int kills = 0, seenWriting = 0;
  for (int k = 0; k < 20; ++k) {
    std::ofstream(path, std::ios::trunc) << "old";
    const pid_t pid = ::fork();
    if (pid == 0) {
      for (;;) scenes::writeScene(path, scene);
    }
    // Every other kill waits for a write to start (its temporary file), then a little more.
    if (k % 2 == 0) {
      const auto give_up = Clock::now() + std::chrono::seconds(5);
      while (!temporaryPresent(dir.path(), pid) && Clock::now() < give_up) std::this_thread::sleep_for(std::chrono::microseconds(50));
      std::this_thread::sleep_for(std::chrono::microseconds(std::uniform_int_distribution<int>(0, 3000)(random)));
    } else {
      std::this_thread::sleep_for(std::chrono::microseconds(std::uniform_int_distribution<int>(0, 400000)(random)));
    }
    seenWriting += temporaryPresent(dir.path(), pid);
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ++kills;
    const std::string now = readText(path);
    EXPECT_TRUE(now == "old" || now == complete) << "kill " << k << ": " << now.size() << " bytes";
  }
  scenes::writeScene(path, scene);
  EXPECT_EQ(temporaries(dir.path()), 0);
  std::printf("scene save: %d kills, %d while a temporary existed\n", kills, seenWriting);
  EXPECT_GE(seenWriting, 5);
}

}  // namespace
}  // namespace ffdkit::cli::test
