// ffdkit-cli deform with a STEP input: the program run as a user runs it, its output file read back.
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include <sys/wait.h>

#include <gtest/gtest.h>

#include "cad_test_support.h"
#include "../cli/ffdkit_cli_path.h"
#include "ffdkit/cad/cad_check.h"
#include "ffdkit/cad/cad_deform.h"
#include "ffdkit/cad/cad_io.h"
#include "ffdkit/cad/sample_parts.h"
#include "ffdkit/cad/tessellation.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::cad {
namespace {

using test::deformedLatticeAround;
using test::ScratchFolder;

std::string rows(const Eigen::MatrixX3d& points) {
  std::ostringstream out;
  out.precision(17);
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    out << (i ? ",\n" : "") << "[" << points(i, 0) << ", " << points(i, 1) << ", " << points(i, 2) << "]";
  return out.str();
}

/// A widget file holding one lattice with `basis` ("bernstein" or a cubic "bspline") on every axis.
void writeTool(const std::filesystem::path& path, const ffd::Lattice& lattice, const std::string& basis) {
  const Eigen::Vector3i n = lattice.counts();
  const std::string axis = basis == "bernstein" ? R"({"kind": "bernstein"})" : R"({"kind": "bspline", "degree": 3})";
  std::ofstream out(path);
  out << R"({"format": "ffdkit-widgets", "version": 1, "lattices": [{"id": "w0", "name": "tool", "counts": [)" << n[0]
      << ", " << n[1] << ", " << n[2] << R"(], "basis": [)" << axis << ", " << axis << ", " << axis
      << R"(], "outside": {"policy": "identity"}, "reembed": {"policy": "immediate"},
        "frame": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]], "children": [], "rest": [)"
      << rows(lattice.restPoints()) << R"(], "points": [)" << rows(lattice.controlPoints()) << "]}]}\n";
}

struct CliRun {
  int status = -1;
  std::string output;
};

CliRun runCli(const std::string& arguments, const std::filesystem::path& log) {
  const std::string command = ffdkit::test::ffdkitCli() + " " + arguments + " > " + log.string() + " 2>&1";
  CliRun run;
  const int raw = std::system(command.c_str());
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(log);
  run.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return run;
}

TEST(CliCadDeform, WritesTheExactlyDeformedStep) {
  ScratchFolder folder;
  const CadModel model = makeSamplePart(SamplePart::Bottle);
  writeStep(model, folder / "bottle.step");
  const CadModel read = readStep(folder / "bottle.step");
  const ffd::Lattice lattice = deformedLatticeAround(read.bounds(), {3, 3, 2}, 0.08);
  writeTool(folder / "tool.json", lattice, "bernstein");
  const CliRun run = runCli("deform -w " + (folder / "tool.json").string() + " " + (folder / "bottle.step").string() +
                             " -o " + (folder / "out.step").string() + " --cad-check",
                         folder / "log.txt");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("BRepCheck: valid"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("exact composition"), std::string::npos) << run.output;
  const CadModel written = readStep(folder / "out.step");
  writeStep(deformCad(read, lattice).model, folder / "in-process.step");
  const double expected = checkModel(readStep(folder / "in-process.step")).volume;
  EXPECT_NEAR(checkModel(written).volume, expected, 1e-7 * expected);
  EXPECT_GT(std::abs(expected - checkModel(read).volume), 1e-3 * expected);  // it did deform
}

TEST(CliCadDeform, PoleMethodAndIgesOutput) {
  ScratchFolder folder;
  writeStep(makeSamplePart(SamplePart::FilletedBox), folder / "box.stp");
  const CadModel read = readStep(folder / "box.stp");
  writeTool(folder / "tool.json", deformedLatticeAround(read.bounds(), {3, 3, 2}, 0.08), "bernstein");
  const CliRun run = runCli("deform -w " + (folder / "tool.json").string() + " " + (folder / "box.stp").string() +
                             " -o " + (folder / "out.igs").string() + " --cad-method poles",
                         folder / "log.txt");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("poles moved"), std::string::npos) << run.output;
  EXPECT_GT(checkModel(readIges(folder / "out.igs")).volume, 0.0);
}

TEST(CliCadDeform, WrongUsesAreRefusedWithTheirReason) {
  ScratchFolder folder;
  writeStep(makeSamplePart(SamplePart::FilletedBox), folder / "box.step");
  const CadModel read = readStep(folder / "box.step");
  writeTool(folder / "bernstein.json", deformedLatticeAround(read.bounds(), {3, 3, 2}, 0.08), "bernstein");
  ffd::BoxLatticeOptions options;
  options.counts = {5, 5, 5};
  options.boxMin = read.bounds().min() - Eigen::Vector3d::Constant(5.0);
  options.boxMax = read.bounds().max() + Eigen::Vector3d::Constant(5.0);
  writeTool(folder / "bspline.json", ffd::makeBoxLattice(options), "bspline");
  const std::string in = (folder / "box.step").string();

  CliRun run = runCli("deform -w " + (folder / "bernstein.json").string() + " " + in + " -o " + (folder / "o.step").string() +
                       " --cad-method bogus",
                   folder / "log.txt");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("--cad-method must be exact or poles"), std::string::npos) << run.output;

  run = runCli("deform -w " + (folder / "bernstein.json").string() + " " + in + " -o " + (folder / "o.obj").string(),
               folder / "log.txt");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("-o OUTPUT.step"), std::string::npos) << run.output;

  // A cubic B-spline lattice: the fillets would compose to degree 18, above the limit; exact only,
  // that is refused and nothing is written.
  run = runCli("deform -w " + (folder / "bspline.json").string() + " " + in + " -o " + (folder / "o.step").string() +
                   " --cad-exact-only",
               folder / "log.txt");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("degree 18, above the limit of 15"), std::string::npos) << run.output;
  EXPECT_FALSE(std::filesystem::exists(folder / "o.step"));

  run = runCli("deform -w " + (folder / "bspline.json").string() + " " + in + " -o " + (folder / "o.step").string() +
                   " --cad-degree-limit 26",
               folder / "log.txt");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("--cad-degree-limit must be an integer in [1, 25]"), std::string::npos) << run.output;

  // Allowed to approximate (the default), it writes the part and says what it approximated.
  run = runCli("deform -w " + (folder / "bspline.json").string() + " " + in + " -o " + (folder / "o.step").string() +
                   " --cad-tolerance 1e-3 --cad-check",
               folder / "log.txt");
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("approximated within 0.001 of the FFD"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("BRepCheck: valid"), std::string::npos) << run.output;
  EXPECT_TRUE(std::filesystem::exists(folder / "o.step"));

  std::ofstream(folder / "broken.step") << "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=FOO(;\n";
  run = runCli("deform -w " + (folder / "bernstein.json").string() + " " + (folder / "broken.step").string() + " -o " +
                   (folder / "o.step").string(),
               folder / "log.txt");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("broken.step"), std::string::npos) << run.output;
}

