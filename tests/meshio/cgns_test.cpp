// The CGNS reader and in-place coordinate writer (meshio/cgns.h) on files the CGNS library itself
// writes in each test: a 2 x 2 x 2 hexahedral block with a boundary face section, a boundary
// condition, a flow solution and a descriptor (so that there is something for the writer to leave
// alone), a MIXED section of prisms and tetrahedra, and a RealSingle zone. CGNS's own tools judge
// the written files: cgnscheck accepts them and cgnsdiff finds no difference but the coordinate
// values.
#include "ffdkit/meshio/cgns.h"

#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include <cgnslib.h>
#include <gtest/gtest.h>

#include "scratch_folder.h"

#include "ffdkit/meshio/mesh_data.h"

namespace ffdkit::meshio {
namespace {

namespace fs = std::filesystem;

// stdout and exit status of a shell command.
std::pair<std::string, int> run(const std::string& command) {
  std::string output;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return {"", -1};
  char buffer[4096];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, n);
  const int status = ::pclose(pipe);
  return {output, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

#define CG(call) ASSERT_EQ((call), CG_OK) << #call << ": " << cg_get_error()

// Node number (1-based) of grid point (i, j, k) of an (n+1)^3 block, x fastest.
int node(int i, int j, int k, int n) { return 1 + i + (n + 1) * (j + (n + 1) * k); }

class Cgns : public testing::ScratchFolderTest {
 protected:
  Cgns() : ScratchFolderTest("cgns") {}

  // The hexahedral block of n^3 cells over [0, 1]^3: points, a HEXA_8 section, a QUAD_4 section
  // of the faces at z = 0 with a wall condition on them, a vertex solution and a descriptor.
  // `badNode`: a connectivity entry replaced by this node number (0: none). RealSingle when `single`.
  fs::path writeBlock(const std::string& name, int n = 2, int badNode = 0, bool single = false) {
    const fs::path path = dir_ / name;
    int fn = 0, B = 0, Z = 0, C = 0, S = 0, BC = 0, F = 0, Fld = 0;
    EXPECT_EQ(cg_open(path.c_str(), CG_MODE_WRITE, &fn), CG_OK) << cg_get_error();
    EXPECT_EQ(cg_base_write(fn, "Base", 3, 3, &B), CG_OK);
    const int points = (n + 1) * (n + 1) * (n + 1), cells = n * n * n;
    cgsize_t size[3] = {points, cells, 0};
    EXPECT_EQ(cg_zone_write(fn, B, "Block", size, CGNS_ENUMV(Unstructured), &Z), CG_OK);
    std::array<std::vector<double>, 3> xyz;
    for (int k = 0; k <= n; ++k)
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          xyz[0].push_back(double(i) / n);
          xyz[1].push_back(double(j) / n + 0.25 * double(i) / n);  // sheared: not all values simple
          xyz[2].push_back(double(k) / n);
        }
    const char* names[3] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
    for (int a = 0; a < 3; ++a) {
      if (single) {
        std::vector<float> f(xyz[a].begin(), xyz[a].end());
        EXPECT_EQ(cg_coord_write(fn, B, Z, CGNS_ENUMV(RealSingle), names[a], f.data(), &C), CG_OK);
      } else {
        EXPECT_EQ(cg_coord_write(fn, B, Z, CGNS_ENUMV(RealDouble), names[a], xyz[a].data(), &C), CG_OK);
      }
    }
    std::vector<cgsize_t> hexa;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          for (int v : {node(i, j, k, n), node(i + 1, j, k, n), node(i + 1, j + 1, k, n), node(i, j + 1, k, n),
                        node(i, j, k + 1, n), node(i + 1, j, k + 1, n), node(i + 1, j + 1, k + 1, n),
                        node(i, j + 1, k + 1, n)})
            hexa.push_back(v);
    if (badNode != 0) hexa[13] = badNode;
    EXPECT_EQ(cg_section_write(fn, B, Z, "Hexa", CGNS_ENUMV(HEXA_8), 1, cells, 0, hexa.data(), &S), CG_OK);
    std::vector<cgsize_t> quads;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int v : {node(i, j, 0, n), node(i, j + 1, 0, n), node(i + 1, j + 1, 0, n), node(i + 1, j, 0, n)})
          quads.push_back(v);
    EXPECT_EQ(cg_section_write(fn, B, Z, "Bottom", CGNS_ENUMV(QUAD_4), cells + 1, cells + n * n, 0, quads.data(), &S),
              CG_OK);
    cgsize_t range[2] = {cells + 1, cells + n * n};
    EXPECT_EQ(cg_boco_write(fn, B, Z, "wall", CGNS_ENUMV(BCWall), CGNS_ENUMV(PointRange), 2, range, &BC), CG_OK);
    EXPECT_EQ(cg_boco_gridlocation_write(fn, B, Z, BC, CGNS_ENUMV(FaceCenter)), CG_OK);
    EXPECT_EQ(cg_sol_write(fn, B, Z, "Solution", CGNS_ENUMV(Vertex), &F), CG_OK);
    std::vector<double> pressure(static_cast<std::size_t>(points));
    for (int p = 0; p < points; ++p) pressure[std::size_t(p)] = 1e5 + p;
    EXPECT_EQ(cg_field_write(fn, B, Z, F, CGNS_ENUMV(RealDouble), "Pressure", pressure.data(), &Fld), CG_OK);
    EXPECT_EQ(cg_goto(fn, B, "end"), CG_OK);
    EXPECT_EQ(cg_descriptor_write("Origin", "made by the CGNS library for ffdkit's tests"), CG_OK);
    EXPECT_EQ(cg_close(fn), CG_OK);
    return path;
  }
};

TEST_F(Cgns, ReadsTheCoordinatesAndTheHexahedraOfABlock) {
  ASSERT_TRUE(cgnsSupported());
  const CgnsMesh mesh = readCgnsMesh(writeBlock("block.cgns"));
  EXPECT_EQ(mesh.zoneName, "Block");
  ASSERT_EQ(mesh.points.rows(), 27);
  EXPECT_EQ(mesh.points.row(0), Eigen::RowVector3d(0, 0, 0));
  EXPECT_EQ(mesh.points.row(26), Eigen::RowVector3d(1, 1.25, 1));
  EXPECT_EQ(mesh.points.row(5), Eigen::RowVector3d(1, 0.5 + 0.25, 0));  // i = 2, j = 1, k = 0
  ASSERT_EQ(mesh.cells.cellCount(), 8);
  EXPECT_EQ(mesh.boundaryElements, 4);
  EXPECT_EQ(mesh.cells.shapes[0], CellShape::Hexahedron);
  EXPECT_EQ(mesh.cells.ids.front(), 1);
  const ElementQuality quality = checkElementCells(mesh.points, mesh.cells);
  EXPECT_TRUE(quality.ok()) << badElementsText(quality);
  EXPECT_NEAR(quality.totalVolume, 1.0, 1e-12);  // a shear keeps the volume
}

TEST_F(Cgns, WritesOnlyTheCoordinatesAndCgnsToolsAcceptTheFile) {
  const fs::path in = writeBlock("block.cgns");
  const CgnsMesh mesh = readCgnsMesh(in);
  Eigen::MatrixX3d moved = mesh.points;
  for (Eigen::Index i = 0; i < moved.rows(); ++i) moved.row(i) += Eigen::RowVector3d(0.1, 0.05 * moved(i, 2), 1.0 / 3.0);
  const fs::path out = dir_ / "moved.cgns";
  writeCgnsMesh(mesh, moved, out, {.durable = false});
  const CgnsMesh back = readCgnsMesh(out);
  EXPECT_EQ(back.points, moved);  // exactly: RealDouble in place
  EXPECT_EQ(back.cells.corners, mesh.cells.corners);
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_NE(entry.path().filename().string()[0], '.') << entry.path();

  // The same tree, node for node; with the data compared, only the three coordinate arrays differ.
  const auto [structure, structureStatus] = run("cgnsdiff " + in.string() + " " + out.string());
  EXPECT_EQ(structureStatus, 0) << structure;
  EXPECT_EQ(structure, "") << structure;
  const auto [data, dataStatus] = run("cgnsdiff -d " + in.string() + " " + out.string());
  std::istringstream lines(data);
  std::string line;
  int differences = 0;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    ++differences;
    EXPECT_NE(line.find("/Base/Block/GridCoordinates/Coordinate"), std::string::npos) << line;
  }
  EXPECT_EQ(differences, 3) << data;
  const auto [check, checkStatus] = run("cgnscheck " + out.string());
  EXPECT_EQ(checkStatus, 0) << check;
  EXPECT_EQ(check.find("ERROR"), std::string::npos) << check;
}

