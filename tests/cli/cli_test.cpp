// End-to-end tests of ffdkit-cli (no display): deform, info, validate, usage errors. Each test
// runs the real binary and checks its exit code, messages and files against the library.
#include <gtest/gtest.h>

#include <algorithm>

#include "cli_runner.h"
#include "../meshio/hostile_files.h"
#include "ffdkit/scenes/mesh_io.h"
#include "ffdkit/scenes/primitive.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/widget_file.h"

namespace ffdkit::cli::test {
namespace {

namespace fs = std::filesystem;
using scenes::MeshData;

/// A sphere of `resolution` inside the unit box (where the example tools' lattices lie).
MeshData sphere(int resolution = 16, bool normals = false) {
  scenes::PrimitiveOptions options;
  options.resolution = resolution;
  options.size = 0.8;
  options.placement = Eigen::Translation3d(0.5, 0.5, 0.5);
  const geometry::TriangleMesh m = scenes::makePrimitive(options);
  MeshData mesh;
  mesh.points = m.vertices;
  mesh.triangles = m.triangles;
  mesh.hasNormals = normals;
  return mesh;
}

/// What the library computes for `mesh` deformed by every root lattice of `model`.
Eigen::MatrixX3d libraryDeform(const widgets::WidgetModel& model, const MeshData& mesh) {
  scenes::Scene scene;
  scene.widgets = model;
  scenes::SceneObject object;
  object.name = "input";
  object.mesh = mesh;
  scene.addObject(object);
  for (auto root : model.roots()) scene.attach(root, "input");
  return scenes::deformScene(scene).at("input");
}

TEST(Cli, HelpListsEveryCommandAndEachCommandHasHelp) {
  const CliResult top = runCli({"--help"});
  ASSERT_EQ(top.exitCode, 0) << describe(top);
  for (const char* command : {"deform", "render", "info", "validate", "plot"}) {
    EXPECT_NE(top.out.find(command), std::string::npos) << command;
    const CliResult help = runCli({command, "--help"});
    EXPECT_EQ(help.exitCode, 0) << describe(help);
    EXPECT_NE(help.out.find(std::string("usage: ffdkit-cli ") + command), std::string::npos) << help.out;
    EXPECT_NE(help.out.find("--quiet"), std::string::npos) << help.out;
  }
}

TEST(Cli, UsageErrorsExitTwoSayWhatAndWriteNothing) {
  TempDir dir;
  const std::string tool = (kWidgetExamples / "fig6-8.json").string();
  const std::string out = (dir / "out.ply").string();
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{}, "usage: ffdkit-cli COMMAND"},
      {{"transmogrify"}, "unknown command 'transmogrify'"},
      {{"deform", "--widgets", tool, "in.ply", "-o", out, "--frobnicate"}, "unknown option '--frobnicate'"},
      {{"deform", "--widgets", tool, "in.ply", "-o"}, "--output needs a value"},
      {{"deform", "in.ply", "-o", out}, "exactly one of --widgets FILE and --scene FILE"},
      {{"deform", "--widgets", tool, "in.ply"}, "missing --output"},
      {{"deform", "--widgets", tool, "in.ply", "-o", out, "--set", "push-front"}, "--set takes NAME=VALUE"},
      {{"deform", "--widgets", tool, "in.ply", "-o", out, "--set", "push-front=abc"}, "must be a finite number"},
      {{"deform", "--widgets", tool, "in.ply", "-o", out, "--format", "docx"}, "--format must be one of"},
      {{"deform", "--widgets", tool, "in.ply", "-o", out, "--precision", "half"}, "--precision must be single or double"},
      {{"render", "scene.json", (dir / "a.png").string(), "--size", "12by4"}, "--size takes WIDTHxHEIGHT"},
      {{"render", "scene.json", (dir / "a.png").string(), "--camera", "fisheye"}, "--camera must be one of"},
      {{"render", "scene.json"}, "render takes a SCENE and an OUTPUT.png"},
      {{"validate"}, "validate takes one or more FILEs"},
      {{"plot", "scene.json", "-o", (dir / "p.png").string()}, "--object NAME"},
  };
  for (const auto& c : cases) {
    const CliResult r = runCli(c.args);
    EXPECT_EQ(r.exitCode, 2) << describe(r);
    EXPECT_NE(r.err.find(c.message), std::string::npos) << "expected '" << c.message << "' in\n" << describe(r);
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(CliDeform, EveryExampleToolDeformsAMeshAsTheLibraryDoes) {
  TempDir dir;
  const MeshData input = sphere(20);
  scenes::writeMesh(dir / "sphere.vtp", input);
  int tools = 0;
  for (const auto& entry : fs::directory_iterator(kWidgetExamples)) {
    if (entry.path().extension() != ".json") continue;
    ++tools;
    const fs::path out = dir / ("out-" + entry.path().stem().string() + ".vtp");
    const CliResult r = runCli({"deform", "--widgets", entry.path().string(), (dir / "sphere.vtp").string(), "-o",
                                out.string()});
    ASSERT_EQ(r.exitCode, 0) << entry.path() << describe(r);
    const MeshData written = scenes::readMesh(out);
    const Eigen::MatrixX3d expected = libraryDeform(scenes::readWidgetFile(entry.path()), input);
    EXPECT_LT(maxDifference(written.points, expected), 1e-12) << entry.path();
    EXPECT_EQ(written.triangles, input.triangles) << entry.path();
  }
  EXPECT_GE(tools, 4);
}

TEST(CliDeform, SetChangesTheResultExactlyAsTheModelPredicts) {
  TempDir dir;
  const MeshData input = sphere(20);
  scenes::writeMesh(dir / "sphere.vtp", input);
  const fs::path tool = kWidgetExamples / "fig6-8.json";
  const CliResult r = runCli({"deform", "-w", tool.string(), (dir / "sphere.vtp").string(), "-o",
                              (dir / "out.vtp").string(), "--set", "push-front=0.25", "--set", "turn-back=0.4"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);

  widgets::WidgetModel model = scenes::readWidgetFile(tool);
  const Eigen::MatrixX3d unset = libraryDeform(model, input);
  model.setVariation(model.find("push-front"), 0.25);
  model.setVariation(model.find("turn-back"), 0.4);
  const Eigen::MatrixX3d expected = libraryDeform(model, input);
  const Eigen::MatrixX3d written = scenes::readMesh(dir / "out.vtp").points;
  EXPECT_LT(maxDifference(written, expected), 1e-12);
  EXPECT_GT(maxDifference(written, unset), 0.05);  // the settings really moved the surface
}

// --precision single: float32 displacements, within the engine's bound (1e-6 of the largest
// control-point move; the points' largest move stands in for it, which it cannot exceed) of the
// library's double result, and not equal to it.
TEST(CliDeform, SinglePrecisionStaysWithinItsBoundOfTheDoubleResult) {
  TempDir dir;
  const MeshData input = sphere(40);
  scenes::writeMesh(dir / "sphere.vtp", input);
  const fs::path tool = kWidgetExamples / "fig6-8.json";
  const CliResult r = runCli({"deform", "-w", tool.string(), (dir / "sphere.vtp").string(), "-o",
                              (dir / "out.vtp").string(), "--set", "push-front=0.25", "--precision", "single"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  widgets::WidgetModel model = scenes::readWidgetFile(tool);
  model.setVariation(model.find("push-front"), 0.25);
  const Eigen::MatrixX3d expected = libraryDeform(model, input);
  const double largestMove = maxDifference(expected, input.points);
  ASSERT_GT(largestMove, 0.05);
  const double error = maxDifference(scenes::readMesh(dir / "out.vtp").points, expected);
  EXPECT_GT(error, 0.0);
  EXPECT_LT(error, 1e-6 * largestMove);
}

TEST(CliDeform, UnknownSetNameFailsNamingTheAffineWidgetsAndWritesNothing) {
  TempDir dir;
  scenes::writeMesh(dir / "sphere.vtp", sphere(8));
  const CliResult r = runCli({"deform", "-w", (kWidgetExamples / "fig6-8.json").string(),
                              (dir / "sphere.vtp").string(), "-o", (dir / "out.vtp").string(), "--set", "push-up=1"});
  EXPECT_EQ(r.exitCode, 1) << describe(r);
  EXPECT_NE(r.err.find("unknown widget 'push-up'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("push-front"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.vtp"));
}

TEST(CliDeform, PointFileInPointFileOut) {
  TempDir dir;
  MeshData cloud;
  cloud.points = (Eigen::MatrixX3d::Random(500, 3).array() * 0.45 + 0.5).matrix();
  scenes::writeMesh(dir / "cloud.xyz", cloud);
  const fs::path tool = kWidgetExamples / "fig6-8.json";
  const CliResult r = runCli({"deform", "-w", tool.string(), (dir / "cloud.xyz").string(), "-o",
                              (dir / "moved.xyz").string(), "--set", "pull-front=0.3"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  widgets::WidgetModel model = scenes::readWidgetFile(tool);
  model.setVariation(model.find("pull-front"), 0.3);
  const MeshData written = scenes::readMesh(dir / "moved.xyz");
  EXPECT_EQ(written.triangles.rows(), 0);
  EXPECT_LT(maxDifference(written.points, libraryDeform(model, cloud)), 1e-12);
}

TEST(CliDeform, FitMovesTheToolOntoAFarAwayInput) {
  TempDir dir;
  MeshData far = sphere(12);
  far.points = (far.points * 10.0).rowwise() + Eigen::RowVector3d(100.0, -50.0, 7.0);
  scenes::writeMesh(dir / "far.ply", far);
  const std::string tool = (kWidgetExamples / "fig6-8.json").string();
  // Without --fit the lattice stays in the unit box: every point is outside and kept.
  const CliResult kept = runCli({"deform", "-w", tool, (dir / "far.ply").string(), "-o", (dir / "kept.ply").string(),
                                 "--set", "push-front=0.5"});
  ASSERT_EQ(kept.exitCode, 0) << describe(kept);
  EXPECT_LT(maxDifference(scenes::readMesh(dir / "kept.ply").points, far.points), 1e-4);  // PLY stores floats
  const CliResult fitted = runCli({"deform", "-w", tool, (dir / "far.ply").string(), "-o",
                                   (dir / "fitted.ply").string(), "--fit", "--set", "push-front=0.5"});
  ASSERT_EQ(fitted.exitCode, 0) << describe(fitted);
  const MeshData out = scenes::readMesh(dir / "fitted.ply");
  EXPECT_GT(maxDifference(out.points, far.points), 0.4);
  EXPECT_EQ(fitted.out.find("outside their lattice"), std::string::npos) << fitted.out;
}

TEST(CliDeform, KeepsNormalsAndConnectivity) {
  TempDir dir;
  scenes::writeMesh(dir / "smooth.vtp", sphere(12, true));
  const CliResult r = runCli({"deform", "-w", (kWidgetExamples / "fig6-2.json").string(),
                              (dir / "smooth.vtp").string(), "-o", (dir / "out.vtp").string()});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const MeshData out = scenes::readMesh(dir / "out.vtp");
  EXPECT_TRUE(out.hasNormals);
  EXPECT_EQ(out.triangles, sphere(12).triangles);
}

TEST(CliDeform, SeveralInputsGoIntoAFolderAndAScenesObjectsToo) {
  TempDir dir;
  scenes::writeMesh(dir / "a.obj", sphere(8));
  MeshData cloud;
  cloud.points = sphere(8).points;
  scenes::writeMesh(dir / "b.xyz", cloud);
  const CliResult r = runCli({"deform", "-w", (kWidgetExamples / "fig6-9.json").string(), (dir / "a.obj").string(),
                              (dir / "b.xyz").string(), "-o", (dir / "out").string(), "--quiet"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_TRUE(fs::exists(dir / "out" / "a.obj"));
  EXPECT_TRUE(fs::exists(dir / "out" / "b.xyz"));

  const fs::path press = kSource / "scenes" / "examples" / "press";
  const CliResult s = runCli({"deform", "--scene", press.string(), "-o", (dir / "press.vtp").string()});
  ASSERT_EQ(s.exitCode, 0) << describe(s);
  const scenes::Scene scene = scenes::readScene(press);
  const auto expected = scenes::deformScene(scene);
  EXPECT_LT(maxDifference(scenes::readMesh(dir / "press.vtp").points, expected.at(scene.objects().front().name)), 1e-12);
}

TEST(CliDeform, AScenesLatticesDeformInputFilesWhereTheyLie) {
  TempDir dir;
  MeshData cloud;
  cloud.points = (Eigen::MatrixX3d::Random(300, 3).array() * 0.4 + 0.5).matrix();
  scenes::writeMesh(dir / "cloud.xyz", cloud);
  const fs::path hierarchy = kSource / "scenes" / "examples" / "hierarchy";
  scenes::Scene scene = scenes::readScene(hierarchy);
  const auto affines = scene.widgets.widgets(widgets::WidgetType::Affine);
  ASSERT_FALSE(affines.empty());
  const std::string name = scene.widgets.name(affines.front());
  const CliResult r = runCli({"deform", "--scene", hierarchy.string(), (dir / "cloud.xyz").string(), "-o",
                              (dir / "out.xyz").string(), "--set", name + "=0.15"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  scene.widgets.setVariation(affines.front(), 0.15);
  const Eigen::MatrixX3d expected = libraryDeform(scene.widgets, cloud);
  const Eigen::MatrixX3d written = scenes::readMesh(dir / "out.xyz").points;
  EXPECT_LT(maxDifference(written, expected), 1e-12);
  EXPECT_GT(maxDifference(written, cloud.points), 0.01);
}

TEST(CliDeform, BrokenInputFailsAndLeavesTheExistingOutputUntouched) {
  TempDir dir;
  {
    std::ofstream(dir / "bad.xyz") << "0 0 0\n1e999 0 0\n";
    std::ofstream(dir / "out.xyz") << "precious\n";
  }
  const CliResult r = runCli({"deform", "-w", (kWidgetExamples / "fig6-8.json").string(), (dir / "bad.xyz").string(),
                              "-o", (dir / "out.xyz").string()});
  EXPECT_EQ(r.exitCode, 1) << describe(r);
  EXPECT_NE(r.err.find("bad.xyz:2"), std::string::npos) << r.err;
  EXPECT_EQ(readText(dir / "out.xyz"), "precious\n");
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"bad.xyz", "out.xyz"}));
}

TEST(CliDeform, TimingsAndProgressOnRequest) {
  TempDir dir;
  scenes::writeMesh(dir / "s.vtp", sphere(8));
  const CliResult r = runCli({"deform", "-w", (kWidgetExamples / "fig6-8.json").string(), (dir / "s.vtp").string(),
                              "-o", (dir / "o.vtp").string(), "--timings", "--progress"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  for (const char* phase : {"read ", "build scene ", "embed ", "deform ", "write ", "total "})
    EXPECT_NE(r.out.find(phase), std::string::npos) << phase << "\n" << r.out;
  EXPECT_NE(r.err.find("embedding and deforming"), std::string::npos) << r.err;
  // Not a terminal and no --progress: stderr stays clean.
  const CliResult quiet = runCli({"deform", "-w", (kWidgetExamples / "fig6-8.json").string(),
                                  (dir / "s.vtp").string(), "-o", (dir / "o.vtp").string()});
  EXPECT_TRUE(quiet.err.empty()) << quiet.err;
}

TEST(CliDeform, ShowsProgressWhenStderrIsATerminalUnlessQuiet) {
  if (!fs::exists("/usr/bin/script")) GTEST_SKIP() << "needs util-linux script(1) for a pseudo-terminal";
  TempDir dir;
  scenes::writeMesh(dir / "s.vtp", sphere(8));
  const auto onTerminal = [&](const std::string& extra) {
    std::string cli = shellQuote(ffdkit::test::ffdkitCli());
    for (const std::string& arg : {std::string("deform"), std::string("-w"), (kWidgetExamples / "fig6-8.json").string(),
                                  (dir / "s.vtp").string(), std::string("-o"), (dir / "o.vtp").string()})
      cli.append(" ").append(shellQuote(arg));
    cli.append(extra);
    std::string command = "/usr/bin/script -qec ";
    command.append(shellQuote(cli)).append(" /dev/null > ").append(shellQuote((dir / "tty.txt").string()));
    EXPECT_EQ(std::system(command.c_str()), 0);
    return readText(dir / "tty.txt");
  };
  const std::string shown = onTerminal("");
  EXPECT_NE(shown.find("embedding and deforming " + std::to_string(sphere(8).points.rows()) + " points ... "), std::string::npos)
      << shown;
  EXPECT_NE(shown.find("wrote "), std::string::npos) << shown;
  EXPECT_EQ(onTerminal(" --quiet").find_first_not_of("\r\n"), std::string::npos);
}

TEST(CliInfo, SummarisesSceneWidgetAndMeshFiles) {
  TempDir dir;
  scenes::writeMesh(dir / "s.ply", sphere(8));
  const CliResult r = runCli({"info", (kSource / "scenes" / "examples" / "press").string(),
                              (kWidgetExamples / "fig6-8.json").string(), (dir / "s.ply").string()});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_NE(r.out.find("scene: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("affine push-front: translate"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mesh: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(std::to_string(sphere(8).points.rows()) + " points"), std::string::npos) << r.out;
}

TEST(CliValidate, EverySampleSceneAndToolIsValid) {
  std::vector<std::string> args = {"validate"};
  for (const auto& e : fs::directory_iterator(kSource / "scenes" / "examples"))
    if (e.is_directory()) args.push_back(e.path().string());
  for (const auto& e : fs::directory_iterator(kWidgetExamples)) args.push_back(e.path().string());
  const CliResult r = runCli(args);
  EXPECT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), static_cast<long>(args.size() - 1)) << r.out;
}

TEST(CliValidate, ReportsEveryBrokenFileWithWhereAndWritesNothing) {
  TempDir dir;
  const auto write = [&](const std::string& name, const std::string& text) { std::ofstream(dir / name) << text; };
  const std::string pressText = readText(kSource / "scenes" / "examples" / "press" / "scene.json");
  write("malformed.json", "{\n  \"format\": \"ffdkit-scene\",\n  \"version\": 1,\n  \"objects\": [ , ]\n}\n");
  write("missing-mesh.json", R"({"format": "ffdkit-scene", "version": 1,
    "objects": [{"name": "m", "mesh": {"path": "nowhere.ply"}}]})");
  write("unknown-generator.json", R"({"format": "ffdkit-scene", "version": 1,
    "objects": [{"name": "g", "generator": {"name": "no-such-curve"}}]})");
  write("unknown-widget.json", R"({"format": "ffdkit-scene", "version": 1,
    "objects": [{"name": "p", "primitive": {"kind": "sphere"}}],
    "attachments": [{"lattice": "no-such-lattice", "objects": ["p"]}]})");
  write("nan.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  write("non-finite.json", R"({"format": "ffdkit-scene", "version": 1,
    "objects": [{"name": "n", "mesh": {"path": "nan.ply"}}]})");
  write("infinite.xyz", "0 0 0\n1e999 2 3\n");
  write("empty.xyz", "# no points\n");
  const std::string lattice = R"({"format": "ffdkit-widgets", "version": 1, "lattices": [{"id": "w0", "name": "big",
    "basis": [{"kind": "bernstein"}, {"kind": "bernstein"}, {"kind": "bernstein"}], "counts": )";
  write("huge-lattice.json", lattice + "[500, 500, 500]}]}");
  write("high-degree.json", lattice + "[60, 3, 2]}]}");
  const std::vector<std::string> before = dir.entries();

  std::vector<std::string> args = {"validate", (kSource / "scenes" / "examples" / "default").string()};
  for (const auto& name : before)
    if (name != "nan.ply") args.push_back((dir / name).string());
  const CliResult r = runCli(args);
  EXPECT_EQ(r.exitCode, 1) << describe(r);
  EXPECT_NE(r.out.find("default: ok"), std::string::npos) << r.out;
  const std::vector<std::string> expected = {
      "malformed.json:4:",                                   // line and column
      "nowhere.ply: no such file",                           // the missing mesh ...
      "missing-mesh.json",                                   // ... and the scene that names it
      "unknown generator 'no-such-curve'",
      "unknown widget name 'no-such-lattice'",
      "nan.ply:11: vertex 1 (y): non-finite number 'nan'",
      "infinite.xyz:2",
      "empty.xyz: the file has no points",
      "huge-lattice.json /lattices/0/counts: lattice 'big' asks for 500 x 500 x 500 = 125000000 control points",
      "high-degree.json /lattices/0/basis: lattice axis u: Bernstein degree must be <= 32",
      "9 of 10 files broken",
  };
  for (const auto& message : expected) EXPECT_NE(r.err.find(message), std::string::npos) << message << "\n" << r.err;
  EXPECT_EQ(dir.entries(), before);
}

TEST(CliScenePaths, AMeshOutsideTheScenesFolderNeedsAllowOutside) {
  TempDir dir;
  fs::create_directories(dir / "shared");
  std::ofstream(dir / "cloud.xyz") << "0 0 0\n1 0 0\n";
  std::ofstream(dir / "shared" / "scene.json")
      << R"({"format": "ffdkit-scene", "version": 1, "objects": [{"name": "c", "mesh": {"path": "../cloud.xyz"}}]})";
  const std::string scene = (dir / "shared" / "scene.json").string();
  for (const std::string command : {"info", "validate"}) {
    const CliResult refused = runCli({command, scene});
    EXPECT_EQ(refused.exitCode, 1) << describe(refused);
    EXPECT_NE(refused.err.find("mesh file '../cloud.xyz' is outside the"), std::string::npos) << describe(refused);
    const CliResult allowed = runCli({command, "--allow-outside", scene});
    EXPECT_EQ(allowed.exitCode, 0) << describe(allowed);
  }
  const CliResult deform = runCli({"deform", "--scene", scene, "-o", (dir / "out.xyz").string()});
  EXPECT_EQ(deform.exitCode, 1) << describe(deform);
  EXPECT_FALSE(fs::exists(dir / "out.xyz"));
}

// Issue 17's table: each bad mesh, through info, validate, deform and a scene that uses it,
// exits 1 with the reader's message (file, element) and writes nothing; none crashes.
TEST(CliHostileInput, EveryBadMeshOfTheIssueTableGetsAClearErrorAndNoOutput) {
  TempDir dir;
  const std::string tool = (kWidgetExamples / "fig6-8.json").string();
  for (const auto& file : meshio::test::hostileFiles()) {
    SCOPED_TRACE(file.name);
    std::ofstream(dir / file.name, std::ios::binary) << file.bytes;
    std::ofstream(dir / "scene.json") << R"({"format": "ffdkit-scene", "version": 1, "objects": [{"name": "m", "mesh": {"path": ")"
                                     << file.name << R"("}}]})";
    const std::string path = (dir / file.name).string();
    const std::vector<std::vector<std::string>> commands = {
        {"info", path},
        {"validate", path},
        {"deform", "--widgets", tool, path, "-o", (dir / "out.ply").string()},
        {"deform", "--scene", (dir / "scene.json").string(), "-o", (dir / "out.ply").string()},
    };
    for (const auto& args : commands) {
      const CliResult r = runCli(args);
      EXPECT_EQ(r.exitCode, 1) << args[0] << "\n" << describe(r);
      EXPECT_NE(r.err.find(file.name), std::string::npos) << describe(r);
      EXPECT_NE(r.err.find(file.expected), std::string::npos) << describe(r);
    }
    EXPECT_FALSE(fs::exists(dir / "out.ply"));
  }
}

}  // namespace
}  // namespace ffdkit::cli::test
