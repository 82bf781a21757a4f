// UNV dataset 2412 (elements): read for the cell check of the solids, beams and shells kept.
// The expectations come from outside the reader: PyGeM's test file (Salome's beams and shells),
// a hand-made mixed file whose volumes are known, and Gmsh, whose UNV and MSH 4.1 files of the
// same mesh must give the same cells at the same corners.
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "ffdkit/meshio/element_cells.h"
#include "ffdkit/meshio/volume_mesh.h"
#include "scratch_folder.h"
#include "meshio_test_support.h"

namespace ffdkit::meshio {
namespace {
using test_support::fileText;
using test_support::kPygem;

namespace fs = std::filesystem;
using testing::meshIoErrorOf;

std::unique_ptr<VolumeMesh> unv(const std::string& bytes) {
  ReadBudget budget;
  return readVolumeMeshBytes(bytes, VolumeMeshFormat::Unv, "mixed.unv", budget);
}

// A universal file's node record pair (2411) and element records (2412), in I-DEAS's columns.
std::string node(int label, double x, double y, double z) {
  char text[160];
  std::snprintf(text, sizeof text, "%10d%10d%10d%10d\n%25.16E%25.16E%25.16E\n", label, 1, 1, 11, x, y, z);
  return text;
}

std::string element(int label, int type, const std::vector<int>& nodes, bool beam = false) {
  char text[80];
  std::snprintf(text, sizeof text, "%10d%10d%10d%10d%10d%10d\n", label, type, 1, 1, 7, int(nodes.size()));
  std::string record = text;
  if (beam) record += "         0         1         1\n";
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    std::snprintf(text, sizeof text, "%10d", nodes[i]);
    record += text;
    if (i % 8 == 7 || i + 1 == nodes.size()) record += "\n";
  }
  return record;
}

// A unit cube (hexahedron 115, nodes 1-8 in Gmsh's order) with a pyramid on top (312, apex 9 at
// height 1.5), a quadratic pyramid (313) below it whose corners mirror the first one's, a beam
// (21) and a shell (94) on the cube's faces.
std::string mixedFile(bool invertHex = false) {
  std::string text = "    -1\n  2411\n";
  const double corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int i = 0; i < 8; ++i) text += node(i + 1, corners[i][0], corners[i][1], corners[i][2]);
  text += node(9, 0.5, 0.5, 1.5);
  text += node(10, 0.5, 0.5, -0.5);
  // The mid-edge nodes of the quadratic pyramid: its base is the cube's bottom seen from below.
  int label = 11;
  const int base[4] = {1, 4, 3, 2};  // counter-clockwise seen from the apex below
  std::vector<int> quadratic;
  for (int k = 0; k < 4; ++k) {
    const int a = base[k] - 1, b = base[(k + 1) % 4] - 1;
    quadratic.push_back(base[k]);
    text += node(label, 0.5 * (corners[a][0] + corners[b][0]), 0.5 * (corners[a][1] + corners[b][1]), 0.0);
    quadratic.push_back(label++);
  }
  for (int k = 0; k < 4; ++k) {
    const int a = base[k] - 1;
    text += node(label, 0.5 * (corners[a][0] + 0.5), 0.5 * (corners[a][1] + 0.5), -0.25);
    quadratic.push_back(label++);
  }
  quadratic.push_back(10);
  text += "    -1\n    -1\n  2412\n";
  text += invertHex ? element(101, 115, {5, 6, 7, 8, 1, 2, 3, 4}) : element(101, 115, {1, 2, 3, 4, 5, 6, 7, 8});
  text += element(102, 312, {5, 6, 7, 8, 9});
  text += element(103, 313, quadratic);
  text += element(104, 21, {1, 2}, true);
  text += element(105, 94, {1, 2, 6, 5});
  text += "    -1\n";
  return text;
}

TEST(UnvElements, PygemsSquareKeepsItsBeamsAndShellsAndHasNoSolids) {
  const std::string bytes = fileText(kPygem / "test_square.unv");
  const auto mesh = unv(bytes);
  // Salome's square: 60 beams (type 11, with their second record) on its edges, 225 shells (44).
  EXPECT_NE(mesh->summary().find("285 elements (dataset 2412): 60 of type 11 (beam), 225 of type 44 (shell); 0 solid cells"),
            std::string::npos)
      << mesh->summary();
  EXPECT_EQ(mesh->cellCount(), 0);
  EXPECT_EQ(mesh->elementCells(), nullptr);
  EXPECT_FALSE(mesh->check(mesh->points()).checked);
  EXPECT_EQ(mesh->bytesWith(mesh->points()), bytes);  // every element record kept
}

