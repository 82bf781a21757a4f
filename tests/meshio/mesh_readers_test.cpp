// Each reader on small hand-written files whose content is known, and on bad files: every error
// names the file, the element and (text formats) the line.
#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ffdkit/meshio/mesh_io.h"
#include "hostile_files.h"

namespace ffdkit::meshio {
namespace {

MeshData readBytes(const std::string& bytes, MeshFormat format) { return readMeshBytes(bytes, format, "test"); }

std::string readerErrorOf(const std::string& bytes, MeshFormat format, const std::string& name = "test") {
  try {
    readMeshBytes(bytes, format, name);
  } catch (const MeshIoError& e) {
    return e.what();
  }
  return "(no error)";
}

#define EXPECT_ERROR(bytes, format, part) EXPECT_NE(readerErrorOf(bytes, format).find(part), std::string::npos) << readerErrorOf(bytes, format)

TEST(PlyReader, ReadsAnAsciiQuadAsTwoFanTriangles) {
  const MeshData m = readBytes(
      "ply\r\nformat ascii 1.0\r\ncomment a square\r\nelement vertex 4\r\nproperty float x\r\nproperty float y\r\n"
      "property float z\r\nproperty uchar red\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\n"
      "end_header\r\n0 0 0 255\r\n1 0 0 255\r\n1 1 0 255\r\n0 1 0.5 255\r\n4 0 1 2 3\r\n",
      MeshFormat::Ply);
  ASSERT_EQ(m.points.rows(), 4);
  EXPECT_EQ(m.points.row(3), Eigen::RowVector3d(0, 1, 0.5));
  ASSERT_EQ(m.triangles.rows(), 2);
  EXPECT_EQ(m.triangles.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(m.triangles.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_FALSE(m.hasNormals);
}

TEST(PlyReader, ReadsBigEndianDoublesAndSkipsOtherElements) {
  std::string b =
      "ply\nformat binary_big_endian 1.0\nelement material 1\nproperty list ushort float weights\n"
      "element vertex 3\nproperty double x\nproperty double y\nproperty double z\nproperty float nx\nproperty float ny\n"
      "property float nz\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  auto putBig = [&](auto v) {
    char raw[sizeof v];
    std::memcpy(raw, &v, sizeof v);
    for (int k = int(sizeof v) - 1; k >= 0; --k) b += raw[k];
  };
  putBig(std::uint16_t(2));
  putBig(0.5f);
  putBig(0.25f);
  for (double v : {1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0}) {
    putBig(v);
    if (v == 3.0 || v == 6.0 || v == 9.0) for (int k = 0; k < 3; ++k) putBig(0.0f);
  }
  b += char(3);
  for (std::uint32_t i : {2u, 1u, 0u}) putBig(i);
  const MeshData m = readBytes(b, MeshFormat::Ply);
  EXPECT_EQ(m.points.row(1), Eigen::RowVector3d(4, 5, 6));
  EXPECT_EQ(m.triangles.row(0), Eigen::RowVector3i(2, 1, 0));
  EXPECT_TRUE(m.hasNormals);
}

TEST(PlyReader, RejectsBadHeadersCountsAndValues) {
  EXPECT_ERROR("", MeshFormat::Ply, "not a PLY file");
  EXPECT_ERROR("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", MeshFormat::Ply, "no 'end_header'");
  EXPECT_ERROR("ply\nformat ascii 2.0\n", MeshFormat::Ply, "test:2: format: only PLY version 1.0");
  EXPECT_ERROR("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n", MeshFormat::Ply,
               "needs the properties x, y and z");
  // Line 8 is the first data line.
  EXPECT_ERROR("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 nan\n",
               MeshFormat::Ply, "test:8: vertex 0 (z): non-finite number 'nan'");
  EXPECT_ERROR("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n4 5   \n",
               MeshFormat::Ply, "test:10: vertex 1 (z): the file ends early");
  EXPECT_ERROR("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n4 5\n",
               MeshFormat::Ply, "test:3: element 'vertex' announces 2 items of at least 6 bytes, the file has 11 bytes of data left");
  EXPECT_ERROR("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3 4\n",
               MeshFormat::Ply, "test:8: vertex 0: unexpected '4'");
  EXPECT_ERROR("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n7\n",
               MeshFormat::Ply, "test:9: data after the last element");
  // Over-long binary data and a binary NaN.
  std::string b = test::plyHeader("3", "0") + test::threeVertices();
  EXPECT_EQ(readBytes(b, MeshFormat::Ply).points.rows(), 3);
  EXPECT_ERROR(b + "x", MeshFormat::Ply, "1 bytes after the last element");
  b.replace(b.size() - 4, 4, std::string("\x00\x00\xc0\x7f", 4));
  EXPECT_ERROR(b, MeshFormat::Ply, "vertex 2 (z): non-finite number");
  EXPECT_ERROR(test::plyHeader("3", "0") + test::threeVertices().substr(0, 30), MeshFormat::Ply, "announces 3 items of at least 12 bytes");
}

// Binary faces: runs of triangles are read as 13-byte records, anything else face by face. A file
// of 5,000 faces with quads and pentagons among the triangles must give the fan triangles in
// order, and a bad face anywhere (an index out of range, negative, a count under 3, a list cut
// by the end of the file) the message that names it.
TEST(PlyReader, BinaryTriangleRunsMixedWithPolygonsAndBadFacesAnywhere) {
  const int vertices = 3;
  std::vector<std::vector<std::int32_t>> faces;
  for (int f = 0; f < 5000; ++f) {
    if (f % 997 == 5) faces.push_back({0, 1, 2, 1});
    else if (f % 1499 == 7) faces.push_back({2, 1, 0, 1, 2});
    else faces.push_back({f % 3, (f + 1) % 3, (f + 2) % 3});
  }
  auto file = [&](const std::vector<std::vector<std::int32_t>>& list) {
    std::string b = test::plyHeader("3", std::to_string(list.size())) + test::threeVertices();
    for (const auto& face : list) {
      b += char(face.size());
      for (std::int32_t i : face) test::appendLittleEndian(b, i);
    }
    return b;
  };
  std::vector<std::array<int, 3>> expected;
  for (const auto& face : faces)
    for (std::size_t k = 1; k + 1 < face.size(); ++k) expected.push_back({face[0], face[k], face[k + 1]});
  const MeshData mesh = readBytes(file(faces), MeshFormat::Ply);
  ASSERT_EQ(mesh.triangles.rows(), Eigen::Index(expected.size()));
  for (std::size_t t = 0; t < expected.size(); ++t)
    ASSERT_TRUE(mesh.triangles(Eigen::Index(t), 0) == expected[t][0] && mesh.triangles(Eigen::Index(t), 1) == expected[t][1] &&
                mesh.triangles(Eigen::Index(t), 2) == expected[t][2])
        << "triangle " << t;
  for (int bad : {0, 1, 2500, 4999}) {
    SCOPED_TRACE("bad face " + std::to_string(bad));
    auto broken = faces;
    broken[std::size_t(bad)] = {0, vertices, 1};
    EXPECT_ERROR(file(broken), MeshFormat::Ply, "face " + std::to_string(bad) + ": vertex index 3 is outside 0..2");
    broken[std::size_t(bad)] = {0, 1, -7};
    EXPECT_ERROR(file(broken), MeshFormat::Ply, "face " + std::to_string(bad) + ": vertex index -7 is outside 0..2");
    broken[std::size_t(bad)] = {0, 1};
    EXPECT_ERROR(file(broken), MeshFormat::Ply, "face " + std::to_string(bad) + ": a face needs at least 3 vertices, it has 2");
  }
  const std::string whole = file(faces);
  EXPECT_ERROR(whole.substr(0, whole.size() - 2), MeshFormat::Ply, "face 4999 (vertex_indices): a list of 3 values runs past the end");
}

TEST(ObjReader, ReadsRelativeAndSlashedReferencesAndLines) {
  const MeshData m = readBytes(
      "# a quad and a line\nmtllib x.mtl\no quad\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
      "usemtl red\ns off\nf 1/1/1 2//1 -2 -1/1\nl 1 3 4\n",
      MeshFormat::Obj);
  ASSERT_EQ(m.points.rows(), 4);
  ASSERT_EQ(m.triangles.rows(), 2);
  EXPECT_EQ(m.triangles.row(1), Eigen::RowVector3i(0, 2, 3));
  ASSERT_EQ(m.segments.rows(), 2);
  EXPECT_EQ(m.segments.row(1), Eigen::RowVector2i(2, 3));
  EXPECT_TRUE(m.hasNormals);
}

TEST(ObjReader, RejectsBadStatementsAndReferences) {
  EXPECT_ERROR("v 0 0 0\nv 1 0 0\nf 1 2\n", MeshFormat::Obj, "test:3: face 0: a face needs at least 3 vertices, it has 2");
  EXPECT_ERROR("v 0 0 0\nf 1 2 3\n", MeshFormat::Obj, "test:2: face 0: vertex index 2 is outside 1..1");
  EXPECT_ERROR("v 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 2 -4\n", MeshFormat::Obj, "test:4: face 0: vertex index -4 is outside");
  EXPECT_ERROR("v 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 2 0\n", MeshFormat::Obj, "vertex index 0 is outside");
  EXPECT_ERROR("v 0 0 0\nv 0 0\n", MeshFormat::Obj, "test:2: vertex 1: expected a number");
  EXPECT_ERROR("v 0 0 0 1 2 3 4\n", MeshFormat::Obj, "test:1: vertex 0: unexpected '4'");
  EXPECT_ERROR("v 1e999 0 0\n", MeshFormat::Obj, "non-finite number '1e999'");
  EXPECT_ERROR("v 0 0 0\nbogus 1\n", MeshFormat::Obj, "test:2: unknown statement 'bogus'");
  EXPECT_ERROR("v 0 0 0\nv 0 0 0\nv 0 0 0\nf 1/x 2 3\n", MeshFormat::Obj, "malformed vertex reference '1/x'");
  EXPECT_ERROR("# nothing\n", MeshFormat::Obj, "the file has no vertices");
}

TEST(StlReader, MergesSharedCornersOfAnAsciiFile) {
  const MeshData m = readBytes(
      "solid square\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 1 1 0\n  endloop\n endfacet\n"
      " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 1 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid square\n",
      MeshFormat::Stl);
  EXPECT_EQ(m.points.rows(), 4);
  ASSERT_EQ(m.triangles.rows(), 2);
  EXPECT_EQ(m.triangles.row(1), Eigen::RowVector3i(0, 2, 3));
}

TEST(StlReader, RejectsTruncatedAndMalformedFiles) {
  EXPECT_ERROR("solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n endloop\n", MeshFormat::Stl,
               "test:6: triangle 0: expected 'vertex'");
  EXPECT_ERROR("solid x\n facet normal 0 0 nan\n", MeshFormat::Stl, "test:2: triangle 0: non-finite number 'nan'");
  EXPECT_ERROR("solid x\nendsolid x\n", MeshFormat::Stl, "the file has no triangles");
  EXPECT_ERROR(std::string(30, 'x'), MeshFormat::Stl, "truncated: header needs 84 bytes");
  std::string b(80, ' ');
  test::appendLittleEndian(b, std::uint32_t(1));
  b.append(50, '\0');
  EXPECT_EQ(readBytes(b, MeshFormat::Stl).triangles.rows(), 1);
  EXPECT_ERROR(b + "xx", MeshFormat::Stl, "announces 1 triangles (134 bytes), the file has 136 bytes");
}

TEST(XyzReader, ReadsPointsWithCommentsAndRejectsBadLines) {
  const MeshData m = readBytes("# cloud\n1 2 3\n\n  -4.5e2\t+5 6 # trailing\r\n", MeshFormat::Xyz);
  ASSERT_EQ(m.points.rows(), 2);
  EXPECT_EQ(m.points.row(1), Eigen::RowVector3d(-450, 5, 6));
  EXPECT_ERROR("1 2 3\n4 five 6\n", MeshFormat::Xyz, "test:2: point 1: expected a number, got 'five'");
  EXPECT_ERROR("1 2 nan\n", MeshFormat::Xyz, "test:1: point 0: non-finite number 'nan'");
  EXPECT_ERROR("1 2\n", MeshFormat::Xyz, "test:1: point 0: expected a number");
  EXPECT_ERROR("1 2 3 4\n", MeshFormat::Xyz, "test:1: point 0: expected three numbers");
  EXPECT_ERROR("\n# only a comment\n", MeshFormat::Xyz, "the file has no points");
}

std::string npy(const std::string& dict, const std::string& data) {
  std::string header = dict;
  header.append((64 - (10 + header.size() + 1) % 64) % 64, ' ').append("\n");
  std::string out("\x93NUMPY\x01\x00", 8);
  test::appendLittleEndian(out, std::uint16_t(header.size()));
  return out + header + data;
}

TEST(NpyReader, ReadsCAndFortranOrderAndRejectsBadShapes) {
  std::string data;
  for (float v : {1.f, 2.f, 3.f, 4.f, 5.f, 6.f}) test::appendLittleEndian(data, v);
  const MeshData c = readBytes(npy("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }", data), MeshFormat::Npy);
  EXPECT_EQ(c.points.row(1), Eigen::RowVector3d(4, 5, 6));
  const MeshData f = readBytes(npy("{'fortran_order': True, 'descr': '<f4', 'shape': (2, 3)}", data), MeshFormat::Npy);
  EXPECT_EQ(f.points.row(1), Eigen::RowVector3d(2, 4, 6));  // column by column
  EXPECT_ERROR(npy("{'descr': '<f4', 'fortran_order': False, 'shape': (3, 3), }", data), MeshFormat::Npy,
               "shape (3, 3) needs 36 bytes of data, the file has 24");
  EXPECT_ERROR(npy("{'descr': '<f4', 'fortran_order': False, 'shape': (6,), }", data), MeshFormat::Npy, "shape (N, 3)");
  EXPECT_ERROR(npy("{'descr': '<i4', 'fortran_order': False, 'shape': (2, 3), }", data), MeshFormat::Npy, "dtype '<i4'");
  EXPECT_ERROR(npy("{'descr': '<f4', 'fortran_order': False, 'shape': (4000000000, 3), }", data), MeshFormat::Npy,
               "needs 48000000000 bytes");
  EXPECT_ERROR("\x93NUMPY\x01", MeshFormat::Npy, "truncated");
}

TEST(GltfReader, AppliesNodeTransformsAndReadsIndices) {
  const std::string gltf = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"children": [1], "translation": [10, 0, 0]}, {"mesh": 0, "scale": [2, 2, 2]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}]})";
  const MeshData m = readBytes(gltf, MeshFormat::Gltf);
  ASSERT_EQ(m.points.rows(), 3);
  EXPECT_EQ(m.points.row(1), Eigen::RowVector3d(12, 0, 0));  // translate(scale(1, 0, 0))
  EXPECT_EQ(m.points.row(2), Eigen::RowVector3d(10, 2, 0));
  EXPECT_EQ(m.triangles.row(0), Eigen::RowVector3i(0, 1, 2));

  std::string bad = gltf;
  bad.replace(bad.find(R"("count": 3, "type": "SCALAR")"), 10, R"("count": 4)");
  EXPECT_ERROR(bad, MeshFormat::Gltf, "run past buffer view 1 of 6 bytes");
  bad = gltf;
  bad.replace(bad.find("AAABAAIAAAA="), 12, "AAABAAkAAAA=");  // index 2 -> 9
  EXPECT_ERROR(bad, MeshFormat::Gltf, "index 2 is 9, outside 0..2");
  bad = gltf;
  bad.replace(bad.find(R"("children": [1])"), 15, R"("children": [0])");
  EXPECT_ERROR(bad, MeshFormat::Gltf, "node 0 is reached twice");
  EXPECT_ERROR("{ not json", MeshFormat::Gltf, "cannot read glTF");
}

