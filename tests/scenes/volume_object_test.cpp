// A volume mesh as a scene object (volume_object.h): the sample scene volume-duct (a Gmsh mesh of
// tetrahedra), read, written back and deformed; its surface is the mesh's boundary, its points
// are every point of the file, and the written mesh is the file with the deformed points.
#include "ffdkit/scenes/volume_object.h"

#include <unistd.h>

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "ffdkit/meshio/element_cells.h"
#include "ffdkit/meshio/volume_mesh.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::scenes {
namespace {

namespace fs = std::filesystem;

const fs::path kSample = fs::path(FFDKIT_SOURCE_DIR) / "scenes/examples/volume-duct";

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class VolumeObject : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ffdkit-volume-object-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// The volume enclosed by a closed triangle surface (divergence theorem).
double enclosedVolume(const MeshData& mesh) {
  double volume = 0.0;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const Eigen::Vector3d a = mesh.points.row(mesh.triangles(t, 0)), b = mesh.points.row(mesh.triangles(t, 1)),
                          c = mesh.points.row(mesh.triangles(t, 2));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

TEST_F(VolumeObject, TheSampleHoldsEveryPointOfTheMeshAndDrawsItsBoundary) {
  const Scene scene = readScene(kSample);
  ASSERT_EQ(scene.objects().size(), 1u);
  const SceneObject& duct = scene.objects().front();
  EXPECT_EQ(volumeMeshFormatOf(duct.source, kSample), meshio::VolumeMeshFormat::Gmsh);
  const auto file = meshio::readVolumeMesh(kSample / "duct.msh");
  EXPECT_EQ(duct.mesh.points, file->points());  // all of them, interior ones too, in the file's order
  ASSERT_GT(duct.mesh.triangles.rows(), 0);
  // The boundary of a 2 x 0.6 x 0.6 box, facing out: it encloses the cells' total volume.
  const meshio::ElementQuality cells = meshio::checkElementCells(file->points(), *file->elementCells());
  EXPECT_NEAR(cells.totalVolume, 2.0 * 0.6 * 0.6, 1e-12);
  EXPECT_NEAR(enclosedVolume(duct.mesh), cells.totalVolume, 1e-12);
  // Only boundary points are drawn: every triangle corner lies on a face of the box.
  for (Eigen::Index k = 0; k < duct.mesh.triangles.size(); ++k) {
    const Eigen::RowVector3d p = duct.mesh.points.row(duct.mesh.triangles.data()[k]);
    const bool onFace = std::abs(p.x()) < 1e-9 || std::abs(p.x() - 2.0) < 1e-9 || std::abs(std::abs(p.y()) - 0.3) < 1e-9 ||
                        std::abs(p.z()) < 1e-9 || std::abs(p.z() - 0.6) < 1e-9;
    ASSERT_TRUE(onFace) << p;
  }
}

TEST_F(VolumeObject, TheSampleSceneFileRoundTripsToItsOwnBytes) {
  const Scene scene = readScene(kSample);
  EXPECT_EQ(sceneFileText(scene), slurp(kSample / "scene.json"));
  // Written beside a copy of its mesh, it reads back the same.
  fs::copy_file(kSample / "duct.msh", dir_ / "duct.msh");
  writeScene(dir_ / "scene.json", scene);
  const Scene again = readScene(dir_ / "scene.json");
  EXPECT_EQ(again.objects().front().mesh.points, scene.objects().front().mesh.points);
  EXPECT_EQ(again.objects().front().mesh.triangles, scene.objects().front().mesh.triangles);
  EXPECT_EQ(sceneFileText(again), sceneFileText(scene));
}

TEST_F(VolumeObject, WritingTheDeformedMeshGivesTheFileWithTheDeformedPoints) {
  Scene scene = readScene(kSample);
  scene.widgets.applyVariation(scene.widgets.find("pinch"), 0.15);
  const Eigen::MatrixX3d deformed = deformScene(scene).at("duct");
  const SceneObject& duct = scene.objects().front();
  ASSERT_GT((deformed - duct.mesh.points).cwiseAbs().maxCoeff(), 0.05);  // interior points moved too
  const VolumeObjectWriteResult result = writeVolumeObject(duct, deformed, kSample, dir_ / "pinched.msh");
  EXPECT_EQ(result.format, meshio::VolumeMeshFormat::Gmsh);
  EXPECT_EQ(result.pointCount, deformed.rows());
  EXPECT_TRUE(result.quality.checked);
  EXPECT_TRUE(result.quality.ok()) << result.quality.badText;
  const auto original = meshio::readVolumeMesh(kSample / "duct.msh");
  EXPECT_EQ(slurp(dir_ / "pinched.msh"), original->bytesWith(deformed));  // pass-through: only coordinates change
  EXPECT_EQ(meshio::readVolumeMesh(dir_ / "pinched.msh")->points(), deformed);
}

TEST_F(VolumeObject, InvertedCellsRefuseTheWriteUnlessAllowed) {
  Scene scene = readScene(kSample);
  scene.widgets.applyVariation(scene.widgets.find("pinch"), 1.5);  // the top pushed through the bottom
  const Eigen::MatrixX3d deformed = deformScene(scene).at("duct");
  const SceneObject& duct = scene.objects().front();
  try {
    writeVolumeObject(duct, deformed, kSample, dir_ / "folded.msh");
    FAIL() << "no error";
  } catch (const InvertedCellsError& e) {
    EXPECT_NE(std::string(e.what()).find("inverted or of zero volume (first: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nothing written"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "folded.msh"));
  VolumeObjectWriteOptions options;
  options.allowInverted = true;
  const VolumeObjectWriteResult result = writeVolumeObject(duct, deformed, kSample, dir_ / "folded.msh", options);
  EXPECT_GT(result.quality.badCells, 0);
  EXPECT_EQ(meshio::readVolumeMesh(dir_ / "folded.msh")->check(deformed).badCells, result.quality.badCells);
}

// Two volume objects written as one batch (writeVolumeObjects): all or nothing.
TEST_F(VolumeObject, SeveralObjectsAreWrittenAllOrNothing) {
  Scene scene = readScene(kSample);
  const SceneObject& duct = scene.objects().front();
  const Eigen::MatrixX3d rest = duct.mesh.points;
  scene.widgets.applyVariation(scene.widgets.find("pinch"), 1.5);  // the top pushed through the bottom
  const Eigen::MatrixX3d folded = deformScene(scene).at("duct");
  ASSERT_FALSE(meshio::readVolumeMesh(kSample / "duct.msh")->check(folded).ok());
  const auto listing = [&] {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
    return names;
  };
  // The second folds: the first, whose cells are valid, is not written either.
  try {
    writeVolumeObjects({{&duct, &rest, dir_ / "first.msh"}, {&duct, &folded, dir_ / "second.msh"}}, kSample);
    FAIL() << "no error";
  } catch (const InvertedCellsError& e) {
    EXPECT_NE(std::string(e.what()).find("second.msh is unchanged"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(listing().empty());
  // The second cannot be written (its folder does not exist): the first written is removed.
  EXPECT_THROW(writeVolumeObjects({{&duct, &rest, dir_ / "first.msh"}, {&duct, &rest, dir_ / "missing" / "second.msh"}}, kSample),
               meshio::MeshIoError);
  EXPECT_TRUE(listing().empty());
  // An existing output stays as it was when the batch fails, and is replaced when it succeeds.
  std::ofstream(dir_ / "first.msh") << "old";
  EXPECT_THROW(writeVolumeObjects({{&duct, &folded, dir_ / "first.msh"}, {&duct, &folded, dir_ / "second.msh"}}, kSample),
               InvertedCellsError);
  EXPECT_EQ(slurp(dir_ / "first.msh"), "old");
  VolumeObjectWriteOptions allow;
  allow.allowInverted = true;
  const std::vector<VolumeObjectWriteResult> results =
      writeVolumeObjects({{&duct, &rest, dir_ / "first.msh"}, {&duct, &folded, dir_ / "second.msh"}}, kSample, allow);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_TRUE(results[0].quality.ok());
  EXPECT_GT(results[1].quality.badCells, 0);
  const auto original = meshio::readVolumeMesh(kSample / "duct.msh");
  EXPECT_EQ(slurp(dir_ / "first.msh"), slurp(kSample / "duct.msh"));
  EXPECT_EQ(slurp(dir_ / "second.msh"), original->bytesWith(folded));
  EXPECT_EQ(listing().size(), 2u);  // no temporary left
}

TEST_F(VolumeObject, AYUpMeshIsTurnedBackAsItIsWritten) {
  fs::copy_file(kSample / "duct.msh", dir_ / "duct.msh");
  SceneObject object;
  object.name = "duct";
  object.source = MeshFileSource{"duct.msh", UpAxis::Y};
  object.mesh = buildObjectMesh(object.source, dir_);
  const Eigen::MatrixX3d file = meshio::readVolumeMesh(dir_ / "duct.msh")->points();
  EXPECT_TRUE(object.mesh.points.col(2).isApprox(file.col(1)));  // the file's y is the world's z
  writeVolumeObject(object, object.mesh.points, dir_, dir_ / "same.msh");
  EXPECT_EQ(slurp(dir_ / "same.msh"), slurp(dir_ / "duct.msh"));  // unchanged points keep their text
}

TEST_F(VolumeObject, AnOutputNamedForAnotherFormatOrAChangedFileIsRefused) {
  const Scene scene = readScene(kSample);
  const SceneObject& duct = scene.objects().front();
  EXPECT_THROW(writeVolumeObject(duct, duct.mesh.points, kSample, dir_ / "duct.su2"), std::invalid_argument);
  EXPECT_THROW(writeVolumeObject(duct, duct.mesh.points.topRows(10), kSample, dir_ / "duct.msh"), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir_ / "duct.su2"));
  EXPECT_FALSE(fs::exists(dir_ / "duct.msh"));
}

}  // namespace
}  // namespace ffdkit::scenes
