// cad_scene (cad/scene/include/ffdkit/cad_scene/scene_cad_objects.h): a scene's STEP part read as
// the tessellation the app and ffdkit-cli show, and written back deformed exactly by its one lattice.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "cad_test_support.h"
#include "ffdkit/cad/cad_check.h"
#include "ffdkit/cad/cad_deform.h"
#include "ffdkit/cad/cad_io.h"
#include "ffdkit/cad/sample_parts.h"
#include "ffdkit/cad/tessellation.h"
#include "ffdkit/cad_scene/scene_cad_objects.h"
#include "ffdkit/scenes/cad_objects.h"
#include "ffdkit/scenes/scene.h"

namespace ffdkit::cad_scene {
namespace {

namespace fs = std::filesystem;
using cad::test::ScratchFolder;

/// A scene holding `part.step` (relative to the scene's folder) as object "part", shown as
/// `triangles` (a lattice attached to it is fitted around them).
scenes::Scene sceneWithPart(const cad::CadTriangles& triangles) {
  scenes::Scene scene;
  scenes::SceneObject object;
  object.name = "part";
  object.source = scenes::MeshFileSource{"part.step"};
  object.mesh.points = triangles.points;
  object.mesh.triangles = triangles.triangles;
  scene.addObject(std::move(object));
  return scene;
}

/// One triangle: enough for a scene whose part is never read.
cad::CadTriangles oneTriangle() {
  cad::CadTriangles triangles;
  triangles.points = Eigen::MatrixX3d::Zero(3, 3);
  triangles.points(1, 0) = triangles.points(2, 1) = 1.0;
  triangles.triangles = Eigen::MatrixX3i(1, 3);
  triangles.triangles << 0, 1, 2;
  return triangles;
}

/// The message of what `work` throws ("" when it throws nothing).
template <typename Work>
std::string errorOf(Work&& work) {
  try {
    work();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

double longestEdge(const scenes::MeshData& mesh) {
  double longest = 0.0;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t)
    for (int e = 0; e < 3; ++e)
      longest = std::max(longest, (mesh.points.row(mesh.triangles(t, e)) - mesh.points.row(mesh.triangles(t, (e + 1) % 3))).norm());
  return longest;
}

TEST(SceneCadObjects, AReadPartIsItsTessellationWithinTheToleranceAndEdgeBound) {
  ScratchFolder folder;
  const cad::CadModel part = cad::makeSamplePart(cad::SamplePart::FilletedBox);
  cad::writeStep(part, folder / "part.step");
  const double size = cad::readStep(folder / "part.step").bounds().diagonal().norm();

  meshio::ReadBudget budget;
  const scenes::MeshData mesh = readCadObject(folder / "part.step", budget);
  // The documented defaults: 1e-3 of the part's size from its faces, no edge over 2% of it.
  cad::TessellationOptions options;
  options.linearDeflection = 1e-3 * size;
  options.maxEdgeLength = 0.02 * size;
  const cad::CadTriangles expected = cad::tessellate(cad::readStep(folder / "part.step"), options);
  ASSERT_EQ(mesh.points.rows(), expected.points.rows());
  EXPECT_EQ(mesh.points, expected.points);
  EXPECT_EQ(mesh.triangles, expected.triangles);
  EXPECT_LE(longestEdge(mesh), 0.02 * size * (1.0 + 1e-9));
  EXPECT_EQ(budget.pointsCharged(), static_cast<std::uint64_t>(mesh.points.rows()));

  // A coarser tolerance gives fewer points; a budget too small for them is an error naming the file.
  meshio::ReadBudget coarseBudget;
  CadObjectTessellation coarse;
  coarse.tolerance = 1e-2;
  coarse.maxEdgeLength = 0.2;
  EXPECT_LT(readCadObject(folder / "part.step", coarseBudget, coarse).points.rows(), mesh.points.rows());
  meshio::ReadLimits tight;
  tight.maxPoints = 10;
  meshio::ReadBudget small(tight);
  const std::string overBudget = errorOf([&] { readCadObject(folder / "part.step", small); });
  EXPECT_NE(overBudget.find("part.step"), std::string::npos) << overBudget;
}

TEST(SceneCadObjects, TheRegisteredReaderTakesTheTessellationOfTheMomentOfEachRead) {
  ScratchFolder folder;
  cad::writeStep(cad::makeSamplePart(cad::SamplePart::FilletedBox), folder / "part.step");
  double tolerance = 1e-2;
  int asked = 0;
  registerCadObjectReader([&] {
    ++asked;
    CadObjectTessellation tessellation;
    tessellation.tolerance = tolerance;
    return tessellation;
  });
  meshio::ReadBudget first, second;
  const Eigen::Index coarse = scenes::readCadMesh(folder / "part.step", first).points.rows();
  tolerance = 1e-4;
  const Eigen::Index fine = scenes::readCadMesh(folder / "part.step", second).points.rows();
  EXPECT_EQ(asked, 2);
  EXPECT_LT(coarse, fine);
  scenes::setCadMeshReader({});
}

TEST(SceneCadObjects, AnExactOutputTakesOneLatticeWithoutChildren) {
  scenes::Scene scene = sceneWithPart(oneTriangle());
  const scenes::SceneObject& part = *scene.findObject("part");
  EXPECT_TRUE(isCadObject(part));
  EXPECT_EQ(cadObjects(scene).size(), 1u);
  EXPECT_EQ(cadObjectFile(part, "/data/scenes"), fs::path("/data/scenes/part.step"));
  EXPECT_FALSE(cadObjectLattice(scene, part).has_value());

  const widgets::WidgetId first = scenes::attachNewLattice(scene, {"part"});
  EXPECT_EQ(cadObjectLattice(scene, part), first);
  const widgets::WidgetId child = scene.widgets.addLattice("child", Eigen::Vector3i(2, 2, 2));
  scene.widgets.bind(scene.widgets.addCell(first, widgets::CellSpec::box(0, 0, 0)), child);
  const std::string withChild = errorOf([&] { cadObjectLattice(scene, part); });
  EXPECT_NE(withChild.find("and its child lattices"), std::string::npos) << withChild;
  scenes::Scene two = sceneWithPart(oneTriangle());
  scenes::attachNewLattice(two, {"part"});
  scenes::attachNewLattice(two, {"part"});
  const std::string twoLattices = errorOf([&] { cadObjectLattice(two, *two.findObject("part")); });
  EXPECT_NE(twoLattices.find("deformed by 2 lattices"), std::string::npos) << twoLattices;
}

TEST(SceneCadObjects, TheWrittenPartIsDeformCadOfItByItsLattice) {
  ScratchFolder folder;
  cad::writeStep(cad::makeSamplePart(cad::SamplePart::FilletedBox), folder / "part.step");
  const cad::CadModel part = cad::readStep(folder / "part.step");
  scenes::Scene scene = sceneWithPart(cad::tessellate(part));
  const scenes::SceneObject& object = *scene.findObject("part");
  const fs::path base = (folder / "part.step").parent_path();

  // No lattice: written as read.
  CadObjectExport written = writeDeformedCadObject(scene, object, base, folder / "as-read.step");
  EXPECT_TRUE(written.lattice.empty());
  const double volume = cad::checkModel(part).volume;
  EXPECT_NEAR(cad::checkModel(cad::readStep(folder / "as-read.step")).volume, volume, 1e-9 * volume);

  scenes::AttachOptions attach;
  attach.latticeName = "bend";
  const widgets::WidgetId lattice = scenes::attachNewLattice(scene, {"part"}, attach);
  // Its top layer of control points raised and sheared, its middle layer shifted (lattice-local).
  Eigen::MatrixX3d points = scene.widgets.controlPoints(lattice);
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    if (points(i, 2) > 0.99) points.row(i) += Eigen::RowVector3d(0.15 * points(i, 1), 0.05, 0.2);
    else if (points(i, 2) > 0.49) points(i, 0) += 0.1;
  scene.widgets.setControlPoints(lattice, points);
  written = writeDeformedCadObject(scene, object, base, folder / "out.step");
  EXPECT_EQ(written.lattice, "bend");
  EXPECT_EQ(written.faces, part.counts().faces);
  const cad::CadDeformResult expected = cad::deformCad(part, scene.widgets.ffdLattice(lattice));
  EXPECT_EQ(written.maxDegree, expected.report.maxDegree);
  EXPECT_EQ(written.approximatedFaces, expected.report.approximatedFaces);
  cad::writeStep(expected.model, folder / "expected.step");
  const double deformed = cad::checkModel(cad::readStep(folder / "expected.step")).volume;
  EXPECT_NEAR(cad::checkModel(cad::readStep(folder / "out.step")).volume, deformed, 1e-9 * deformed);
  EXPECT_GT(std::abs(deformed - volume), 1e-3 * volume);  // it did deform

  // An output that is not STEP or IGES writes nothing.
  EXPECT_THROW(writeDeformedCadObject(scene, object, base, folder / "out.stl"), std::runtime_error);
  EXPECT_FALSE(fs::exists(folder / "out.stl"));
}

}  // namespace
}  // namespace ffdkit::cad_scene
