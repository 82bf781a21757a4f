// Round trips through every writable format, stream and path overloads, and write failures.
#include "ffdkit/meshio/mesh_io.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "ffdkit/scenes/primitive.h"

namespace ffdkit::meshio {
namespace {

class MeshIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("ffdkit-mesh-io-" + std::to_string(::getpid()) + "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static MeshData torus() {
    const auto mesh = scenes::makePrimitive({.kind = scenes::PrimitiveKind::Torus, .resolution = 12});
    return MeshData{mesh.vertices, mesh.triangles, {}, false};
  }
  int filesInDir() const {
    int files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_)) ++files;
    return files;
  }

  std::filesystem::path dir_;
};

// Float32 storage (binary PLY, STL) rounds each coordinate to 24 bits: relative 2^-24.
constexpr double kFloatTolerance = 1e-6;

TEST_F(MeshIo, RoundTripsEveryWritableFormat) {
  const MeshData original = torus();
  const std::pair<const char*, double> formats[] = {{".vtp", 0.0}, {".vtk", 0.0}, {".xyz", 0.0}, {".npy", 0.0},
                                                    {".obj", 0.0}, {".ply", kFloatTolerance}, {".stl", kFloatTolerance}};
  for (const auto& [ext, tolerance] : formats) {
    SCOPED_TRACE(ext);
    const auto path = dir_ / (std::string("torus") + ext);
    writeMesh(path, original);
    const MeshData back = readMesh(path);
    if (std::string(ext) == ".stl") {
      // STL stores corners per triangle; the reader merges identical ones back into shared points.
      ASSERT_EQ(back.points.rows(), original.points.rows());
      ASSERT_EQ(back.triangles.rows(), original.triangles.rows());
      for (Eigen::Index t = 0; t < original.triangles.rows(); ++t)
        for (int c = 0; c < 3; ++c)
          EXPECT_LE((back.points.row(back.triangles(t, c)) - original.points.row(original.triangles(t, c))).norm(), tolerance);
      continue;
    }
    ASSERT_EQ(back.points.rows(), original.points.rows());
    EXPECT_LE((back.points - original.points).cwiseAbs().maxCoeff(), tolerance);
    if (std::string(ext) != ".xyz" && std::string(ext) != ".npy") {
      EXPECT_EQ(back.triangles, original.triangles);
    }
  }
  EXPECT_EQ(filesInDir(), 7);  // no temporaries left
}

TEST_F(MeshIo, TextFormatsAndAsciiPlyRoundTripDoublesExactly) {
  MeshData mesh = torus();
  mesh.points(0, 0) = 0.1;
  mesh.points(1, 1) = -2.5e-7;
  mesh.points(2, 2) = 1.0 / 3.0;
  mesh.points(3, 0) = 1e300;
  mesh.points(4, 1) = 5e-324;  // the smallest subnormal
  for (MeshFormat format : {MeshFormat::Obj, MeshFormat::Xyz, MeshFormat::Npy, MeshFormat::Ply}) {
    SCOPED_TRACE(std::string(meshFormatExtension(format)));
    std::stringstream stream;
    writeMesh(stream, mesh, format, {.plyEncoding = PlyEncoding::Ascii});
    const MeshData back = readMesh(stream, format);
    EXPECT_EQ(back.points, mesh.points);  // bit for bit
  }
}

// Large text files are formatted in slices side by side (one per hardware thread): the text must be
// line for line what a serial printf-style loop gives, in order. 300,007 points make several
// slices with an uneven last one; each line is checked against std::to_chars of its own point.
TEST_F(MeshIo, LargeTextFilesAreTheSerialTextLineForLine) {
  MeshData mesh;
  mesh.points.resize(300007, 3);
  for (Eigen::Index i = 0; i < mesh.points.rows(); ++i)
    mesh.points.row(i) << std::ldexp(double(i) + 0.1, -int(i % 40)), -1.0 / double(i + 3), double(i) * 1e100;
  for (MeshFormat format : {MeshFormat::Xyz, MeshFormat::Obj}) {
    SCOPED_TRACE(std::string(meshFormatExtension(format)));
    const std::string text = meshFileBytes(mesh, format);
    std::istringstream lines(text);
    std::string line;
    if (format == MeshFormat::Obj) std::getline(lines, line);  // "# ffdkit"
    for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) {
      ASSERT_TRUE(std::getline(lines, line)) << "missing line for point " << i;
      std::string expected = format == MeshFormat::Obj ? "v " : "";
      for (int c = 0; c < 3; ++c) {
        char buffer[32];
        expected.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, mesh.points(i, c)).ptr);
        if (c < 2) expected += ' ';
      }
      ASSERT_EQ(line, expected) << "point " << i;
    }
    EXPECT_FALSE(std::getline(lines, line)) << "extra text: " << line;
    std::istringstream in(text);
    EXPECT_EQ(readMesh(in, format).points, mesh.points);  // bit for bit
    // A path write streams the slices into the file as they are formatted: the same bytes.
    const std::filesystem::path file = dir_ / ("large" + std::string(meshFormatExtension(format)));
    writeMesh(file, mesh);
    std::ifstream written(file, std::ios::binary);
    EXPECT_TRUE(std::equal(text.begin(), text.end(), std::istreambuf_iterator<char>(written), std::istreambuf_iterator<char>()));
  }
}

