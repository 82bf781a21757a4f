// Y-up mesh files turned to ffdkit's Z-up world (scenes/up_axis.h): a proper rotation, applied
// once as the file is read, kept by the scene file (`"up": "y"`) so the object stands up again
// when the scene is opened.
#include "ffdkit/scenes/up_axis.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::scenes {
namespace {

const std::filesystem::path kColumn = FFDKIT_SOURCE_DIR "/tests/data/y_up_column.obj";

TEST(UpAxis, YUpIsAProperRotationTakingYToZ) {
  const Eigen::Matrix3d r = upAxisRotation(UpAxis::Y);
  EXPECT_NEAR((r * r.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-15);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-15);
  EXPECT_EQ(r * Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ());   // up stays up
  EXPECT_EQ(r * Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitY());  // the front faces -y
  EXPECT_EQ(r * Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitX());
  EXPECT_EQ(upAxisRotation(UpAxis::Z), Eigen::Matrix3d::Identity());
}

TEST(UpAxis, AYUpColumnFileStandsUp) {
  MeshData mesh = readMesh(kColumn);
  const MeshData asWritten = mesh;
  convertToZUp(mesh, UpAxis::Y);
  // The file's column: x in [-0.5, 0.5], y (up) in [0, 3], z in [0.1, 0.7].
  const Eigen::Vector3d lo = mesh.points.colwise().minCoeff(), hi = mesh.points.colwise().maxCoeff();
  EXPECT_NEAR((lo - Eigen::Vector3d(-0.5, -0.7, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((hi - Eigen::Vector3d(0.5, -0.1, 3.0)).norm(), 0.0, 1e-15);
  for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) {
    EXPECT_EQ(mesh.points(i, 0), asWritten.points(i, 0));
    EXPECT_EQ(mesh.points(i, 1), -asWritten.points(i, 2));
    EXPECT_EQ(mesh.points(i, 2), asWritten.points(i, 1));
  }
  EXPECT_EQ(mesh.triangles, asWritten.triangles);
}

TEST(UpAxis, TheSceneFileKeepsTheUpAxis) {
  const std::string text = R"({"format": "ffdkit-scene", "version": 1, "objects": [
    {"name": "column", "mesh": {"path": ")" + kColumn.string() + R"(", "up": "y"}}]})";
  SceneReadOptions options;
  options.confinement.allowOutside = true;
  std::istringstream in(text);
  const Scene scene = readScene(in, "column.json", options);
  ASSERT_EQ(scene.objects().size(), 1u);
  EXPECT_EQ(std::get<MeshFileSource>(scene.objects()[0].source).up, UpAxis::Y);
  EXPECT_NEAR(scene.objects()[0].mesh.points.col(2).maxCoeff(), 3.0, 1e-15);  // read standing
  std::ostringstream out;
  writeScene(out, scene);
  EXPECT_NE(out.str().find("\"up\": \"y\""), std::string::npos) << out.str();
  std::istringstream again(out.str());
  EXPECT_EQ(readScene(again, "again.json", options).objects()[0].mesh.points, scene.objects()[0].mesh.points);

  std::string bad = text;
  bad.replace(bad.find("\"up\": \"y\""), 9, "\"up\": \"x\"");
  std::istringstream badIn(bad);
  try {
    readScene(badIn, "bad.json", options);
    FAIL() << "an unknown up axis was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("/objects/0/mesh/up: unknown up axis 'x' (known: z, y)"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace ffdkit::scenes