/// A scene naming part.step (relative to its folder) with a 3 x 3 x 3 Bernstein lattice attached,
/// its top layer of control points raised and shifted; returns the lattice as the scene holds it.
ffd::Lattice writeSceneWithPart(const std::filesystem::path& scenePath, const CadModel& part) {
  scenes::Scene scene;
  scenes::SceneObject object;
  object.name = "part";
  object.source = scenes::MeshFileSource{"part.step"};
  const CadTriangles triangles = tessellate(part);
  object.mesh.points = triangles.points;
  object.mesh.triangles = triangles.triangles;
  scene.addObject(std::move(object));
  scenes::AttachOptions attach;
  attach.latticeName = "lattice";
  const widgets::WidgetId lattice = scenes::attachNewLattice(scene, {"part"}, attach);
  Eigen::MatrixX3d points = scene.widgets.ffdLattice(lattice).controlPoints();
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    if (points(i, 2) > 0.99) points.row(i) += Eigen::RowVector3d(0.15 * points(i, 1), 0.05, 0.2);
    else if (points(i, 2) > 0.49) points(i, 0) += 0.1;
  scene.widgets.setControlPoints(lattice, points);
  scenes::writeScene(scenePath, scene);
  return scene.widgets.ffdLattice(lattice);
}

TEST(CliCadScene, DeformWritesTheScenesStepPartDeformedAsDeformCadDoes) {
  // deform --scene with a .step output reads the part the scene names again and composes the
  // attached lattice with it: the file equals deformCad's of the same part by the same lattice.
  ScratchFolder folder;
  writeStep(makeSamplePart(SamplePart::FilletedBox), folder / "part.step");
  const CadModel part = readStep(folder / "part.step");
  const ffd::Lattice lattice = writeSceneWithPart(folder / "scene.json", part);
  const CliRun run = runCli("deform --scene " + (folder / "scene.json").string() + " -o " +
                                (folder / "out.step").string() + " --cad-check",
                            folder / "log.txt");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("exact composition"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("BRepCheck: valid"), std::string::npos) << run.output;
  const CadModel written = readStep(folder / "out.step");
  const CadModel expected = deformCad(part, lattice).model;
  writeStep(expected, folder / "in-process.step");
  const CadModel expectedBack = readStep(folder / "in-process.step");
  EXPECT_EQ(written.counts().faces, part.counts().faces);
  const double volume = checkModel(expectedBack).volume;
  EXPECT_NEAR(checkModel(written).volume, volume, 1e-9 * volume);
  EXPECT_LT((written.bounds().min() - expectedBack.bounds().min()).norm(), 1e-6);
  EXPECT_LT((written.bounds().max() - expectedBack.bounds().max()).norm(), 1e-6);
  EXPECT_GT(std::abs(volume - checkModel(part).volume), 1e-2 * volume);  // it did deform

  // A mesh output writes the deformed tessellation instead; info and validate read the scene.
  const CliRun mesh = runCli("deform --scene " + (folder / "scene.json").string() + " -o " +
                                 (folder / "out.stl").string(),
                             folder / "log.txt");
  ASSERT_EQ(mesh.status, 0) << mesh.output;
  EXPECT_GT(std::filesystem::file_size(folder / "out.stl"), 1000u);
  const CliRun info = runCli("info " + (folder / "scene.json").string(), folder / "log.txt");
  EXPECT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("part"), std::string::npos) << info.output;
  const CliRun validate = runCli("validate " + (folder / "scene.json").string(), folder / "log.txt");
  EXPECT_EQ(validate.status, 0) << validate.output;
}

TEST(CliCadScene, AStepOutputNeedsTheScenesCadObject) {
  ScratchFolder folder;
  writeStep(makeSamplePart(SamplePart::TwoPartAssembly), folder / "part.step");
  writeSceneWithPart(folder / "scene.json", readStep(folder / "part.step"));
  CliRun run = runCli("deform --scene " + (folder / "scene.json").string() + " --object nothing -o " +
                          (folder / "out.step").string(),
                      folder / "log.txt");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("no object named 'nothing'"), std::string::npos) << run.output;
  run = runCli("deform --scene " + (folder / "scene.json").string() + " -o " + (folder / "out.step").string() +
                   " --cad-method poles --fit",
               folder / "log.txt");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_FALSE(std::filesystem::exists(folder / "out.step"));
}

}  // namespace
}  // namespace ffdkit::cad
