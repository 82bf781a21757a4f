// ffdkit-cli's read options end to end: --max-points and --max-memory refuse a read over them
// with a message naming the file and the limit (exit 1, nothing written) and a raised limit reads
// the same file; --allow-outside (and its older name --allow-outside-meshes) opens what a file
// names outside its folder, which is refused by default without quoting the other file; a
// malformed value is a usage error (exit 2) on every command that reads.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.h"

namespace ffdkit::cli::test {
namespace {

namespace fs = std::filesystem;

const fs::path kTool = FFDKIT_SOURCE_DIR "/widgets/examples/fig6-8.json";

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// An .xyz file of `count` points inside the unit box (where the example tool's lattices lie).
void writeCloud(const fs::path& path, int count) {
  std::ofstream out(path);
  for (int i = 0; i < count; ++i) out << 0.1 + 0.8 * (i % 10) / 9.0 << ' ' << 0.1 + 0.8 * (i / 10 % 10) / 9.0 << ' ' << 0.5 << '\n';
}

/// A scene file whose one object is the mesh file `mesh` (as the scene names it).
void writeMeshScene(const fs::path& path, const std::string& mesh) {
  std::ofstream(path) << R"({"format": "ffdkit-scene", "version": 1, "objects": [{"name": "cloud", "mesh": {"path": ")"
                      << mesh << R"("}}]})";
}

TEST(CliReadLimits, AMeshOverMaxPointsIsRefusedNamingTheFileAndTheLimitAndARaisedLimitReadsIt) {
  TempDir dir;
  writeCloud(dir / "cloud.xyz", 1000);
  const std::string cloud = (dir / "cloud.xyz").string();
  const std::string out = (dir / "out.xyz").string();
  const std::vector<std::vector<std::string>> reads = {
      {"info", cloud},
      {"validate", cloud},
      {"deform", "--widgets", kTool.string(), cloud, "-o", out},
  };
  for (std::vector<std::string> args : reads) {
    SCOPED_TRACE(args[0]);
    std::vector<std::string> limited = args;
    limited.insert(limited.begin() + 1, {"--max-points", "500"});
    const CliResult refused = runCli(limited);
    EXPECT_EQ(refused.exitCode, 1) << describe(refused);
    EXPECT_TRUE(contains(refused.err, "cloud.xyz")) << describe(refused);
    EXPECT_TRUE(contains(refused.err, "limit of 500 points (--max-points)")) << describe(refused);
    EXPECT_FALSE(fs::exists(out));

    std::vector<std::string> raised = args;
    raised.insert(raised.begin() + 1, "--max-points=1k");
    const CliResult read = runCli(raised);
    EXPECT_EQ(read.exitCode, 0) << describe(read);
  }
  EXPECT_TRUE(contains(runCli({"info", "--max-points", "1000", cloud}).out, "1000 points"));
  EXPECT_TRUE(fs::exists(out));
}

TEST(CliReadLimits, AScenesMeshesCountAgainstItsLimit) {
  TempDir dir;
  writeCloud(dir / "cloud.xyz", 1000);
  writeMeshScene(dir / "scene.json", "cloud.xyz");
  const std::string scene = (dir / "scene.json").string();
  for (const std::string command : {"info", "validate"}) {
    SCOPED_TRACE(command);
    const CliResult refused = runCli({command, "--max-points", "999", scene});
    EXPECT_EQ(refused.exitCode, 1) << describe(refused);
    EXPECT_TRUE(contains(refused.err, "scene.json")) << describe(refused);
    EXPECT_TRUE(contains(refused.err, "limit of 999 points (--max-points)")) << describe(refused);
    EXPECT_EQ(runCli({command, "--max-points", "1000", scene}).exitCode, 0);
  }
  const CliResult deform = runCli({"deform", "--max-points", "999", "--scene", scene, "-o", (dir / "out.xyz").string()});
  EXPECT_EQ(deform.exitCode, 1) << describe(deform);
  EXPECT_FALSE(fs::exists(dir / "out.xyz"));
}

TEST(CliReadLimits, MaxMemoryOneKibibyteRefusesAHundredPoints) {
  TempDir dir;
  writeCloud(dir / "cloud.xyz", 100);  // 100 points of 3 doubles: 2400 bytes
  const std::string cloud = (dir / "cloud.xyz").string();
  const CliResult refused = runCli({"info", "--max-memory", "1K", cloud});
  EXPECT_EQ(refused.exitCode, 1) << describe(refused);
  EXPECT_TRUE(contains(refused.err, "cloud.xyz")) << describe(refused);
  EXPECT_TRUE(contains(refused.err, "limit of 1.0 KiB (--max-memory)")) << describe(refused);
  const CliResult read = runCli({"info", "--max-memory", "1MiB", cloud});
  EXPECT_EQ(read.exitCode, 0) << describe(read);
  EXPECT_TRUE(contains(read.out, "100 points")) << describe(read);
  const CliResult deform =
      runCli({"deform", "--max-memory=1KiB", "--widgets", kTool.string(), cloud, "-o", (dir / "out.xyz").string()});
  EXPECT_EQ(deform.exitCode, 1) << describe(deform);
  EXPECT_FALSE(fs::exists(dir / "out.xyz"));
}