TEST(UnvElements, MixedSolidsAreCheckedAtTheirCornersAndTheRestIsKept) {
  const std::string bytes = mixedFile();
  const auto mesh = unv(bytes);
  ASSERT_NE(mesh->elementCells(), nullptr);
  const ElementCells& cells = *mesh->elementCells();
  ASSERT_EQ(cells.cellCount(), 3);
  EXPECT_EQ(cells.shapes, (std::vector<CellShape>{CellShape::Hexahedron, CellShape::Pyramid, CellShape::Pyramid}));
  EXPECT_EQ(cells.ids, (std::vector<std::int64_t>{101, 102, 103}));
  // The quadratic pyramid's corners are its nodes 0, 2, 4, 6 and 12: nodes 1, 4, 3, 2 and 10.
  EXPECT_EQ(std::vector<std::int32_t>(cells.corners.begin() + 13, cells.corners.end()),
            (std::vector<std::int32_t>{0, 3, 2, 1, 9}));
  const ElementQuality q = checkElementCells(mesh->points(), cells);
  EXPECT_EQ(q.badCells, 0);
  EXPECT_NEAR(q.totalVolume, 1.0 + 1.0 / 6.0 + 1.0 / 6.0, 1e-12);  // the cube and two pyramids of height 1/2
  EXPECT_NEAR(q.minVolume, 1.0 / 6.0, 1e-12);
  EXPECT_TRUE(mesh->check(mesh->points()).ok());
  EXPECT_NE(mesh->summary().find("1 of type 21 (beam), 1 of type 94 (shell), 1 of type 115 (solid), 1 of type 312 (solid), "
                                 "1 of type 313 (solid); 3 solid cells checked"),
            std::string::npos)
      << mesh->summary();
  // Moved points: only coordinates change; every element record comes back.
  const Eigen::MatrixX3d moved = mesh->points() * 2.0;
  const std::string written = mesh->bytesWith(moved);
  EXPECT_EQ(written.substr(written.find("  2412")), bytes.substr(bytes.find("  2412")));
  EXPECT_NEAR(checkElementCells(moved, *unv(written)->elementCells()).totalVolume, 8.0 * (1.0 + 1.0 / 3.0), 1e-11);
}

TEST(UnvElements, AnInvertedSolidIsNamedByItsLabel) {
  const auto mesh = unv(mixedFile(true));
  const VolumeMeshQuality quality = mesh->check(mesh->points());
  EXPECT_EQ(quality.badCells, 1);
  EXPECT_NE(quality.badText.find("(first: 101)"), std::string::npos) << quality.badText;
}

TEST(UnvElements, BadElementRecordsNameTheLine) {
  const std::string good = mixedFile();
  const auto errorOf = [](const std::string& bytes) { return meshIoErrorOf([&] { unv(bytes); }); };
  std::string unknownNode = good;
  unknownNode.replace(unknownNode.find("         1         2         3         4         5"), 10, "        99");
  EXPECT_NE(errorOf(unknownNode).find("dataset 2412: element 101: node 99 is not in dataset 2411"), std::string::npos)
      << errorOf(unknownNode);
  std::string wrongCount = good;
  wrongCount.replace(wrongCount.find("       102       312         1         1         7         5"), 60,
                     "       102       312         1         1         7         6");
  EXPECT_NE(errorOf(wrongCount).find("element 102: type 312 has 5 nodes, the record says 6"), std::string::npos)
      << errorOf(wrongCount);
  std::string noBeamRecord = good;
  noBeamRecord.erase(noBeamRecord.find("         0         1         1\n"), 31);
  EXPECT_NE(errorOf(noBeamRecord).find("element 104: a beam's second record"), std::string::npos) << errorOf(noBeamRecord);
  const std::string truncated = good.substr(0, good.find("       104"));
  EXPECT_NE(errorOf(truncated).find("mixed.unv:"), std::string::npos);
  EXPECT_NE(errorOf(truncated).find("dataset 2412 is not closed by '-1'"), std::string::npos) << errorOf(truncated);
  std::string twice = good;
  twice.replace(twice.find("         2         1         1        11"), 10, "         1");
  EXPECT_NE(errorOf(twice).find("dataset 2411: node label 1 given twice"), std::string::npos) << errorOf(twice);
  std::string tooMany = good;
  tooMany.replace(tooMany.find("       105        94         1         1         7         4"), 60,
                  "       105        94         1         1         7    999999");
  EXPECT_NE(errorOf(tooMany).find("element 105: 999999 nodes (expected 1..64)"), std::string::npos) << errorOf(tooMany);
}

