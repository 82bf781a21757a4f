// Issue 32's defect classes in the mesh readers and writers, each with the issue's own example
// built as a real file (hostile_files.h) and the other formats where the class applies:
// unset columns, writers that write what the readers refuse, amplification (instancing,
// aliasing), paths outside the file's folder, and silent drops.
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include "ffdkit/meshio/mesh_io.h"
#include "ffdkit/meshio/vertex_slices.h"
#include "hostile_files.h"

namespace ffdkit::meshio {
namespace {

namespace fs = std::filesystem;
using test::appendLittleEndian;

std::string hostileErrorOf(const std::string& bytes, MeshFormat format, const MeshReadOptions& options = {}) {
  try {
    readMeshBytes(bytes, format, "test", options);
  } catch (const MeshIoError& e) {
    return e.what();
  }
  return "(no error)";
}

#define EXPECT_CONTAINS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

MeshReadOptions limitedTo(std::uint64_t maxPoints, std::uint64_t maxMemoryBytes = std::uint64_t(4) << 30) {
  MeshReadOptions options;
  options.limits.maxPoints = maxPoints;
  options.limits.maxMemoryBytes = maxMemoryBytes;
  return options;
}

class TempFolder {
 public:
  TempFolder() : path_(fs::temp_directory_path() / ("ffdkit-round3-" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempFolder() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// --- 1. A column left to whatever memory held ---------------------------------------------

TEST(HostileRound3, APlyVertexWithXTwiceAndNoZIsRefusedAtItsHeaderLine) {
  const std::string error = hostileErrorOf(test::duplicateCoordinatePly(), MeshFormat::Ply);
  EXPECT_CONTAINS(error, "test:3: element 'vertex': property 'x' is declared twice");
  // Any property named twice, not just coordinates; and each of x, y, z missing on its own.
  EXPECT_CONTAINS(hostileErrorOf(test::plyWithVertexProperties({"x", "y", "z", "red", "red"}), MeshFormat::Ply),
                  "property 'red' is declared twice");
  EXPECT_CONTAINS(hostileErrorOf(test::plyWithVertexProperties({"x", "y", "w"}), MeshFormat::Ply), "needs the properties x, y and z");
  // The same file with z declared reads the values of its records.
  const MeshData m = readMeshBytes(test::plyWithVertexProperties({"x", "y", "z"}), MeshFormat::Ply, "test");
  ASSERT_EQ(m.points.rows(), 3);
  EXPECT_EQ(m.points.row(2), Eigen::RowVector3d(30, 31, 32));
}

// --- 5. Silent drops: every declared element and property is accounted for ------------------

TEST(HostileRound3, APlyWithTwoFaceElementsIsRefusedNotHalfRead) {
  EXPECT_CONTAINS(hostileErrorOf(test::twoFaceElementsPly(), MeshFormat::Ply),
                  "test:9: element 'face': declared a second time (the first is on line 7)");
  // One face element with both triangles reads both.
  const std::string one = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                          "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n"
                          "3 0 1 2\n3 1 3 2\n";
  EXPECT_EQ(readMeshBytes(one, MeshFormat::Ply, "test").triangles.rows(), 2);
}

TEST(HostileRound3, APlyEdgeWithoutVertex2IsRefused) {
  EXPECT_CONTAINS(hostileErrorOf(test::edgeWithoutVertex2Ply(), MeshFormat::Ply),
                  "test:7: element 'edge': needs the properties vertex1 and vertex2 (vertex2 missing)");
  std::string both = test::edgeWithoutVertex2Ply();
  both.replace(both.find("property uchar red"), 18, "property int vertex2");
  both.replace(both.find("0 255\n1 255\n"), 12, "0 1\n1 2\n");
  const MeshData m = readMeshBytes(both, MeshFormat::Ply, "test");
  ASSERT_EQ(m.segments.rows(), 2);
  EXPECT_EQ(m.segments.row(1), Eigen::RowVector2i(1, 2));
}

TEST(HostileRound3, APlyFaceWithoutIndicesOrWithStripsIsRefused) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  EXPECT_CONTAINS(hostileErrorOf(head + "element face 1\nproperty uchar red\nend_header\n0 0 0\n1 0 0\n0 1 0\n7\n", MeshFormat::Ply),
                  "test:7: element 'face': needs a 'vertex_indices' list");
  EXPECT_CONTAINS(hostileErrorOf(head + "element face 1\nproperty list uchar int vertex_indices\nproperty list uchar int vertex_index\n"
                                 "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 3 0 1 2\n",
                          MeshFormat::Ply),
                  "has both 'vertex_indices' and 'vertex_index'");
  EXPECT_CONTAINS(hostileErrorOf(head + "element tristrips 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                                 "3 0 1 2\n",
                          MeshFormat::Ply),
                  "element 'tristrips': triangle strips are not read");
  EXPECT_CONTAINS(hostileErrorOf(head + "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n",
                          MeshFormat::Ply),
                  "element 'vertex': declared a second time");
}

TEST(HostileRound3, LegacyVtkRepeatedSectionsAndShortCellsAreRefused) {
  const std::string head = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n";
  EXPECT_CONTAINS(hostileErrorOf(head + "POLYGONS 1 4\n3 0 1 2\nPOLYGONS 1 4\n3 0 2 1\n", MeshFormat::Vtk), "a second POLYGONS section");
  EXPECT_CONTAINS(hostileErrorOf(head + "POINTS 3 float\n0 0 0 1 0 0 0 1 0\n", MeshFormat::Vtk), "a second POINTS section");
  EXPECT_CONTAINS(hostileErrorOf(head + "POLYGONS 2 7\n3 0 1 2\n2 0 1\n", MeshFormat::Vtk), "polygon 1: needs at least 3 points, it has 2");
  EXPECT_CONTAINS(hostileErrorOf(head + "LINES 1 2\n1 0\n", MeshFormat::Vtk), "line 0: needs at least 2 points, it has 1");
  // POLYGONS and LINES once each read both.
  const MeshData m = readMeshBytes(head + "POLYGONS 1 4\n3 0 1 2\nLINES 1 3\n2 0 1\n", MeshFormat::Vtk, "test");
  EXPECT_EQ(m.triangles.rows(), 1);
  EXPECT_EQ(m.segments.rows(), 1);
}

std::string vtpPiece(const std::string& inside) {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\">\n<PolyData>\n"
         "<Piece NumberOfPoints=\"3\" NumberOfPolys=\"1\">\n" +
         inside + "</Piece>\n</PolyData>\n</VTKFile>\n";
}
const std::string kVtpPoints =
    "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray></Points>\n";
std::string vtpPolys(const std::string& connectivity, const std::string& offsets) {
  return "<Polys><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" + connectivity +
         "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" + offsets + "</DataArray></Polys>\n";
}

TEST(HostileRound3, VtpRepeatedElementsAndShortCellsAreRefused) {
  EXPECT_EQ(readMeshBytes(vtpPiece(kVtpPoints + vtpPolys("0 1 2", "3")), MeshFormat::Vtp, "test").triangles.rows(), 1);
  EXPECT_CONTAINS(hostileErrorOf(vtpPiece(kVtpPoints + kVtpPoints + vtpPolys("0 1 2", "3")), MeshFormat::Vtp),
                  "test:6: Piece: a second <Points> (one is read)");
  EXPECT_CONTAINS(hostileErrorOf(vtpPiece(kVtpPoints + vtpPolys("0 1 2", "3") + vtpPolys("0 2 1", "3")), MeshFormat::Vtp),
                  "Piece: a second <Polys>");
  std::string twoArrays = kVtpPoints;
  twoArrays.insert(twoArrays.find("</Points>"), "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
                                                "5 5 5 6 6 6 7 7 7</DataArray>");
  EXPECT_CONTAINS(hostileErrorOf(vtpPiece(twoArrays + vtpPolys("0 1 2", "3")), MeshFormat::Vtp), "Points: a second DataArray");
  EXPECT_CONTAINS(hostileErrorOf(vtpPiece(kVtpPoints + vtpPolys("0 1", "2")), MeshFormat::Vtp),
                  "polygon 0: needs at least 3 points, it has 2");
}

TEST(HostileRound3, GltfRequiredExtensionsAndMorphWeightsAreRefused) {
  std::string gltf = test::instancedGltf(3, 1, 1);
  std::string required = gltf;
  required.insert(1, R"("extensionsRequired": ["KHR_draco_mesh_compression"], )");
  EXPECT_CONTAINS(hostileErrorOf(required, MeshFormat::Gltf), "requires the extension 'KHR_draco_mesh_compression'");
  std::string morphed = gltf;
  morphed.replace(morphed.find("\"mode\":0}"), 9, "\"mode\":0,\"targets\":[{\"POSITION\":0}]}");
  EXPECT_EQ(readMeshBytes(morphed, MeshFormat::Gltf, "test").points.rows(), 3);  // no weights: the base positions
  morphed.replace(morphed.find("\"primitives\""), 0, "\"weights\": [0.5], ");
  EXPECT_CONTAINS(hostileErrorOf(morphed, MeshFormat::Gltf), "mesh 0: morph target weights would move its points");
}

TEST(HostileRound3, NpyKeysGivenTwiceAreRefused) {
  std::string dict = "{'descr': '<f8', 'shape': (1, 3), 'fortran_order': False, 'shape': (2, 3), }";
  dict.append(118 - 10 - dict.size() - 1, ' ').append("\n");
  std::string b("\x93NUMPY\x01\x00", 8);
  appendLittleEndian(b, std::uint16_t(dict.size()));
  b += dict;
  for (double v : {1.0, 2.0, 3.0, 4.0, 5.0, 6.0}) appendLittleEndian(b, v);
  EXPECT_CONTAINS(hostileErrorOf(b, MeshFormat::Npy), "header: 'shape' is given twice");
}

// --- 2. Writers refuse what their format cannot hold ----------------------------------------

MeshData triangleAt(double x) {
  MeshData m;
  m.points.resize(3, 3);
  m.points << 0, 0, 0, x, 0, 0, 0, 1, 0;
  m.triangles.resize(1, 3);
  m.triangles << 0, 1, 2;
  return m;
}

TEST(HostileRound3, ACoordinateOf1e39IsRefusedByFloatWritersAndKeptExactlyByTheOthers) {
  TempFolder dir;
  const MeshData mesh = triangleAt(1e39);
  for (const char* name : {"out.ply", "out.stl"}) {
    SCOPED_TRACE(name);
    const fs::path path = dir.path() / name;
    try {
      writeMesh(path, mesh);
      ADD_FAILURE() << "written";
    } catch (const MeshIoError& e) {
      EXPECT_CONTAINS(e.what(), path.string() + ": vertex 1 (x) = 1e+39 does not fit the float32 coordinates of binary ");
    }
    EXPECT_FALSE(fs::exists(path));
    EXPECT_TRUE(fs::is_empty(dir.path()));  // no temporary left either
  }
  // ASCII PLY, OBJ, XYZ, NPY, VTP and legacy VTK keep doubles: what they write reads back exactly.
  MeshWriteOptions ascii;
  ascii.plyEncoding = PlyEncoding::Ascii;
  for (const char* name : {"ascii.ply", "out.obj", "out.xyz", "out.npy", "out.vtp", "out.vtk"}) {
    SCOPED_TRACE(name);
    const fs::path path = dir.path() / name;
    const MeshData extreme = [&] {
      MeshData m = triangleAt(1e39);
      m.points(0, 1) = -DBL_MAX;
      m.points(2, 2) = std::numeric_limits<double>::denorm_min();
      return m;
    }();
    writeMesh(path, extreme, std::string(name) == "ascii.ply" ? ascii : MeshWriteOptions{});
    const MeshData back = readMesh(path);
    ASSERT_EQ(back.points.rows(), 3);
    EXPECT_EQ(back.points, extreme.points);
  }
}

TEST(HostileRound3, TheFloat32LimitIsWhereRoundingReachesInfinity) {
  // 2^128 - 2^103 is half way between FLT_MAX and 2^128: it rounds (to even) to infinity, and
  // the largest double below it rounds to FLT_MAX.
  const double limit = std::ldexp(double((1 << 25) - 1), 103);
  const double below = std::nextafter(limit, 0.0);
  ASSERT_EQ(float(below), FLT_MAX);
  for (MeshFormat format : {MeshFormat::Ply, MeshFormat::Stl}) {
    const MeshData back = readMeshBytes(meshFileBytes(triangleAt(-below), format), format, "test");
    EXPECT_EQ(back.points.col(0).minCoeff(), -double(FLT_MAX));
    try {
      meshFileBytes(triangleAt(-limit), format);
      ADD_FAILURE() << "written";
    } catch (const MeshIoError& e) {
      EXPECT_CONTAINS(e.what(), "vertex 1 (x) = -3.4028235677973366e+38 does not fit the float32 coordinates");
    }
  }
  // Sliced PLY writes check the same rule.
  EXPECT_THROW(slicedFileVertices(MeshFormat::Ply, triangleAt(1e39).points), MeshIoError);
}

// --- 3. Amplification: one budget for every reader ------------------------------------------

TEST(HostileRound3, AnInstancedGltfOfAbout50KBAnnouncing100MPointsIsRefusedQuickly) {
  const std::string gltf = test::instancedGltf(1000, 500, 200);
  EXPECT_LT(gltf.size(), 55'000u);
  const auto start = std::chrono::steady_clock::now();
  const std::string error = hostileErrorOf(gltf, MeshFormat::Gltf);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_CONTAINS(error, "test: the scene's nodes instantiate 100000000 points; the most: mesh 0 (500 primitives, 500000 points) "
                         "instanced by 200 nodes: 100000000 points over the read limit of 50000000 points (--max-points)");
  EXPECT_LT(seconds, 2.0);
}

TEST(HostileRound3, ASmallLimitRefusesASmallerInstancedGltfThatTheDefaultReads) {
  const std::string gltf = test::instancedGltf(100, 10, 200);  // 200,000 points
  const MeshData m = readMeshBytes(gltf, MeshFormat::Gltf, "test");
  ASSERT_EQ(m.points.rows(), 200'000);
  // Node n's instances of point k are at (k + n, 0, 0): the last point is node 199's point 99.
  EXPECT_EQ(m.points.row(m.points.rows() - 1), Eigen::RowVector3d(99 + 199, 0, 0));
  EXPECT_CONTAINS(hostileErrorOf(gltf, MeshFormat::Gltf, limitedTo(100'000)),
                  "instanced by 200 nodes: 200000 points over the read limit of 100000 points (--max-points)");
  EXPECT_EQ(readMeshBytes(gltf, MeshFormat::Gltf, "test", limitedTo(200'000)).points.rows(), 200'000);
  EXPECT_CONTAINS(hostileErrorOf(gltf, MeshFormat::Gltf, limitedTo(199'999)), "over the read limit of 199999 points");
}

// One compressed block of `ids` zero Int64 ids, as VTK's zlib compressor lays it out.
std::string zlibBlockOfZeroIds(std::uint32_t ids) {
  const std::string raw(std::size_t(ids) * 8, '\0');
  uLongf size = compressBound(uLong(raw.size()));
  std::string compressed(size, '\0');
  EXPECT_EQ(compress2(reinterpret_cast<Bytef*>(compressed.data()), &size, reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()), 9),
            Z_OK);
  compressed.resize(size);
  std::string block;
  for (std::uint32_t word : {1u, std::uint32_t(raw.size()), std::uint32_t(raw.size()), std::uint32_t(size)})
    appendLittleEndian(block, word);
  return block + compressed;
}

TEST(HostileRound3, VtpPiecesAliasingOneCompressedBlockEachCountInFull) {
  // 8 Mi ids: 64 MiB decompressed from one block of ~65 KB, named by every piece.
  const std::uint32_t ids = 8u << 20;
  const std::string block = zlibBlockOfZeroIds(ids);
  const MeshReadOptions limited = limitedTo(1000, std::uint64_t(200) << 20);
  // Three pieces decode 192 MiB in all (each block freed after its piece): under the limit.
  const std::string three = test::aliasedBlockVtp(3, block, ids);
  EXPECT_LT(three.size(), 80'000u);
  EXPECT_EQ(readMeshBytes(three, MeshFormat::Vtp, "test", limited).points.rows(), 9);
  // A fourth piece decodes the same block again: 256 MiB decoded in this read.
  const std::string error = hostileErrorOf(test::aliasedBlockVtp(4, block, ids), MeshFormat::Vtp, limited);
  EXPECT_CONTAINS(error, "test:");
  EXPECT_CONTAINS(error, ": DataArray \"connectivity\": decoded data (every piece's arrays count, also where they share a block): "
                         "67108864 items of 1 bytes need 64.0 MiB; with what this read holds already (192.0 MiB) that is over the "
                         "read limit of 200.0 MiB (--max-memory)");
}

TEST(HostileRound3, TheBudgetAtExactlyTheLimitPassesAndOneOverFails) {
  // Binary PLY: 3 points (72 bytes) and 1 triangle (12 bytes), charged from the header's counts.
  std::string ply = test::plyHeader("3", "1") + test::threeVertices();
  ply += char(3);
  for (std::int32_t i : {0, 1, 2}) appendLittleEndian(ply, i);
  // OBJ: the same mesh, charged as its sinks grow.
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  for (const auto& [bytes, format] : {std::pair{ply, MeshFormat::Ply}, std::pair{obj, MeshFormat::Obj}}) {
    SCOPED_TRACE(meshFormatExtension(format));
    EXPECT_EQ(readMeshBytes(bytes, format, "test", limitedTo(3, 84)).triangles.rows(), 1);
    EXPECT_CONTAINS(hostileErrorOf(bytes, format, limitedTo(2, 84)), "over the read limit of 2 points (--max-points)");
    EXPECT_CONTAINS(hostileErrorOf(bytes, format, limitedTo(3, 83)), "over the read limit of 83 bytes (--max-memory)");
  }
  // Text formats name the line of the element over the budget.
  EXPECT_CONTAINS(hostileErrorOf(obj, MeshFormat::Obj, limitedTo(2)), "test:3: OBJ vertices: 1 points; with the 2 this read holds");
  EXPECT_CONTAINS(hostileErrorOf("0 0 0\n1 1 1\n# c\n2 2 2\n", MeshFormat::Xyz, limitedTo(2)), "test:4: xyz points");
  // Every reader charges its points: each format's file of 3 points over a limit of 2.
  const MeshData mesh = triangleAt(1.0);
  for (MeshFormat format : {MeshFormat::Ply, MeshFormat::Stl, MeshFormat::Xyz, MeshFormat::Npy, MeshFormat::Vtp, MeshFormat::Vtk}) {
    SCOPED_TRACE(meshFormatExtension(format));
    const std::string bytes = meshFileBytes(mesh, format);
    EXPECT_EQ(readMeshBytes(bytes, format, "test", limitedTo(3)).points.rows(), 3);
    EXPECT_CONTAINS(hostileErrorOf(bytes, format, limitedTo(2)), "over the read limit of 2 points (--max-points)");
  }
}

TEST(HostileRound3, AReadSharesTheBudgetItIsGiven) {
  ReadBudget shared(ReadLimits{std::uint64_t(4) << 30, 5});
  MeshReadOptions options;
  options.budget = &shared;
  const std::string xyz = "0 0 0\n1 1 1\n2 2 2\n";
  EXPECT_EQ(readMeshBytes(xyz, MeshFormat::Xyz, "a.xyz", options).points.rows(), 3);
  EXPECT_EQ(shared.pointsCharged(), 3u);
  // The second read's first guess takes the 2 points left; its third point is one too many.
  const std::string error = hostileErrorOf(xyz, MeshFormat::Xyz, options);
  EXPECT_CONTAINS(error, "test:3: xyz points: 1 points; with the 5 this read holds already that is over the read limit of 5 points");
}

TEST(HostileRound3, SlicesReadAgainstTheReadersLimits) {
  TempFolder dir;
  const fs::path path = dir.path() / "triangle.ply";
  writeMesh(path, triangleAt(1.0));
  const VertexSliceReader reader(path, ReadLimits{std::uint64_t(4) << 30, 2});
  EXPECT_EQ(reader.readVertices(0, 2).rows(), 2);
  try {
    reader.readVertices(2, 3);
    ADD_FAILURE() << "read";
  } catch (const MeshIoError& e) {
    EXPECT_CONTAINS(e.what(), path.string() + ": vertices 2..3: 1 points; with the 2 this read holds already that is over the read "
                                              "limit of 2 points (--max-points)");
  }
}

// A failed allocation leaves a reader as its documented error. The child process gets an
// address-space limit a little above what it uses, and a read whose budget allows far more:
// the instanced glTF's 100M points (2.4 GB) cannot be allocated.
TEST(HostileRound3, AFailedAllocationIsAMeshIoError) {
#ifdef FFDKIT_ASAN
  GTEST_SKIP() << "AddressSanitizer reserves its shadow memory up front and reports a failed allocation itself";
#endif
  const std::string gltf = test::instancedGltf(1000, 500, 200);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    long pages = 0;
    std::ifstream("/proc/self/statm") >> pages;
    const rlim_t used = rlim_t(pages) * rlim_t(::sysconf(_SC_PAGESIZE));
    const rlimit limit{used + (rlim_t(512) << 20), used + (rlim_t(512) << 20)};
    if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(3);
    try {
      readMeshBytes(gltf, MeshFormat::Gltf, "test", limitedTo(std::uint64_t(1) << 40, std::uint64_t(1) << 50));
    } catch (const MeshIoError& e) {
      ::_exit(std::string(e.what()).find("test: out of memory while reading") == 0 ? 0 : 4);
    } catch (...) {
      ::_exit(5);
    }
    ::_exit(6);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "the child died of signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0) << "3: setrlimit failed, 4: another MeshIoError, 5: another exception, 6: read";
}

// --- 4. Every path a glTF names goes through the confinement rule -----------------------------

TEST(HostileRound3, AGltfBufferOutsideItsFolderIsRefusedWithoutQuotingIt) {
  TempFolder dir;
  fs::create_directories(dir.path() / "shared");
  std::ofstream(dir.path() / "secret.bin", std::ios::binary) << "hunter2 hunter2 hunter2 hunter2 hunter2 ";  // 40 bytes
  std::string triangle;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) appendLittleEndian(triangle, v);
  std::ofstream(dir.path() / "shared" / "inside.bin", std::ios::binary) << triangle;
  const auto gltf = [](const std::string& uri, int length) {
    return R"({"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"byteLength": )" +
           std::to_string(length) + R"(, "uri": ")" + uri + R"("}]})";
  };
  const fs::path outside = dir.path() / "shared" / "outside.gltf";
  std::ofstream(outside) << gltf("../secret.bin", 40);
  try {
    readMesh(outside);
    ADD_FAILURE() << "read";
  } catch (const MeshIoError& e) {
    EXPECT_CONTAINS(e.what(), outside.string() + ": external file '../secret.bin' is outside the folder of the file that names it");
    EXPECT_CONTAINS(e.what(), "--allow-outside");
    EXPECT_EQ(std::string(e.what()).find("hunter2"), std::string::npos) << e.what();
  }
  // The explicit opt-out reads it (and the buffer's bytes, as floats, are finite).
  MeshReadOptions allow;
  allow.confinement.allowOutside = true;
  EXPECT_EQ(readMesh(outside, allow).points.rows(), 3);
  // A buffer inside the folder is read; the same file from a stream names no file.
  const fs::path inside = dir.path() / "shared" / "inside.gltf";
  std::ofstream(inside) << gltf("inside.bin", 36);
  EXPECT_EQ(readMesh(inside).points.row(1), Eigen::RowVector3d(1, 0, 0));
  std::ifstream stream(inside);
  try {
    readMesh(stream, MeshFormat::Gltf, "stream");
    ADD_FAILURE() << "read";
  } catch (const MeshIoError& e) {
    EXPECT_CONTAINS(e.what(), "stream: external file 'inside.bin': a glTF read from a stream or from memory cannot name other files");
  }
  // The external buffer is charged to the read's budget before it is read.
  EXPECT_CONTAINS([&] {
    try {
      readMesh(inside, limitedTo(1000, 35));
    } catch (const MeshIoError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  }(), "external file 'inside.bin': 36 items of 1 bytes need 36 bytes, over the read limit of 35 bytes");
}

}  // namespace
}  // namespace ffdkit::meshio