// plot samples a generated curve again (at --density): its points count against the limit before
// anything is sampled or drawn (so no display is needed to see the refusal).
TEST(CliReadLimits, APlotOverMaxPointsIsRefusedBeforeItSamples) {
  TempDir dir;
  const std::string scene = (kSource / "scenes" / "examples" / "qi-interpolate").string();
  const std::string png = (dir / "plot.png").string();
  const CliResult dense = runCli({"plot", scene, "--object", "qi-curve", "--density", "64", "--max-points", "1000", "-o", png});
  EXPECT_EQ(dense.exitCode, 1) << describe(dense);
  EXPECT_TRUE(contains(dense.err, "qi-interpolate: object 'qi-curve': generator 'qi-interpolate': ")) << describe(dense);
  EXPECT_TRUE(contains(dense.err, "over the read limit of 1000 points (--max-points)")) << describe(dense);
  std::ofstream(dir / "parameters.json") << R"({"points": [[0, 3, 0], [1, 2.8, 0.3], [1.8, 2.2, 0.9], [2.2, 1.3, 1.2]]})";
  const CliResult generator =
      runCli({"plot", "--generator", "qi-interpolate", (dir / "parameters.json").string(), "--max-points", "100", "-o", png});
  EXPECT_EQ(generator.exitCode, 1) << describe(generator);
  EXPECT_TRUE(contains(generator.err, "parameters.json: generator 'qi-interpolate': ")) << describe(generator);
  EXPECT_TRUE(contains(generator.err, "over the read limit of 100 points (--max-points)")) << describe(generator);
  EXPECT_FALSE(fs::exists(png));
}

// The scene in shared/ names ../tool.json; the tool holds a name that must not reach a message.
TEST(CliConfinement, ASceneWhoseWidgetFileIsOutsideIsRefusedAndAllowOutsideReadsIt) {
  TempDir dir;
  fs::create_directories(dir / "shared");
  std::string tool = readText(kTool);
  ASSERT_FALSE(tool.empty());
  std::ofstream(dir / "tool.json") << tool;
  std::ofstream(dir / "shared" / "scene.json")
      << R"({"format": "ffdkit-scene", "version": 1, "objects": [], "widgetFile": "../tool.json"})";
  const std::string scene = (dir / "shared" / "scene.json").string();
  const std::string out = (dir / "out.xyz").string();
  writeCloud(dir / "shared" / "cloud.xyz", 100);
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"info", scene}, {"validate", scene}, {"deform", "--scene", scene, (dir / "shared" / "cloud.xyz").string(), "-o", out}}) {
    SCOPED_TRACE(args[0]);
    const CliResult refused = runCli(args);
    EXPECT_EQ(refused.exitCode, 1) << describe(refused);
    EXPECT_TRUE(contains(refused.err, "'../tool.json' is outside the")) << describe(refused);
    EXPECT_TRUE(contains(refused.err, "scene.json")) << describe(refused);
    EXPECT_TRUE(contains(refused.err, "--allow-outside")) << describe(refused);
    EXPECT_FALSE(contains(refused.err, "ffdkit-widgets")) << "quotes the other file:\n" << describe(refused);
    EXPECT_FALSE(fs::exists(out));
    for (const std::string option : {"--allow-outside", "--allow-outside-meshes"}) {
      std::vector<std::string> allowed = args;
      allowed.insert(allowed.begin() + 1, option);
      const CliResult read = runCli(allowed);
      EXPECT_EQ(read.exitCode, 0) << option << "\n" << describe(read);
    }
  }
  EXPECT_TRUE(fs::exists(out));
}

// A file that is not the other file's format: the refusal says where it is named, never what it holds.
TEST(CliConfinement, TheRefusalNeverQuotesTheOtherFile) {
  TempDir dir;
  fs::create_directories(dir / "shared");
  std::ofstream(dir / "secret.txt") << "password=hunter2\n";
  std::ofstream(dir / "shared" / "scene.json")
      << R"({"format": "ffdkit-scene", "version": 1, "objects": [], "widgetFile": "../secret.txt"})";
  writeMeshScene(dir / "shared" / "mesh-scene.json", "../secret.txt");
  for (const char* scene : {"scene.json", "mesh-scene.json"}) {
    SCOPED_TRACE(scene);
    const CliResult refused = runCli({"validate", (dir / "shared" / scene).string()});
    EXPECT_EQ(refused.exitCode, 1) << describe(refused);
    EXPECT_TRUE(contains(refused.err, "'../secret.txt' is outside the")) << describe(refused);
    EXPECT_FALSE(contains(refused.err, "hunter2")) << describe(refused);
  }
}