// OBJ faces and lines are also formatted in slices: 200,003 faces and 70,001 lines, each checked.
TEST_F(MeshIo, LargeObjFacesAndLinesAreTheSerialTextLineForLine) {
  MeshData mesh;
  mesh.points = Eigen::MatrixX3d::Random(200005, 3);
  mesh.triangles.resize(200003, 3);
  for (int t = 0; t < 200003; ++t) mesh.triangles.row(t) << t, t + 2, t + 1;
  mesh.segments.resize(70001, 2);
  for (int s = 0; s < 70001; ++s) mesh.segments.row(s) << s + 1, s;
  for (bool normals : {false, true}) {
    mesh.hasNormals = normals;
    const std::string text = meshFileBytes(mesh, MeshFormat::Obj);
    std::istringstream lines(text);
    std::string line;
    for (Eigen::Index i = 0; i < 1 + 2 * mesh.points.rows() - (normals ? 0 : mesh.points.rows()); ++i) std::getline(lines, line);
    auto index = [&](int v) { return std::to_string(v + 1) + (normals ? "//" + std::to_string(v + 1) : ""); };
    for (int t = 0; t < 200003; ++t) {
      ASSERT_TRUE(std::getline(lines, line));
      ASSERT_EQ(line, "f " + index(t) + " " + index(t + 2) + " " + index(t + 1)) << "face " << t;
    }
    for (int s = 0; s < 70001; ++s) {
      ASSERT_TRUE(std::getline(lines, line));
      ASSERT_EQ(line, "l " + std::to_string(s + 2) + " " + std::to_string(s + 1)) << "line " << s;
    }
    EXPECT_FALSE(std::getline(lines, line)) << "extra text: " << line;
  }
}

