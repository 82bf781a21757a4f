// Reading a file in slices gives the points, cells and messages of readMesh on the whole file;
// writing in slices gives the bytes of meshFileBytes.
#include "ffdkit/meshio/vertex_slices.h"

#include <cstring>
#include <filesystem>
#include <limits>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "ffdkit/meshio/mesh_io.h"
#include "ffdkit/scenes/primitive.h"

namespace ffdkit::meshio {
namespace {

class VertexSlices : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("ffdkit-vertex-slices-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  /// A torus with a few hundred points, written as `ext`.
  std::filesystem::path torusFile(const std::string& ext) const {
    const auto torus = scenes::makePrimitive({.kind = scenes::PrimitiveKind::Torus, .resolution = 12});
    const auto path = dir_ / ("torus" + ext);
    writeMesh(path, MeshData{torus.vertices, torus.triangles, {}, false});
    return path;
  }
  std::filesystem::path write(const std::string& name, const std::string& bytes) const {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  std::filesystem::path dir_;
};

std::string fileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The points of parts 0..parts-1 stacked, as the ranks of a batch read them.
Eigen::MatrixX3d readInParts(const VertexSliceReader& reader, int parts) {
  std::vector<Eigen::MatrixX3d> slices;
  Eigen::Index rows = 0;
  std::int64_t lines = 0, points = 0;
  for (int part = 0; part < parts; ++part) {
    if (const auto n = reader.vertexCount()) {
      slices.push_back(reader.readVertices(part * *n / parts, (part + 1) * *n / parts));
    } else {
      const auto text = reader.readXyzPart(part, parts);
      slices.push_back(reader.parseXyzPart(text, lines, points));
      lines += text.lines;
      points += text.points;
      EXPECT_EQ(slices.back().rows(), text.points);
    }
    rows += slices.back().rows();
  }
  Eigen::MatrixX3d all(rows, 3);
  Eigen::Index at = 0;
  for (const auto& slice : slices) {
    all.middleRows(at, slice.rows()) = slice;
    at += slice.rows();
  }
  return all;
}

TEST_F(VertexSlices, PartsStackToThePointsReadMeshReads) {
  for (const std::string ext : {".ply", ".npy", ".xyz"}) {
    SCOPED_TRACE(ext);
    const auto path = torusFile(ext);
    const MeshData whole = readMesh(path);
    const VertexSliceReader reader(path);
    for (int parts : {1, 2, 3, 7, 1000}) {
      SCOPED_TRACE(parts);
      const Eigen::MatrixX3d stacked = readInParts(reader, parts);
      ASSERT_EQ(stacked.rows(), whole.points.rows());
      EXPECT_EQ(stacked, whole.points);  // the same decoding: bit for bit
    }
    const MeshData cells = reader.readCells();
    EXPECT_EQ(cells.points.rows(), 0);
    if (ext == ".ply") {
      EXPECT_EQ(cells.triangles, whole.triangles);
    } else {
      EXPECT_EQ(cells.triangles.rows(), 0);
    }
  }
}

// The cells a batch's first rank reads after its slice count as in a whole read: with every
// vertex of the file (24 bytes each) and the faces (12 bytes a triangle), not only the slice.
// At the memory limit a whole read takes the file reads and the cells read; a byte less, both
// refuse it, however small the slice read before (each rank's slice alone would fit).
TEST_F(VertexSlices, CellsCountWithEveryVertexOfTheFileAsInAWholeRead) {
  const auto path = torusFile(".ply");
  const MeshData whole = readMesh(path);
  const std::uint64_t n = std::uint64_t(whole.points.rows()), t = std::uint64_t(whole.triangles.rows());
  ASSERT_GT(t, 0u);
  const std::uint64_t needed = 24 * n + 12 * t;  // docs/robustness.md, PLY's row of the budget table
  const auto limits = [](std::uint64_t bytes) { return ReadLimits{.maxMemoryBytes = bytes, .maxPoints = 1'000'000}; };
  // readMesh: exactly what it charges.
  EXPECT_EQ(readMesh(path, MeshReadOptions{.limits = limits(needed)}).triangles, whole.triangles);
  EXPECT_THROW(readMesh(path, MeshReadOptions{.limits = limits(needed - 1)}), MeshIoError);
  for (int parts : {1, 2, 8}) {
    SCOPED_TRACE(parts);
    {
      const VertexSliceReader first(path, limits(needed));
      first.readVertices(0, std::int64_t(n) / parts);
      EXPECT_EQ(first.readCells().triangles, whole.triangles);
    }
    const VertexSliceReader first(path, limits(needed - 1));
    first.readVertices(0, std::int64_t(n) / parts);
    try {
      first.readCells();
      ADD_FAILURE() << "the cells read at a limit the whole file is over";
    } catch (const MeshIoError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path.string()), std::string::npos) << message;
      EXPECT_NE(message.find("element 'face'"), std::string::npos) << message;
      EXPECT_NE(message.find("--max-memory"), std::string::npos) << message;
    }
  }
}

TEST_F(VertexSlices, XyzPartsCutAtLineStartsAndNumberLinesAsTheWholeFile) {
  // Lines of very different lengths, comments and blank lines; a bad number on line 9.
  const std::string text = "# points\n0 0 0\n\n1 1 1\n   # x\n2.5 2.5 2.5e0\n3 3 3\n4 4 4\n5 5 oops\n6 6 6\n";
  const auto path = write("p.xyz", text);
  const VertexSliceReader reader(path);
  std::string joined;
  std::int64_t lines = 0, points = 0;
  std::string message;
  for (int part = 0; part < 4; ++part) {
    const auto piece = reader.readXyzPart(part, 4);
    EXPECT_TRUE(piece.text.empty() || joined.empty() || joined.back() == '\n') << "part " << part << " starts mid-line";
    joined += piece.text;
    try {
      reader.parseXyzPart(piece, lines, points);
    } catch (const MeshIoError& e) {
      message = e.what();
    }
    lines += piece.lines;
    points += piece.points;
  }
  EXPECT_EQ(joined, text);
  EXPECT_EQ(lines, 10);
  EXPECT_EQ(points, 7);
  try {
    readMesh(path);
    FAIL() << "the whole file read";
  } catch (const MeshIoError& e) {
    EXPECT_EQ(message, e.what());
  }
  EXPECT_NE(message.find("p.xyz:9: point 5: "), std::string::npos) << message;
}

TEST_F(VertexSlices, ChecksCountsAgainstTheFileSizeAndNamesTheVertexInTheFile) {
  const std::string ply = fileBytes(torusFile(".ply"));
  const std::int64_t n = VertexSliceReader(torusFile(".ply")).vertexCount().value();
  const std::size_t data = ply.find("end_header\n") + 11;
  // Cut inside the vertices: the header's count fails on opening (every rank sees it).
  EXPECT_THROW({ VertexSliceReader reader(write("cut.ply", ply.substr(0, data + std::size_t(n) * 6))); }, MeshIoError);
  // Cut inside the faces: the vertices read, the faces fail with readMesh's message.
  const auto cutPath = write("cut-faces.ply", ply.substr(0, ply.size() - 20));
  std::string whole;
  try {
    readMesh(cutPath);
  } catch (const MeshIoError& e) {
    whole = e.what();
  }
  EXPECT_NE(whole.find("cut-faces.ply: face "), std::string::npos) << whole;
  const VertexSliceReader cutFaces(cutPath);
  EXPECT_NO_THROW(cutFaces.readVertices(0, n));
  try {
    cutFaces.readCells();
    FAIL() << "the cut faces were read";
  } catch (const MeshIoError& e) {
    EXPECT_EQ(e.what(), whole);
  }

  // A NaN in the y of vertex k is reported as vertex k by the slice that holds it.
  const std::int64_t k = n / 2;
  std::string bad = ply;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(bad.data() + data + std::size_t(k) * 12 + 4, &nan, 4);
  const VertexSliceReader reader(write("nan.ply", bad));
  EXPECT_NO_THROW(reader.readVertices(0, k));
  try {
    reader.readVertices(k - 3, n);
    FAIL() << "a NaN was read";
  } catch (const MeshIoError& e) {
    EXPECT_NE(std::string(e.what()).find("nan.ply: vertex " + std::to_string(k) + " (y): non-finite number"), std::string::npos)
        << e.what();
  }
}

TEST_F(VertexSlices, RefusesLayoutsWithoutFixedRecords) {
  const auto path = torusFile(".obj");
  EXPECT_THROW({ VertexSliceReader reader(path); }, MeshIoError);
  const auto ascii = write("a.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                    "property float z\nend_header\n0 0 0\n");
  EXPECT_THROW({ VertexSliceReader reader(ascii); }, MeshIoError);
  const auto faceFirst = write("f.ply", "ply\nformat binary_little_endian 1.0\nelement face 1\n"
                                        "property list uchar int vertex_indices\nelement vertex 3\nproperty float x\n"
                                        "property float y\nproperty float z\nend_header\n" +
                                            std::string(13 + 36, '\0'));
  EXPECT_THROW({ VertexSliceReader reader(faceFirst); }, MeshIoError);
}

TEST_F(VertexSlices, SlicedBytesEqualTheWholeFile) {
  const auto torus = scenes::makePrimitive({.kind = scenes::PrimitiveKind::Torus, .resolution = 12});
  const MeshData mesh{torus.vertices, torus.triangles, {}, false};
  MeshData cells;
  cells.triangles = mesh.triangles;
  for (MeshFormat format : {MeshFormat::Ply, MeshFormat::Npy, MeshFormat::Xyz}) {
    SCOPED_TRACE(std::string(meshFormatExtension(format)));
    ASSERT_TRUE(isSliceWritable(format));
    const Eigen::Index n = mesh.points.rows();
    std::string bytes = slicedFileHead(format, n, cells);
    for (int part = 0; part < 3; ++part)
      bytes += slicedFileVertices(format, mesh.points.middleRows(part * n / 3, (part + 1) * n / 3 - part * n / 3));
    bytes += slicedFileTail(format, cells);
    EXPECT_EQ(bytes, meshFileBytes(mesh, format));
    // The sizes a batch places the slices by (PLY, npy: before writing them).
    if (const auto size = slicedVerticesSize(format, n)) EXPECT_EQ(*size, slicedFileVertices(format, mesh.points).size());
    else EXPECT_EQ(format, MeshFormat::Xyz);
    EXPECT_EQ(slicedTailSize(format, cells), slicedFileTail(format, cells).size());
  }
  EXPECT_FALSE(isSliceWritable(MeshFormat::Obj));
}

}  // namespace
}  // namespace ffdkit::meshio
