// ffdkit-cli deform --keep-volume / --keep-centre / --fold-check, and the fold-over line of info:
// the written mesh's volume and centroid against the test's own divergence-theorem sums.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <Eigen/Geometry>

#include "../ffd/closed_surfaces.h"
#include "cli_runner.h"
#include "ffdkit/scenes/mesh_io.h"

namespace ffdkit::cli::test {
namespace {

namespace fs = std::filesystem;
using scenes::MeshData;

const fs::path kSceneExamples = fs::path(FFDKIT_SOURCE_DIR) / "scenes" / "examples";

/// A closed UV sphere of radius 1 about the origin (rings x 2 rings quads), outward triangles.
MeshData ball(int rings = 16) {
  const ffd::testing::TestMesh sphere = ffd::testing::sphereMesh(Eigen::Vector3d::Zero(), 1.0, rings, 2 * rings);
  MeshData mesh;
  mesh.points = sphere.points;
  mesh.triangles = sphere.triangles;
  return mesh;
}

// Volume and first moment by the divergence theorem (tetrahedra from the origin).
double volumeOf(const MeshData& m, Eigen::Vector3d* centroid = nullptr) {
  double six = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (Eigen::Index t = 0; t < m.triangles.rows(); ++t) {
    const Eigen::Vector3d a = m.points.row(m.triangles(t, 0)), b = m.points.row(m.triangles(t, 1)),
                          c = m.points.row(m.triangles(t, 2));
    const double det = a.dot(b.cross(c));
    six += det;
    moment += det * (a + b + c);
  }
  if (centroid) *centroid = moment / (4.0 * six);
  return six / 6.0;
}


TEST(CliShapeGuard, KeepVolumeAndCentreRestoreThemInTheWrittenMesh) {
  TempDir dir;
  scenes::writeMesh(dir / "ball.vtp", ball());
  Eigen::Vector3d restCentre;
  const double rest = volumeOf(ball(), &restCentre);
  const std::string tool = (kWidgetExamples / "fig6-8.json").string();
  const CliResult plain = runCli({"deform", "-w", tool, (dir / "ball.vtp").string(), "-o", (dir / "plain.vtp").string(),
                                  "--fit", "--set", "push-front=0.5"});
  ASSERT_EQ(plain.exitCode, 0) << describe(plain);
  const double changed = volumeOf(scenes::readMesh(dir / "plain.vtp"));
  ASSERT_GT(std::abs(changed - rest) / rest, 1e-3);  // the tool does change the volume

  const CliResult kept = runCli({"deform", "-w", tool, (dir / "ball.vtp").string(), "-o", (dir / "kept.vtp").string(),
                                 "--fit", "--set", "push-front=0.5", "--keep-volume", "ball", "--keep-centre", "ball"});
  ASSERT_EQ(kept.exitCode, 0) << describe(kept);
  EXPECT_NE(kept.out.find("volume kept"), std::string::npos) << kept.out;
  Eigen::Vector3d centre;
  const MeshData out = scenes::readMesh(dir / "kept.vtp");
  EXPECT_LT(std::abs(volumeOf(out, &centre) - rest) / rest, 1e-12);
  EXPECT_LT((centre - restCentre).norm(), 1e-11);
  EXPECT_GT((out.points - scenes::readMesh(dir / "plain.vtp").points).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(CliShapeGuard, KeepVolumeOfAnOpenSurfaceFailsNamingTheEdgeAndWritesNothing) {
  TempDir dir;
  MeshData open = ball(8);
  open.triangles.conservativeResize(open.triangles.rows() - 1, 3);
  scenes::writeMesh(dir / "cup.vtp", open);
  const CliResult r = runCli({"deform", "-w", (kWidgetExamples / "fig6-8.json").string(), (dir / "cup.vtp").string(),
                              "-o", (dir / "out.vtp").string(), "--fit", "--keep-volume", "cup"});
  EXPECT_EQ(r.exitCode, 1) << describe(r);
  EXPECT_NE(r.err.find("object 'cup'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("open"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.vtp"));
  const CliResult unknown = runCli({"deform", "-w", (kWidgetExamples / "fig6-8.json").string(), (dir / "cup.vtp").string(),
                                    "-o", (dir / "out.vtp").string(), "--keep-centre", "nothing"});
  EXPECT_EQ(unknown.exitCode, 1) << describe(unknown);
  EXPECT_NE(unknown.err.find("no object 'nothing'"), std::string::npos) << unknown.err;
}

TEST(CliShapeGuard, FoldCheckErrorRefusesAFoldingToolWarnWritesOffIsSilent) {
  TempDir dir;
  scenes::writeMesh(dir / "ball.vtp", ball(8));
  const std::vector<std::string> folding = {"deform", "-w", (kWidgetExamples / "fig6-8.json").string(),
                                            (dir / "ball.vtp").string(), "--fit", "--set", "push-front=-3"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = folding;
    a.insert(a.end(), extra.begin(), extra.end());
    return runCli(a);
  };
  const CliResult error = with({"-o", (dir / "e.vtp").string(), "--fold-check", "error"});
  EXPECT_EQ(error.exitCode, 1) << describe(error);
  EXPECT_NE(error.err.find("folds"), std::string::npos) << error.err;
  EXPECT_FALSE(fs::exists(dir / "e.vtp"));
  const CliResult warn = with({"-o", (dir / "w.vtp").string()});  // warn is the default
  EXPECT_EQ(warn.exitCode, 0) << describe(warn);
  EXPECT_NE(warn.err.find("folds"), std::string::npos) << warn.err;
  EXPECT_TRUE(fs::exists(dir / "w.vtp"));
  const CliResult off = with({"-o", (dir / "o.vtp").string(), "--fold-check", "off"});
  EXPECT_EQ(off.exitCode, 0) << describe(off);
  EXPECT_EQ(off.err.find("folds"), std::string::npos) << off.err;
  const CliResult mild = runCli({"deform", "-w", (kWidgetExamples / "fig6-8.json").string(), (dir / "ball.vtp").string(),
                                 "--fit", "--set", "push-front=0.5", "-o", (dir / "m.vtp").string(), "--fold-check", "error"});
  EXPECT_EQ(mild.exitCode, 0) << describe(mild);
  const CliResult bad = with({"-o", (dir / "b.vtp").string(), "--fold-check", "sometimes"});
  EXPECT_EQ(bad.exitCode, 2) << describe(bad);
}

TEST(CliShapeGuard, InfoAndValidateReportFoldOverOfTheExampleTools) {
  for (const char* name : {"fig6-8.json", "fig6-9.json", "fig6-10-press.json"}) {
    const CliResult info = runCli({"info", (kWidgetExamples / name).string()});
    ASSERT_EQ(info.exitCode, 0) << describe(info);
    EXPECT_NE(info.out.find("fold-over: every lattice certified free of it"), std::string::npos) << name << info.out;
    const CliResult validate = runCli({"validate", (kWidgetExamples / name).string()});
    EXPECT_EQ(validate.exitCode, 0) << describe(validate);
    EXPECT_EQ(validate.out.find("fold-over"), std::string::npos) << validate.out;
  }
  // Kuriyama 1996, Fig. 6-2's twisted box: det J reaches 0 at the corner (1, 1, 0) of its
  // parameter box (positive inside), which the bound reports as a point with det J <= 0.
  const CliResult info = runCli({"info", (kWidgetExamples / "fig6-2.json").string()});
  ASSERT_EQ(info.exitCode, 0) << describe(info);
  EXPECT_NE(info.out.find("fold-over: lattice unit-box folds in 1 of 1 cells (det J = 0 at u,v,w = 1, 1, 0): "
                          "cells (0, 0, 0)\n"),
            std::string::npos) << info.out;
  const CliResult validate = runCli({"validate", (kWidgetExamples / "fig6-2.json").string()});
  EXPECT_EQ(validate.exitCode, 0) << describe(validate);  // reported, not a broken file
  EXPECT_NE(validate.out.find("fold-over: lattice unit-box folds"), std::string::npos) << validate.out;
}

// The press sample with its handle-to-press gain raised so that a full turn of the handle (the
// animation's last key, t = 3 s) pushes the jaw 3.1 below its rest, through the block's bottom
// face: the 2x2x2 lattice's map turns inside out there (det J < 0) while t = 0 is the rest.
fs::path foldingPress(const fs::path& dir) {
  std::string text = readText(kSceneExamples / "press" / "scene.json");
  const std::string binding = "\"gain\": 0.06366197723675814,\n        \"clamp\": [0.0, 0.3],";
  const std::size_t at = text.find(binding);
  EXPECT_NE(at, std::string::npos) << "the press sample's binding changed";
  if (at != std::string::npos) text.replace(at, binding.size(), "\"gain\": 0.5,\n        \"clamp\": [0.0, 5.0],");
  fs::create_directories(dir / "press");
  std::ofstream(dir / "press" / "scene.json", std::ios::binary) << text;
  return dir / "press";
}

TEST(CliShapeGuard, ExportSkinRefusesAFoldingDeformationUnlessAllowed) {
  TempDir dir;
  // Certified: the press as shipped (the jaw moves 0.4 of the block's height at most).
  const CliResult fine = runCli({"export", (kSceneExamples / "press").string(), "-o", (dir / "fine.glb").string(), "--skin"});
  EXPECT_EQ(fine.exitCode, 0) << describe(fine);
  EXPECT_TRUE(fs::exists(dir / "fine.glb"));
  EXPECT_EQ(fine.err.find("folds"), std::string::npos) << fine.err;
  // Folding at the last key: refused, nothing written, the key, lattice and cell named.
  const fs::path press = foldingPress(dir.path());
  const CliResult refused = runCli({"export", press.string(), "-o", (dir / "fold.glb").string(), "--skin"});
  EXPECT_EQ(refused.exitCode, 1) << describe(refused);
  EXPECT_FALSE(fs::exists(dir / "fold.glb"));
  EXPECT_NE(refused.err.find("export --skin: the deformation folds space over itself"), std::string::npos) << refused.err;
  // Checked at every frame the skin samples (keys 0 and 3 s at 24 frames/s: 73 times), not only at
  // the keys: the first folding frame is named, and it is the first frame `deform --frame
  // --fold-check error` refuses.
  const std::string prefix = "at t = ";
  const std::size_t first = refused.err.find(prefix);
  ASSERT_NE(first, std::string::npos) << refused.err;
  const double foldTime = std::stod(refused.err.substr(first + prefix.size()));
  EXPECT_GT(foldTime, 0.0) << refused.err;  // the rest does not fold
  EXPECT_LT(foldTime, 3.0) << refused.err;  // between the keys
  EXPECT_NE(refused.err.find(" s: lattice press-frame folds in 1 of 1 cells"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("cells (0, 0, 0)"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("of the 73 sampled times fold"), std::string::npos) << refused.err;
  const long frame = std::lround(foldTime * 24.0);
  EXPECT_NEAR(foldTime * 24.0, double(frame), 1e-4) << "sampled at a frame (printed to 6 digits)";
  const auto deformAtFrame = [&](long f) {
    return runCli({"deform", press.string(), "--frame", std::to_string(f), "--fold-check", "error", "-o",
                   (dir / ("frame" + std::to_string(f) + ".ply")).string()});
  };
  const CliResult atFold = deformAtFrame(frame);
  EXPECT_EQ(atFold.exitCode, 1) << describe(atFold);
  EXPECT_NE(atFold.err.find("folds"), std::string::npos) << atFold.err;
  const CliResult before = deformAtFrame(frame - 1);
  EXPECT_EQ(before.exitCode, 0) << describe(before);
  EXPECT_NE(refused.err.find("--allow-folding"), std::string::npos) << refused.err;
  // Asked for: written, with the finding as a warning.
  const CliResult allowed =
      runCli({"export", press.string(), "-o", (dir / "fold.glb").string(), "--skin", "--allow-folding"});
  EXPECT_EQ(allowed.exitCode, 0) << describe(allowed);
  EXPECT_TRUE(fs::exists(dir / "fold.glb"));
  EXPECT_NE(allowed.err.find(" s: lattice press-frame folds"), std::string::npos) << allowed.err;
  // --allow-folding belongs to --skin.
  const CliResult usage =
      runCli({"export", press.string(), "-o", (dir / "m.glb").string(), "--morph", "--allow-folding"});
  EXPECT_EQ(usage.exitCode, 2) << describe(usage);
  // info reports the same lattice as it is saved (the jaw at the saved variation): certified.
  const CliResult info = runCli({"info", press.string()});
  EXPECT_EQ(info.exitCode, 0) << describe(info);
}

}  // namespace
}  // namespace ffdkit::cli::test
