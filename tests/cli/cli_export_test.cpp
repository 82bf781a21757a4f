// End-to-end tests of ffdkit-cli export: the real binary, its exit codes, messages and files,
// read back by ffdkit's own glTF reader and compared with the library's deformation.
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/mesh_io.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::cli::test {
namespace {

namespace fs = std::filesystem;

const fs::path kExamples = fs::path(FFDKIT_SOURCE_DIR) / "scenes" / "examples";

TEST(CliExport, AFrameIsTheLibrarysDeformationAsFloat32) {
  TempDir dir;
  const fs::path out = dir / "press.glb";
  const CliResult r = runCli({"export", (kExamples / "press").string(), "-o", out.string(), "--set", "handle=2"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_NE(r.out.find("wrote " + out.string() + ": frame, 1 objects"), std::string::npos) << r.out;
  scenes::Scene scene = scenes::readScene(kExamples / "press");
  // No --frame: the scene as saved, then --set on top.
  scene.widgets.setVariation(scene.widgets.find("handle"), 2.0);
  const Eigen::MatrixX3d exact = scenes::deformScene(scene).at(scene.objects().at(0).name);
  const scenes::MeshData read = scenes::readMesh(out);  // ffdkit's own (validating) glTF reader
  ASSERT_EQ(read.points.rows(), exact.rows());
  EXPECT_EQ(read.points, exact.cast<float>().cast<double>());
  EXPECT_EQ(read.triangles, scene.objects().at(0).mesh.triangles);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"press.glb"});  // no temporary left
}

TEST(CliExport, AFrameOfAKeyedSceneIsItsAnimationAtThatFrame) {
  TempDir dir;
  const fs::path out = dir / "default.glb";
  const CliResult r = runCli({"export", (kExamples / "default").string(), "-o", out.string(), "--frame", "30"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  scenes::Scene scene = scenes::readScene(kExamples / "default");
  scenes::applyAnimationFrame(scene, 30);
  const Eigen::MatrixX3d exact = scenes::deformScene(scene).at("sphere");
  EXPECT_EQ(scenes::readMesh(out).points, exact.cast<float>().cast<double>());
}

TEST(CliExport, MorphAndSkinOfTheKeyedSamplesWithTheirErrors) {
  TempDir dir;
  const fs::path out = dir / "out.glb";
  CliResult r = runCli({"export", (kExamples / "mirror").string(), "-o", out.string(), "--morph"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_NE(r.out.find("morph targets: 4 per mesh, LINEAR weights"), std::string::npos) << r.out;
  // press: one 2x2x2 lattice, whose 8 weights per vertex all fit in 8 joints.
  r = runCli({"export", (kExamples / "press").string(), "-o", out.string(), "--skin", "--joints", "8",
              "--tolerance", "1e-5"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_NE(r.out.find("skin: 9 joints (the static joint and the control points), 8 per vertex"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("largest error with k = 8: "), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(out));
}

TEST(CliExport, ASkinOverTheToleranceIsRefusedWithItsNumbersAndNothingWritten) {
  TempDir dir;
  const fs::path out = dir / "default.glb";
  const CliResult r = runCli({"export", (kExamples / "default").string(), "-o", out.string(), "--skin", "--tolerance", "1e-4"});
  EXPECT_EQ(r.exitCode, 1) << describe(r);
  EXPECT_NE(r.err.find("refused"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("with 4 joints per vertex"), std::string::npos) << r.err;
  EXPECT_TRUE(dir.entries().empty());
  // A scene without keys has no animation to export.
  const CliResult none = runCli({"export", (kExamples / "vise").string(), "-o", out.string(), "--morph"});
  EXPECT_EQ(none.exitCode, 1) << describe(none);
  EXPECT_NE(none.err.find("no animation"), std::string::npos) << none.err;
  EXPECT_TRUE(dir.entries().empty());
}

TEST(CliExport, UsageErrorsExitTwoAndWriteNothing) {
  TempDir dir;
  const std::string scene = (kExamples / "default").string();
  const std::string out = (dir / "x.glb").string();
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"export", scene},
           {"export", scene, "-o", out, "--morph", "--skin"},
           {"export", scene, "-o", out, "--joints", "4"},
           {"export", scene, "-o", out, "--skin", "--joints", "5"},
           {"export", scene, "-o", out, "--skin", "--tolerance", "-1"},
           {"export", scene, "-o", out, "--frame", "x"},
           {"export", scene, "-o", out, "--frame", "100000"}}) {
    const CliResult r = runCli(args);
    EXPECT_EQ(r.exitCode, 2) << describe(r);
    EXPECT_NE(r.err.find("usage: ffdkit-cli export"), std::string::npos) << r.err;
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(CliExport, HelpNamesTheThreeContents) {
  const CliResult r = runCli({"export", "--help"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  for (const char* word : {"--frame", "--morph", "--skin", "--joints", "--tolerance"})
    EXPECT_NE(r.out.find(word), std::string::npos) << word;
}

}  // namespace
}  // namespace ffdkit::cli::test