TEST_F(Cgns, RealSingleCoordinatesStaySingle) {
  const CgnsMesh mesh = readCgnsMesh(writeBlock("single.cgns", 2, 0, true));
  EXPECT_TRUE(mesh.singlePrecision[0] && mesh.singlePrecision[1] && mesh.singlePrecision[2]);
  const Eigen::MatrixX3d moved = mesh.points * 1.1;
  writeCgnsMesh(mesh, moved, dir_ / "out.cgns", {.durable = false});
  const CgnsMesh back = readCgnsMesh(dir_ / "out.cgns");
  EXPECT_TRUE(back.singlePrecision[2]);
  EXPECT_EQ(back.points, moved.cast<float>().cast<double>());
  Eigen::MatrixX3d huge = mesh.points;
  huge(4, 1) = 1e300;
  const std::string message = testing::meshIoErrorOf([&] { writeCgnsMesh(mesh, huge, dir_ / "huge.cgns"); });
  EXPECT_NE(message.find("vertex 5: CoordinateY"), std::string::npos) << message;
  EXPECT_NE(message.find("RealSingle"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(dir_ / "huge.cgns"));
}

TEST_F(Cgns, FoldedCellsAreFoundByTheElementCheck) {
  const CgnsMesh mesh = readCgnsMesh(writeBlock("block.cgns"));
  Eigen::MatrixX3d folded = mesh.points;
  // The centre point below the bottom: the 4 cells under it (elements 1-4, the bottom layer) turn
  // inside out; the 4 above are stretched down but keep positive corner Jacobians.
  folded(node(1, 1, 1, 2) - 1, 2) = -0.8;
  const ElementQuality quality = checkElementCells(folded, mesh.cells);
  EXPECT_EQ(quality.badCells, 4) << badElementsText(quality);
  EXPECT_EQ(quality.firstBadCells, (std::vector<std::int64_t>{1, 2, 3, 4}));  // CGNS element numbers
}

TEST_F(Cgns, MixedSectionsOfPrismsAndTetrahedra) {
  const fs::path path = dir_ / "mixed.cgns";
  int fn = 0, B = 0, Z = 0, C = 0, S = 0;
  CG(cg_open(path.c_str(), CG_MODE_WRITE, &fn));
  CG(cg_base_write(fn, "Base", 3, 3, &B));
  cgsize_t size[3] = {7, 2, 0};
  CG(cg_zone_write(fn, B, "Wedge", size, CGNS_ENUMV(Unstructured), &Z));
  const double x[7] = {0, 1, 0, 0, 1, 0, 0}, y[7] = {0, 0, 1, 0, 0, 1, 0}, z[7] = {0, 0, 0, 1, 1, 1, 2};
  CG(cg_coord_write(fn, B, Z, CGNS_ENUMV(RealDouble), "CoordinateX", x, &C));
  CG(cg_coord_write(fn, B, Z, CGNS_ENUMV(RealDouble), "CoordinateY", y, &C));
  CG(cg_coord_write(fn, B, Z, CGNS_ENUMV(RealDouble), "CoordinateZ", z, &C));
  // A prism (1 2 3 / 4 5 6) and the tetrahedron (4 5 6 7) on top of it.
  const cgsize_t elements[] = {CGNS_ENUMV(PENTA_6), 1, 2, 3, 4, 5, 6, CGNS_ENUMV(TETRA_4), 4, 5, 6, 7};
  const cgsize_t offsets[] = {0, 7, 12};
  CG(cg_poly_section_write(fn, B, Z, "Cells", CGNS_ENUMV(MIXED), 1, 2, 0, elements, offsets, &S));
  CG(cg_close(fn));
  const CgnsMesh mesh = readCgnsMesh(path);
  ASSERT_EQ(mesh.cells.cellCount(), 2);
  EXPECT_EQ(mesh.cells.shapes[0], CellShape::Prism);
  EXPECT_EQ(mesh.cells.shapes[1], CellShape::Tetrahedron);
  const ElementQuality quality = checkElementCells(mesh.points, mesh.cells);
  EXPECT_TRUE(quality.ok()) << badElementsText(quality);
  EXPECT_NEAR(quality.totalVolume, 0.5 + 1.0 / 6.0, 1e-15);
}

TEST_F(Cgns, ReadVolumeMeshTakesCgnsFiles) {
  const fs::path in = writeBlock("block.CGNS");
  ASSERT_EQ(volumeMeshFormatOf(in), VolumeMeshFormat::Cgns);
  std::unique_ptr<VolumeMesh> mesh = readVolumeMesh(in);
  EXPECT_EQ(mesh->format(), VolumeMeshFormat::Cgns);
  EXPECT_EQ(mesh->cellCount(), 8);
  Eigen::MatrixX3d points = mesh->takePoints();
  ASSERT_EQ(points.rows(), 27);
  EXPECT_TRUE(mesh->check(points).ok());
  points.col(0) *= 3.0;
  const VolumeMeshQuality stretched = mesh->check(points);
  EXPECT_TRUE(stretched.checked);
  EXPECT_EQ(stretched.cellCount, 8);
  mesh->write(points, dir_ / "out.cgns", {.durable = false});
  EXPECT_EQ(readCgnsMesh(dir_ / "out.cgns").points, points);
}

// --- bad input: a clear message naming the file, the zone and the section ---

TEST_F(Cgns, NodeOutOfRangeIsRefusedWithTheSectionAndElement) {
  const fs::path path = writeBlock("bad.cgns", 2, 99);
  const std::string message = testing::meshIoErrorOf([&] { readCgnsMesh(path); });
  EXPECT_NE(message.find(path.string() + ": zone Block, section 1 'Hexa', element 2: node 99 is outside 1..27"),
            std::string::npos)
      << message;
}

TEST_F(Cgns, NotACgnsFileIsRefused) {
  const fs::path path = dir_ / "text.cgns";
  std::ofstream(path) << "not a CGNS file\n";
  const std::string message = testing::meshIoErrorOf([&] { readCgnsMesh(path); });
  EXPECT_NE(message.find(path.string() + ": not a CGNS file"), std::string::npos) << message;
  EXPECT_NE(testing::meshIoErrorOf([&] { readCgnsMesh(dir_ / "missing.cgns"); }).find("not a regular file"), std::string::npos);
}

TEST_F(Cgns, TooManyPointsForTheBudgetAreRefusedBeforeReading) {
  const fs::path path = writeBlock("big.cgns", 6);
  CgnsReadOptions options;
  options.limits.maxPoints = 100;  // the block has 343
  const std::string message = testing::meshIoErrorOf([&] { readCgnsMesh(path, options); });
  EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
  EXPECT_NE(message.find("343"), std::string::npos) << message;
}

TEST_F(Cgns, StructuredZoneIsRefused) {
  const fs::path path = dir_ / "structured.cgns";
  int fn = 0, B = 0, Z = 0;
  CG(cg_open(path.c_str(), CG_MODE_WRITE, &fn));
  CG(cg_base_write(fn, "Base", 3, 3, &B));
  cgsize_t size[9] = {2, 2, 2, 1, 1, 1, 0, 0, 0};
  CG(cg_zone_write(fn, B, "Box", size, CGNS_ENUMV(Structured), &Z));
  CG(cg_close(fn));
  const std::string message = testing::meshIoErrorOf([&] { readCgnsMesh(path); });
  EXPECT_NE(message.find("zone Box is structured"), std::string::npos) << message;
}

// Files fuzz_cgns found (tests/fuzz/regressions/fuzz_cgns). The CGNS library reads each in a child
// process: one whose header announces more memory than the read may take makes the library exit
// (its allocator exits when calloc fails), which is an error here, and this process goes on; a
// MIXED section whose element type is no type of the enumeration is refused by its number.
TEST(CgnsHostile, ALibraryThatExitsIsAnErrorAndThisProcessGoesOn) {
  const fs::path dir = fs::path(FFDKIT_SOURCE_DIR) / "tests/fuzz/regressions/fuzz_cgns";
  for (const char* name : {"oom-52b49a41f98227df8e70652649ab2d1b685f431b", "oom-91352231420bf70e781f927dd802061e10b23568",
                           "oom-b52f2c00c3287bd6b3840cfa061e691201cef046"}) {
    const std::string message = testing::meshIoErrorOf([&] { readCgnsMesh(dir / name); });
    EXPECT_NE(message.find(name), std::string::npos) << message;
#ifndef FFDKIT_ASAN
    // Under AddressSanitizer the child gets no memory limit (ASan reserves its shadow memory up
    // front), so the library reads on and refuses the file itself: an error as well.
    EXPECT_NE(message.find(std::string(name) + ": the CGNS library crashed reading it"), std::string::npos) << message;
#endif
  }
  const std::pair<const char*, const char*> types[] = {{"crash-3eb08f41dc319ddc026ef8ebf89553996b0ed0a9", "type 16384 "},
                                                       {"crash-80d8c39fe5c192ec3c21769807a5cc29a46b4c60", "type -500 "}};
  for (const auto& [file, type] : types) {
    const char* name = file;  // captured below: clang before 16 cannot capture a structured binding
    const std::string message = testing::meshIoErrorOf([&] { readCgnsMesh(dir / name); });
    EXPECT_NE(message.find(std::string(type) + "with 5 nodes is not a fixed element type ffdkit reads"), std::string::npos)
        << message;
  }
}

}  // namespace
}  // namespace ffdkit::meshio