// Gmsh writes the same mesh as MSH 4.1 and as a universal file: every solid of the UNV file is
// the MSH file's element of the same tag, with the same corners (Gmsh's own reading of its
// I-DEAS node orders), and no cell of either is inverted.
class UnvFromGmsh : public testing::ScratchFolderTest {
 protected:
  UnvFromGmsh() : ScratchFolderTest("unv-gmsh") {}
};

TEST_F(UnvFromGmsh, SolidsHaveTheCornersOfGmshsOwnMesh) {
  ASSERT_EQ(std::system("command -v gmsh > /dev/null"), 0) << "gmsh is not installed (scripts/setup-deps.sh installs it)";
  const std::map<std::string, std::string> geometries = {
      {"tets", "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\nMesh.MeshSizeMax = 0.5;\n"},
      {"hexes",
       "Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};\n"
       "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
       "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
       "Transfinite Curve{1, 2, 3, 4} = 3; Transfinite Surface{1}; Recombine Surface{1};\n"
       "Extrude {0, 0, 1} { Surface{1}; Layers{2}; Recombine; }\n"},
      {"prisms",
       "Point(1) = {0, 0, 0, 0.5}; Point(2) = {1, 0, 0, 0.5}; Point(3) = {1, 1, 0, 0.5}; Point(4) = {0, 1, 0, 0.5};\n"
       "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
       "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
       "Extrude {0, 0, 1} { Surface{1}; Layers{2}; Recombine; }\n"},
  };
  int compared = 0;
  for (const auto& [name, geo] : geometries) {
    for (int order : {1, 2}) {
      SCOPED_TRACE(name + " order " + std::to_string(order));
      const fs::path geoFile = dir_ / (name + std::to_string(order) + ".geo");
      // Second order without face and volume nodes: hexahedra of 20 nodes and prisms of 15, which
      // UNV has types for (116, 113).
      std::ofstream(geoFile) << geo << "Mesh.SecondOrderIncomplete = 1;\nMesh.SaveAll = 1;\n";
      for (const char* format : {"msh41", "unv"}) {
        const std::string command = "gmsh -3 -order " + std::to_string(order) + " -format " + format + " " + geoFile.string() +
                                    " -o " + (dir_ / (name + std::to_string(order) + "." + (format[0] == 'm' ? "msh" : "unv"))).string() +
                                    " > /dev/null 2>&1";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
      }
      const auto fromMsh = readVolumeMesh(dir_ / (name + std::to_string(order) + ".msh"));
      const auto fromUnv = readVolumeMesh(dir_ / (name + std::to_string(order) + ".unv"));
      ASSERT_NE(fromUnv->elementCells(), nullptr);
      const ElementCells& u = *fromUnv->elementCells();
      const ElementCells& m = *fromMsh->elementCells();
      ASSERT_EQ(u.cellCount(), m.cellCount());
      ASSERT_GT(u.cellCount(), 0);
      std::map<std::int64_t, std::int64_t> mshCell;
      for (std::int64_t c = 0; c < m.cellCount(); ++c) mshCell[m.ids[std::size_t(c)]] = c;
      for (std::int64_t c = 0; c < u.cellCount(); ++c) {
        ASSERT_EQ(mshCell.count(u.ids[std::size_t(c)]), 1u);
        const std::int64_t k = mshCell[u.ids[std::size_t(c)]];
        ASSERT_EQ(u.shapes[std::size_t(c)], m.shapes[std::size_t(k)]);
        for (int corner = 0; corner < cornerCount(u.shapes[std::size_t(c)]); ++corner) {
          const Eigen::RowVector3d a = fromUnv->points().row(u.corners[std::size_t(u.cornerStarts[std::size_t(c)] + corner)]);
          const Eigen::RowVector3d b = fromMsh->points().row(m.corners[std::size_t(m.cornerStarts[std::size_t(k)] + corner)]);
          ASSERT_LT((a - b).norm(), 1e-12) << "cell " << u.ids[std::size_t(c)] << " corner " << corner;
        }
      }
      const VolumeMeshQuality q = fromUnv->check(fromUnv->points());
      EXPECT_TRUE(q.checked);
      EXPECT_EQ(q.cellCount, u.cellCount());
      EXPECT_TRUE(q.ok()) << q.badText;
      // Mirrored, every cell turns inside out.
      Eigen::MatrixX3d mirrored = fromUnv->points();
      mirrored.col(0) *= -1.0;
      EXPECT_EQ(fromUnv->check(mirrored).badCells, u.cellCount());
      ++compared;
    }
  }
  EXPECT_EQ(compared, 6);
}

}  // namespace
}  // namespace ffdkit::meshio
