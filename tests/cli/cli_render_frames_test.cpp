// End-to-end tests of ffdkit-cli render --frames (need an X display: CTest label render).
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "png_image.h"

namespace ffdkit::cli::test {
namespace {

namespace fs = std::filesystem;
const fs::path kDefault = fs::path(FFDKIT_SOURCE_DIR) / "scenes" / "examples" / "default";

TEST(CliRenderFrames, WritesOnePngPerFrameThroughThePattern) {
  TempDir dir;
  const std::string pattern = (dir / "out_%04d.png").string();
  const CliResult r = runCli({"render", kDefault.string(), "--frames", "22:24", "-o", pattern, "--size", "120x90"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"out_0022.png", "out_0023.png", "out_0024.png"}));
  // Frame 0 (the arrow at rest) and frame 24 (pulled up by 0.5) differ where the sphere's top is.
  ASSERT_EQ(runCli({"render", kDefault.string(), "--frame", "0", "-o", (dir / "rest.png").string(), "--size", "120x90"}).exitCode, 0);
  const PngImage rest = readPng(dir / "rest.png");
  const PngImage pulled = readPng(dir / "out_0024.png");
  int differing = 0;
  for (int y = 0; y < 90; ++y)
    for (int x = 0; x < 120; ++x) differing += (rest.rgb(x, y) - pulled.rgb(x, y)).cwiseAbs().maxCoeff() > 30 ? 1 : 0;
  EXPECT_GT(differing, 50);
}

TEST(CliRenderFrames, BadPatternsAndRangesAreRefusedBeforeAnythingIsWritten) {
  TempDir dir;
  const auto refused = [&](std::vector<std::string> args, const std::string& message) {
    const CliResult r = runCli(args);
    EXPECT_EQ(r.exitCode, 2) << describe(r);
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  };
  const std::string scene = kDefault.string();
  refused({"render", scene, "--frames", "0:2", "-o", (dir / "out.png").string()}, "exactly one %0Nd");
  refused({"render", scene, "--frames", "0:2", "-o", (dir / "out_%d.png").string()}, "exactly one %0Nd");
  refused({"render", scene, "--frames", "0:2", "-o", (dir / "%04d_%04d.png").string()}, "exactly one %0Nd");
  refused({"render", scene, "--frames", "0:2", "-o", (dir / "out_%04s.png").string()}, "exactly one %0Nd");
  refused({"render", scene, "--frames", "70:80", "-o", (dir / "o_%04d.png").string()}, "outside the scene's frame range 0..72");
  refused({"render", scene, "--frames", "5:2", "-o", (dir / "o_%04d.png").string()}, "the first frame is after the last");
  refused({"render", scene, "--frames", "1", "-o", (dir / "o_%04d.png").string()}, "expected A:B");
  refused({"render", scene, "--frame", "-1", "-o", (dir / "o.png").string()}, "outside the scene's frame range");
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace ffdkit::cli::test