TEST(GltfReader, RefusesExternalBuffersFromAStream) {
  const std::string gltf = R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 36, "uri": "../../secret.bin"}]})";
  EXPECT_ERROR(gltf, MeshFormat::Gltf, "test: external file '../../secret.bin': a glTF read from a stream or from memory cannot name");
}

TEST(LegacyVtkReader, ReadsAndChecksCellsPointsAndCounts) {
  const std::string legacy =
      "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n3 0 1 7\n";
  EXPECT_ERROR(legacy, MeshFormat::Vtk, "polygon 0: point id 7 is outside 0..2");
  std::string good = legacy;
  good.replace(good.find("3 0 1 7"), 7, "3 0 1 2");
  EXPECT_EQ(readBytes(good, MeshFormat::Vtk).triangles.row(0), Eigen::RowVector3i(0, 1, 2));
  std::string nan = good;
  nan.replace(nan.find("0 1 0\n"), 6, "0 nan 0\n");
  EXPECT_ERROR(nan, MeshFormat::Vtk, "test:6: point 2: non-finite number 'nan'");
  std::string binary = "# vtk DataFile Version 3.0\nx\nBINARY\nDATASET POLYDATA\nPOINTS 3 float\n";
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, std::numeric_limits<float>::quiet_NaN(), 0.f}) {
    char raw[4];
    std::memcpy(raw, &v, 4);
    for (int k = 3; k >= 0; --k) binary += raw[k];
  }
  binary += "\n";
  EXPECT_ERROR(binary, MeshFormat::Vtk, "point 2: non-finite coordinate");
  // A cell count past its list (this crashed VTK's legacy reader under fuzzing).
  std::string past = good;
  past.replace(past.find("3 0 1 2"), 7, "9 0 1 2");
  EXPECT_ERROR(past, MeshFormat::Vtk, "polygon 0: 9 points run past the cell list");
  std::string huge = good;
  huge.replace(huge.find("POINTS 3"), 8, "POINTS 300000000");
  EXPECT_ERROR(huge, MeshFormat::Vtk, "POINTS: 300000000 points do not fit");
  EXPECT_ERROR("# vtk DataFile Version 3.0\nx\nASCII\nDATASET STRUCTURED_POINTS\n", MeshFormat::Vtk, "only POLYDATA");
}

TEST(HostileFiles, EveryFileOfTheIssueTableGetsItsError) {
  for (const auto& file : test::hostileFiles()) {
    SCOPED_TRACE(file.name);
    const auto format = meshFormatOf(file.name);
    ASSERT_TRUE(format.has_value());
    const std::string error = readerErrorOf(file.bytes, *format, file.name);
    EXPECT_NE(error.find(file.name), std::string::npos) << error;
    EXPECT_NE(error.find(file.expected), std::string::npos) << error;
  }
}

}  // namespace
}  // namespace ffdkit::meshio