// Binary files stream through a 1 MiB buffer (records never straddle it): a mesh of several MiB
// must be, record for record, what a serial loop appends, in both byte orders, and a path write
// must hold the same bytes.
TEST_F(MeshIo, LargeBinaryFilesAreTheSerialRecordsByteForByte) {
  MeshData mesh;
  mesh.points = Eigen::MatrixX3d::Random(100003, 3) * 7.0;
  mesh.triangles.resize(100001, 3);
  for (int t = 0; t < 100001; ++t) mesh.triangles.row(t) << t, t + 2, t + 1;
  mesh.segments.resize(70001, 2);
  for (int s = 0; s < 70001; ++s) mesh.segments.row(s) << s + 1, s;
  auto append = [](std::string& out, auto value, bool big) {
    char raw[sizeof(value)];
    std::memcpy(raw, &value, sizeof(value));
    if (big) std::reverse(raw, raw + sizeof(value));
    out.append(raw, sizeof(value));
  };
  auto body = [](const std::string& file, const std::string& headerEnd) {
    const std::size_t at = file.find(headerEnd);
    return at == std::string::npos ? std::string() : file.substr(at + headerEnd.size());
  };
  for (bool normals : {false, true}) {
    mesh.hasNormals = normals;
    const Eigen::MatrixX3d n = vertexNormals(mesh.points, mesh.triangles);
    for (bool big : {false, true}) {
      SCOPED_TRACE(std::string("ply, normals ") + (normals ? "on" : "off") + (big ? ", big endian" : ", little endian"));
      std::string expected;
      for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) {
        for (int c = 0; c < 3; ++c) append(expected, float(mesh.points(i, c)), big);
        for (int c = 0; normals && c < 3; ++c) append(expected, float(n(i, c)), big);
      }
      for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
        expected += char(3);
        for (int c = 0; c < 3; ++c) append(expected, std::int32_t(mesh.triangles(t, c)), big);
      }
      for (Eigen::Index s = 0; s < mesh.segments.rows(); ++s)
        for (int c = 0; c < 2; ++c) append(expected, std::int32_t(mesh.segments(s, c)), big);
      const MeshWriteOptions options{.plyEncoding = big ? PlyEncoding::BinaryBigEndian : PlyEncoding::BinaryLittleEndian};
      const std::string bytes = meshFileBytes(mesh, MeshFormat::Ply, options);
      ASSERT_GT(expected.size(), std::size_t(2) << 20);  // spans several buffers
      EXPECT_TRUE(body(bytes, "end_header\n") == expected);
      const std::filesystem::path file = dir_ / "large.ply";
      writeMesh(file, mesh, options);
      std::ifstream written(file, std::ios::binary);
      EXPECT_TRUE(std::equal(bytes.begin(), bytes.end(), std::istreambuf_iterator<char>(written), std::istreambuf_iterator<char>()));
    }
  }
  std::string npy;
  for (Eigen::Index i = 0; i < mesh.points.rows(); ++i)
    for (int c = 0; c < 3; ++c) append(npy, mesh.points(i, c), false);
  const std::string npyBytes = meshFileBytes(mesh, MeshFormat::Npy);
  ASSERT_EQ(npyBytes.size() % 64, npy.size() % 64);  // the header is padded to 64 bytes
  EXPECT_TRUE(npyBytes.substr(npyBytes.size() - npy.size()) == npy);
  std::string stl;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const Eigen::Vector3d a = mesh.points.row(mesh.triangles(t, 0)), b = mesh.points.row(mesh.triangles(t, 1)),
                          c = mesh.points.row(mesh.triangles(t, 2));
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    for (int k = 0; k < 3; ++k) append(stl, std::isfinite(normal[k]) ? float(normal[k]) : 0.0f, false);
    for (const Eigen::Vector3d* p : {&a, &b, &c})
      for (int k = 0; k < 3; ++k) append(stl, float((*p)[k]), false);
    append(stl, std::uint16_t(0), false);
  }
  const std::string stlBytes = meshFileBytes(mesh, MeshFormat::Stl);
  ASSERT_EQ(stlBytes.size(), 84 + stl.size());
  EXPECT_TRUE(stlBytes.substr(84) == stl);
}

TEST_F(MeshIo, BinaryPlyOfBothByteOrdersReadsTheSame) {
  MeshData mesh = torus();
  mesh.segments.resize(2, 2);
  mesh.segments << 0, 1, 5, 7;
  mesh.hasNormals = true;
  const std::string little = meshFileBytes(mesh, MeshFormat::Ply, {.plyEncoding = PlyEncoding::BinaryLittleEndian});
  const std::string big = meshFileBytes(mesh, MeshFormat::Ply, {.plyEncoding = PlyEncoding::BinaryBigEndian});
  EXPECT_NE(little, big);
  EXPECT_NE(big.find("format binary_big_endian 1.0"), std::string::npos);
  const MeshData a = readMeshBytes(little, MeshFormat::Ply), b = readMeshBytes(big, MeshFormat::Ply);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.triangles, mesh.triangles);
  EXPECT_EQ(b.triangles, mesh.triangles);
  EXPECT_EQ(b.segments, mesh.segments);
  EXPECT_TRUE(b.hasNormals);
  EXPECT_LE((b.points - mesh.points).cwiseAbs().maxCoeff(), kFloatTolerance);
}

TEST_F(MeshIo, NormalsAreRecomputedFromTheDeformedPoints) {
  // A unit square in the z = 0 plane, "deformed" by swapping y and z: its normal must follow.
  MeshData mesh;
  mesh.points.resize(4, 3);
  mesh.points << 0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1;  // now in the y = 0 plane
  mesh.triangles.resize(2, 3);
  mesh.triangles << 0, 1, 2, 0, 2, 3;
  mesh.hasNormals = true;
  const std::string obj = meshFileBytes(mesh, MeshFormat::Obj);
  // (1,0,0) x (1,0,1) = (0,-1,0): every vertex normal is -y.
  EXPECT_NE(obj.find("vn 0 -1 0\nvn 0 -1 0\nvn 0 -1 0\nvn 0 -1 0\n"), std::string::npos) << obj;
  EXPECT_NE(obj.find("f 1//1 2//2 3//3"), std::string::npos) << obj;
  writeMesh(dir_ / "n.vtp", mesh);
  const MeshData back = readMesh(dir_ / "n.vtp");
  EXPECT_TRUE(back.hasNormals);
  EXPECT_EQ(back.points, mesh.points);
  const Eigen::MatrixX3d n = vertexNormals(mesh.points, mesh.triangles);
  for (Eigen::Index i = 0; i < 4; ++i) EXPECT_EQ(n.row(i), Eigen::RowVector3d(0, -1, 0));
}

