// End-to-end tests of ffdkit-cli export: the real binary, its exit codes, messages and files,
// read back by ffdkit's own glTF reader and compared with the library's deformation.
#include <gtest/gtest.h>

#include "cli_runner.h"
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
  scene.widgets.setVariation(scene.widgets.find("handle"), 2.0);
  const Eigen::MatrixX3d exact = scenes::deformScene(scene).at(scene.objects.at(0).name);
  const scenes::MeshData read = scenes::readMesh(out);  // ffdkit's own (validating) glTF reader
  ASSERT_EQ(read.points.rows(), exact.rows());
  EXPECT_EQ(read.points, exact.cast<float>().cast<double>());
  EXPECT_EQ(read.triangles, scene.objects.at(0).mesh.triangles);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"press.glb"});  // no temporary left
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
           {"export", scene, "-o", out, "--frame", "x"}}) {
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
