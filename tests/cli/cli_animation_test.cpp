// End-to-end tests of ffdkit-cli's animation options: deform --frame (core, no display).
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/mesh_io.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::cli::test {
namespace {

namespace fs = std::filesystem;
const fs::path kDefault = fs::path(FFDKIT_SOURCE_DIR) / "scenes" / "examples" / "default";

TEST(CliAnimation, DeformAtAFrameWritesTheAnimatedPoints) {
  TempDir dir;
  const fs::path out = dir / "mesh.vtp";
  const CliResult r = runCli({"deform", kDefault.string(), "--frame", "36", "-o", out.string()});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  scenes::Scene scene = scenes::readScene(kDefault);
  const Eigen::MatrixX3d unanimated = scenes::deformScene(scene).at("sphere");
  scenes::applyAnimationFrame(scene, 36);
  // Frame 36 lies between the keys 0.5 (frame 24) and -0.2 (frame 48), both local extrema: flat
  // slopes, so the Hermite midpoint is their mean.
  EXPECT_NEAR(scene.widgets.variation(scene.widgets.find("pull")), 0.15, 1e-12);
  const Eigen::MatrixX3d expected = scenes::deformScene(scene).at("sphere");
  const Eigen::MatrixX3d written = scenes::readMesh(out).points;
  EXPECT_LT(maxDifference(written, expected), 1e-12);
  // The frame mattered: the file stores frame 0 (no pull); the pull of 0.15 moves the sphere's top
  // by 0.15 times the top point's Bernstein weight there, (1/2)^2 w^2 with w ~ 0.93: ~0.032.
  EXPECT_GT(maxDifference(written, unanimated), 0.02);

  // --scene SCENE is the same.
  const CliResult s = runCli({"deform", "--scene", kDefault.string(), "--frame", "36", "-o", (dir / "again.vtp").string()});
  ASSERT_EQ(s.exitCode, 0) << describe(s);
  EXPECT_EQ(scenes::readMesh(dir / "again.vtp").points, written);
}

TEST(CliAnimation, FramesOutsideTheRangeAndFramesOfAToolAreRefused) {
  TempDir dir;
  const CliResult outside = runCli({"deform", kDefault.string(), "--frame", "73", "-o", (dir / "m.ply").string()});
  EXPECT_EQ(outside.exitCode, 2) << describe(outside);
  EXPECT_NE(outside.err.find("--frame 73 is outside the scene's frame range 0..72"), std::string::npos) << outside.err;
  const CliResult word = runCli({"deform", kDefault.string(), "--frame", "soon", "-o", (dir / "m.ply").string()});
  EXPECT_EQ(word.exitCode, 2) << describe(word);
  const CliResult tool = runCli({"deform", "-w", (fs::path(FFDKIT_SOURCE_DIR) / "widgets/examples/fig6-8.json").string(),
                                 (dir / "in.obj").string(), "--frame", "1", "-o", (dir / "m.ply").string()});
  EXPECT_EQ(tool.exitCode, 2) << describe(tool);
  EXPECT_NE(tool.err.find("a widget file has no animation"), std::string::npos) << tool.err;
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace ffdkit::cli::test