TEST_F(MeshIo, PolylinesBecomeSegments) {
  MeshData curve;
  curve.points.resize(4, 3);
  curve.points << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 1;
  curve.segments.resize(3, 2);
  curve.segments << 0, 1, 1, 2, 2, 3;
  for (const char* ext : {".vtp", ".vtk", ".obj", ".ply"}) {
    SCOPED_TRACE(ext);
    writeMesh(dir_ / (std::string("c") + ext), curve);
    const MeshData back = readMesh(dir_ / (std::string("c") + ext));
    EXPECT_EQ(back.segments, curve.segments);
    EXPECT_EQ(back.triangles.rows(), 0);
  }
}

TEST_F(MeshIo, PointCloudsKeepEveryPoint) {
  MeshData cloud;
  cloud.points = Eigen::MatrixX3d::Random(50, 3);
  for (const char* ext : {".vtp", ".vtk", ".obj", ".ply", ".xyz", ".npy"}) {
    SCOPED_TRACE(ext);
    writeMesh(dir_ / (std::string("p") + ext), cloud);
    const MeshData back = readMesh(dir_ / (std::string("p") + ext));
    ASSERT_EQ(back.points.rows(), 50);
    EXPECT_LE((back.points - cloud.points).cwiseAbs().maxCoeff(), kFloatTolerance);
  }
}

TEST_F(MeshIo, WriteErrorsNameTheProblemAndWriteNothing) {
  auto expectError = [](auto&& call, const std::string& part) {
    try {
      call();
      ADD_FAILURE() << "expected an error containing '" << part << "'";
    } catch (const MeshIoError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  MeshData broken = torus();
  broken.points(3, 1) = std::nan("");
  expectError([&] { writeMesh(dir_ / "out.obj", broken); }, "out.obj: point 3 has a non-finite coordinate");
  broken = torus();
  broken.triangles(5, 0) = 100000;
  expectError([&] { writeMesh(dir_ / "out.ply", broken); }, "out.ply: triangle 5 uses a point index outside 0..");
  expectError([&] { writeMesh(dir_ / "out.gltf", torus()); }, "cannot write format '.gltf'");
  expectError([&] { writeMesh(dir_ / "out.3ds", torus()); }, "cannot write format '.3ds'");
  MeshData cloud;
  cloud.points = Eigen::MatrixX3d::Zero(3, 3);
  expectError([&] { writeMesh(dir_ / "out.stl", cloud); }, "out.stl: STL needs triangles");
  expectError([&] { writeMesh(dir_ / "missing-folder" / "out.ply", torus()); }, "cannot write (create temporary file");
  EXPECT_EQ(filesInDir(), 0);
}

TEST_F(MeshIo, AFailedWriteLeavesTheExistingFileUntouched) {
  const auto path = dir_ / "keep.xyz";
  std::ofstream(path) << "1 2 3\n";
  EXPECT_THROW(writeMesh(path, MeshData{}), MeshIoError);
  EXPECT_EQ(readMesh(path).points.rows(), 1);
  EXPECT_EQ(filesInDir(), 1);
}

TEST_F(MeshIo, ReadErrorsForMissingFilesAndUnknownFormats) {
  try {
    readMesh(dir_ / "missing.obj");
    FAIL();
  } catch (const MeshIoError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.obj: no such file"), std::string::npos) << e.what();
  }
  try {
    readMesh(dir_ / "x.3ds");
    FAIL();
  } catch (const MeshIoError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown mesh format '.3ds' (reads .obj .ply .stl .xyz .npy .gltf .glb .vtp .vtk)"),
              std::string::npos)
        << e.what();
  }
}

// A GLB whose BIN chunk declares 4 bytes more than the file holds (found by fuzz_mesh_glb:
// tinygltf copied the chunk by its declared length, a heap over-read): a located error.
TEST(GlbLayout, AChunkPastTheEndOfTheFileIsALocatedError) {
  std::ifstream in(std::filesystem::path(FFDKIT_SOURCE_DIR) / "tests/fuzz/regressions/fuzz_mesh_glb/bin-chunk-past-the-end.glb",
                   std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), 816u);
  try {
    readMeshBytes(bytes, MeshFormat::Glb, "tool.glb");
    FAIL() << "read";
  } catch (const MeshIoError& e) {
    EXPECT_STREQ(e.what(), "tool.glb: GLB chunk 1 at byte 640 declares 172 bytes, 168 are left");
  }
}

}  // namespace
}  // namespace ffdkit::meshio
