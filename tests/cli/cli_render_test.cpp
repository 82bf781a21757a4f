// End-to-end tests of ffdkit-cli render and plot (need an X display: CTest label render).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "ffdkit/scenes/scene_file.h"
#include "png_image.h"

namespace ffdkit::cli::test {
namespace {

namespace fs = std::filesystem;
TEST(CliRender, WritesAPngWithTheObjectsPixels) {
  TempDir dir;
  const fs::path scene = kSource / "scenes" / "examples" / "default";
  const scenes::Scene loaded = scenes::readScene(scene);
  const Eigen::Vector3i background = (loaded.background() * 255.0).array().round().cast<int>();
  for (const char* camera : {"scene", "front", "top", "side", "iso"}) {
    const fs::path png = dir / (std::string(camera) + ".png");
    const CliResult r = runCli({"render", scene.string(), png.string(), "--size", "200x150", "--camera", camera});
    ASSERT_EQ(r.exitCode, 0) << camera << describe(r);
    const PngImage image = readPng(png);
    ASSERT_EQ(image.width, 200) << camera;
    ASSERT_EQ(image.height, 150) << camera;
    EXPECT_LE((image.rgb(1, 1) - background).cwiseAbs().maxCoeff(), 2) << camera;
    // The orange object fills the middle (lattice points and edges cross it).
    int orange = 0;
    for (int y = 55; y < 95; ++y) {
      for (int x = 80; x < 120; ++x) {
        const Eigen::Vector3i c = image.rgb(x, y);
        orange += c.x() > c.z() + 60 ? 1 : 0;
      }
    }
    EXPECT_GT(orange, 40 * 40 / 2) << camera;
  }
}

TEST(CliRender, AMissingSceneFailsAndWritesNothing) {
  TempDir dir;
  const CliResult r = runCli({"render", (dir / "nothing.json").string(), (dir / "out.png").string()});
  EXPECT_EQ(r.exitCode, 1) << describe(r);
  EXPECT_NE(r.err.find("nothing.json"), std::string::npos) << r.err;
  EXPECT_TRUE(dir.entries().empty());
}

TEST(CliPlot, ANonCurveObjectOrUnknownGeneratorIsAClearError) {
  TempDir dir;
  const fs::path scene = kSource / "scenes" / "examples" / "default";
  const std::string object = scenes::readScene(scene).objects().front().name;
  const CliResult primitive = runCli({"plot", scene.string(), "--object", object, "-o", (dir / "p.png").string()});
  EXPECT_EQ(primitive.exitCode, 1) << describe(primitive);
  EXPECT_NE(primitive.err.find("not a generated curve"), std::string::npos) << primitive.err;

  const CliResult missing = runCli({"plot", scene.string(), "--object", "ghost", "-o", (dir / "p.png").string()});
  EXPECT_EQ(missing.exitCode, 1) << describe(missing);
  EXPECT_NE(missing.err.find("no object 'ghost'"), std::string::npos) << missing.err;

  std::ofstream(dir / "params.json") << "{\"points\": [[0, 0, 0], [1, 0, 0]]}\n";
  const CliResult unknown =
      runCli({"plot", "--generator", "no-such-curve", (dir / "params.json").string(), "-o", (dir / "p.png").string()});
  EXPECT_EQ(unknown.exitCode, 1) << describe(unknown);
  EXPECT_NE(unknown.err.find("no-such-curve"), std::string::npos) << unknown.err;

  std::ofstream(dir / "bad.json") << "{\n  \"points\": [1, 2,]\n}\n";
  const CliResult malformed =
      runCli({"plot", "--generator", "no-such-curve", (dir / "bad.json").string(), "-o", (dir / "p.png").string()});
  EXPECT_EQ(malformed.exitCode, 1) << describe(malformed);
  EXPECT_NE(malformed.err.find("bad.json:2:"), std::string::npos) << malformed.err;
  EXPECT_FALSE(fs::exists(dir / "p.png"));
}

TEST(CliPlot, PlotsEveryGeneratedCurveOfTheSampleScenesAndRefusesSurfaces) {
  TempDir dir;
  const auto& registry = scenes::builtinGenerators();
  int curves = 0;
  int surfaces = 0;
  for (const auto& entry : fs::directory_iterator(kSource / "scenes" / "examples")) {
    if (!entry.is_directory()) continue;
    const scenes::Scene scene = scenes::readScene(entry.path());
    for (const auto& object : scene.objects()) {
      const auto* generated = std::get_if<scenes::GeneratedSource>(&object.source);
      if (!generated) continue;
      const fs::path png = dir / (object.name + ".png");
      const CliResult r = runCli({"plot", entry.path().string(), "--object", object.name, "-o", png.string(),
                                  "--size", "300x200"});
      if (!registry.get(generated->generator).profile) {
        ++surfaces;
        EXPECT_EQ(r.exitCode, 1) << describe(r);
        EXPECT_NE(r.err.find("surface"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(png));
        continue;
      }
      ++curves;
      ASSERT_EQ(r.exitCode, 0) << entry.path() << describe(r);
      const PngImage image = readPng(png);
      EXPECT_EQ(image.width, 300);
      EXPECT_GT(countPixels(image, orange), 100) << object.name;
      const scenes::CurvatureProfile profile =
          registry.profile(generated->generator, generated->parameters, generated->density);
      const bool torsion = profile.torsion.size() != 0;
      EXPECT_EQ(r.out.find("curvature and torsion") != std::string::npos, torsion) << r.out;
      // A varying torsion is a blue line across the chart (a zero one may lie on the x axis).
      if (torsion && profile.torsion.maxCoeff() - profile.torsion.minCoeff() > 1e-3) {
        EXPECT_GT(countPixels(image, blue), 150) << object.name;
      }
    }
  }
  EXPECT_GE(curves, 1);
  EXPECT_GE(surfaces, 1);
}

TEST(CliPlot, PlotsAGeneratorWithAParameterFile) {
  TempDir dir;
  const fs::path sceneFile = kSource / "scenes" / "examples" / "g3-curve" / "scene.json";
  if (!fs::exists(sceneFile)) GTEST_SKIP() << "no g3-curve sample scene";
  const nlohmann::json scene = nlohmann::json::parse(readText(sceneFile));
  std::ofstream(dir / "g3.json") << scene["objects"][0]["generator"]["parameters"].dump(2);
  const CliResult r = runCli({"plot", "--generator", "g3-curve", (dir / "g3.json").string(), "-o",
                              (dir / "g3.png").string(), "--size", "300x200", "--title", "G3"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_GT(countPixels(readPng(dir / "g3.png"), orange), 100);
}

TEST(CliPlot, EveryRegisteredCurveGeneratorIsReachable) {
  // Curve generators plug in from the geometry topics; each must be named by `info --generators`.
  const CliResult r = runCli({"info", "--generators"});
  ASSERT_EQ(r.exitCode, 0) << describe(r);
  const auto names = scenes::builtinGenerators().names();
  if (names.empty()) {
    EXPECT_NE(r.out.find("no generators registered"), std::string::npos) << r.out;
  }
  for (const auto& name : names) EXPECT_NE(r.out.find(name + " ("), std::string::npos) << name << "\n" << r.out;
}

}  // namespace
}  // namespace ffdkit::cli::test
