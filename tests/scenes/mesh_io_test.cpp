#include "ffdkit/scenes/mesh_io.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "ffdkit/scenes/primitive.h"

namespace ffdkit::scenes {
namespace {

class MeshIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("ffdkit-mesh-io-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static MeshData torus() {
    const auto mesh = makePrimitive({.kind = PrimitiveKind::Torus, .resolution = 12});
    return MeshData{mesh.vertices, mesh.triangles, {}, false};
  }

  std::filesystem::path dir_;
};

TEST_F(MeshIo, RoundTripsEveryWritableFormat) {
  const MeshData original = torus();
  // STL and PLY store single precision; OBJ text keeps ~6 significant digits in VTK 9.1.
  const std::pair<const char*, double> formats[] = {{".vtp", 0.0}, {".xyz", 0.0}, {".ply", 1e-6},
                                                    {".obj", 1e-5}, {".stl", 1e-6}};
  for (const auto& [ext, tolerance] : formats) {
    SCOPED_TRACE(ext);
    const auto path = dir_ / (std::string("torus") + ext);
    writeMesh(path, original);
    const MeshData back = readMesh(path);
    if (std::string(ext) == ".stl") {
      // STL has no shared vertices: compare the triangles' corner positions.
      ASSERT_EQ(back.triangles.rows(), original.triangles.rows());
      for (Eigen::Index t = 0; t < original.triangles.rows(); ++t)
        for (int c = 0; c < 3; ++c)
          EXPECT_LE((back.points.row(back.triangles(t, c)) - original.points.row(original.triangles(t, c))).norm(), tolerance);
      continue;
    }
    ASSERT_EQ(back.points.rows(), original.points.rows());
    EXPECT_LE((back.points - original.points).cwiseAbs().maxCoeff(), tolerance);
    if (std::string(ext) != ".xyz") {
      EXPECT_EQ(back.triangles, original.triangles);
    }
  }
}

TEST_F(MeshIo, NormalsAreRecomputedFromTheDeformedPoints) {
  MeshData mesh = torus();
  mesh.hasNormals = true;
  mesh.points.col(2) *= 3.0;  // a "deformation"
  writeMesh(dir_ / "n.vtp", mesh);
  const MeshData back = readMesh(dir_ / "n.vtp");
  EXPECT_TRUE(back.hasNormals);
  EXPECT_EQ(back.points, mesh.points);
}

TEST_F(MeshIo, PolylinesBecomeSegments) {
  MeshData curve;
  curve.points.resize(4, 3);
  curve.points << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 1;
  curve.segments.resize(3, 2);
  curve.segments << 0, 1, 1, 2, 2, 3;
  writeMesh(dir_ / "c.vtp", curve);
  const MeshData back = readMesh(dir_ / "c.vtp");
  EXPECT_EQ(back.segments, curve.segments);
  EXPECT_EQ(back.triangles.rows(), 0);
}

TEST_F(MeshIo, XyzStreamsRoundTripExactly) {
  Eigen::MatrixX3d points(2, 3);
  points << 0.1, -2.5e-7, 3.0, 1.0 / 3.0, 2.0, -4.0;
  std::stringstream text;
  writeXyz(text, points);
  EXPECT_EQ(readXyz(text).points, points);
}

TEST_F(MeshIo, BadInputGetsClearErrorsAndWritesNothing) {
  EXPECT_THROW(
      {
        try {
          readMesh(dir_ / "missing.obj");
        } catch (const MeshIoError& e) {
          EXPECT_NE(std::string(e.what()).find("missing.obj: no such file"), std::string::npos) << e.what();
          throw;
        }
      },
      MeshIoError);
  std::ofstream(dir_ / "bad.xyz") << "1 2 3\n4 five 6\n";
  try {
    readMesh(dir_ / "bad.xyz");
    FAIL() << "expected an error";
  } catch (const MeshIoError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.xyz:2:"), std::string::npos) << e.what();
  }
  for (const char* bad : {"1 2 nan\n", "1e999 0 0\n", "0 0 0\nnan 0 0\n", "1 2\n", "1 2 3 4\n"}) {
    std::ofstream(dir_ / "nan.xyz") << bad;
    EXPECT_THROW(readMesh(dir_ / "nan.xyz"), MeshIoError) << bad;
  }
  std::ofstream(dir_ / "empty.ply") << "";
  EXPECT_THROW(readMesh(dir_ / "empty.ply"), MeshIoError);
  EXPECT_THROW(readMesh(dir_ / "x.3ds"), MeshIoError);

  MeshData broken = torus();
  broken.points(3, 1) = std::nan("");
  EXPECT_THROW(writeMesh(dir_ / "out.obj", broken), MeshIoError);
  broken = torus();
  broken.triangles(0, 0) = 100000;
  EXPECT_THROW(writeMesh(dir_ / "out.ply", broken), MeshIoError);
  EXPECT_THROW(writeMesh(dir_ / "out.gltf", torus()), MeshIoError);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out.obj"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out.ply"));
}

TEST_F(MeshIo, AFailedWriteLeavesTheExistingFileUntouched) {
  const auto path = dir_ / "keep.xyz";
  std::ofstream(path) << "1 2 3\n";
  MeshData empty;
  EXPECT_THROW(writeMesh(path, empty), MeshIoError);
  EXPECT_EQ(readMesh(path).points.rows(), 1);
  // No temporary files are left behind.
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_)) ++files;
  EXPECT_EQ(files, 1);
}

}  // namespace
}  // namespace ffdkit::scenes