// A glTF's external buffer is a path the file names: the same rule.
TEST(CliConfinement, AGltfBufferOutsideItsFolderIsRefusedAndAllowOutsideReadsIt) {
  TempDir dir;
  fs::create_directories(dir / "shared");
  fs::create_directories(dir / "buffers");
  std::string bytes;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  std::ofstream(dir / "buffers" / "triangle.bin", std::ios::binary) << bytes;
  std::ofstream(dir / "shared" / "triangle.gltf") << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "buffers": [{"byteLength": 36, "uri": "../buffers/triangle.bin"}]})";
  const std::string gltf = (dir / "shared" / "triangle.gltf").string();
  const CliResult refused = runCli({"info", gltf});
  EXPECT_EQ(refused.exitCode, 1) << describe(refused);
  EXPECT_TRUE(contains(refused.err, "triangle.gltf")) << describe(refused);
  EXPECT_TRUE(contains(refused.err, "'../buffers/triangle.bin' is outside the")) << describe(refused);
  const CliResult read = runCli({"info", "--allow-outside", gltf});
  EXPECT_EQ(read.exitCode, 0) << describe(read);
  EXPECT_TRUE(contains(read.out, "3 points")) << describe(read);
}

TEST(CliReadLimits, AMalformedLimitIsAUsageErrorOnEveryCommandThatReads) {
  TempDir dir;
  writeCloud(dir / "cloud.xyz", 10);
  writeMeshScene(dir / "scene.json", "cloud.xyz");
  const std::string scene = (dir / "scene.json").string();
  const std::string cloud = (dir / "cloud.xyz").string();
  const std::vector<std::vector<std::string>> commands = {
      {"info", cloud},
      {"validate", cloud},
      {"deform", "--widgets", kTool.string(), cloud, "-o", (dir / "out.xyz").string()},
      {"deform", "--scene", scene, "-o", (dir / "out.xyz").string()},
      {"render", scene, (dir / "out.png").string()},
      {"export", scene, "-o", (dir / "out.glb").string()},
      {"plot", scene, "--object", "cloud", "-o", (dir / "plot.png").string()},
  };
  const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
      {{"--max-memory", "4X"}, "--max-memory: '4X' is not a size in bytes (unknown unit 'X')"},
      {{"--max-memory", "-1"}, "--max-memory: '-1' is not a size in bytes"},
      {{"--max-memory", "0"}, "--max-memory: '0' is not a size in bytes (expected at least 1"},
      {{"--max-memory", "lots"}, "--max-memory: 'lots' is not a size in bytes"},
      {{"--max-points", "1.5"}, "--max-points: '1.5' is not a count (expected a whole number)"},
      {{"--max-points", "50Mi"}, "--max-points: '50Mi' is not a count (unknown unit 'Mi')"},
      {{"--max-points="}, "--max-points: '' is not a count"},
      {{"--max-points"}, "--max-points needs a value"},
  };
  for (const auto& command : commands) {
    for (const auto& [options, message] : bad) {
      std::vector<std::string> args = command;
      args.insert(args.end(), options.begin(), options.end());
      SCOPED_TRACE(args[0] + " " + options.front());
      const CliResult r = runCli(args);
      EXPECT_EQ(r.exitCode, 2) << describe(r);
      EXPECT_TRUE(contains(r.err, message)) << describe(r);
      EXPECT_TRUE(contains(r.err, "usage: ffdkit-cli " + args[0])) << describe(r);
    }
  }
  EXPECT_FALSE(fs::exists(dir / "out.xyz"));
}

TEST(CliReadLimits, EveryCommandThatReadsListsTheOptionsWithTheirDefaults) {
  for (const std::string command : {"info", "validate", "deform", "render", "export", "plot"}) {
    SCOPED_TRACE(command);
    const CliResult help = runCli({command, "--help"});
    EXPECT_EQ(help.exitCode, 0);
    EXPECT_TRUE(contains(help.out, "--max-memory SIZE")) << help.out;
    EXPECT_TRUE(contains(help.out, "default 4.0 GiB")) << help.out;
    EXPECT_TRUE(contains(help.out, "--max-points N")) << help.out;
    EXPECT_TRUE(contains(help.out, "default 50000000")) << help.out;
    EXPECT_TRUE(contains(help.out, "--allow-outside ")) << help.out;
    EXPECT_TRUE(contains(help.out, "--allow-outside-meshes")) << help.out;
    EXPECT_TRUE(contains(help.out, "older name of --allow-outside")) << help.out;
  }
}

}  // namespace
}  // namespace ffdkit::cli::test
