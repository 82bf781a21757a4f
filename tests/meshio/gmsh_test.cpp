#include "ffdkit/meshio/gmsh.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include <unistd.h>

#include <gtest/gtest.h>

#include "ffdkit/meshio/mesh_data.h"

namespace ffdkit::meshio {
namespace {

// Two tetrahedra sharing the face (2, 3, 4), a boundary triangle and a point element; node tags
// 10..14, element tags 1, 5, 6, 7 (not 0-based, not contiguous).
const char* const kTwoTets =
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
    "$PhysicalNames\n2\n2 5 \"wall\"\n3 9 \"fluid domain\"\n$EndPhysicalNames\n"
    "$Entities\n0 0 1 1\n1 0 0 0 1 1 1 1 5 0 \n1 0 0 0 1 1 1 1 9 1 1 \n$EndEntities\n"
    "$Nodes\n2 5 10 14\n"
    "3 1 0 2\n10\n11\n"
    "0 0 0\n1 0 0\n"
    "2 1 1 3\n12\n13\n14\n"
    "0 1 0 0.5 0.5\n0 0 1 0.25 0.75\n1 1 1 1 1\n"
    "$EndNodes\n"
    "$Elements\n3 4 1 7\n"
    "3 1 4 2\n1 10 11 12 13\n5 11 14 12 13\n"
    "2 1 2 1\n6 10 12 11\n"
    "0 1 15 1\n7 10\n"
    "$EndElements\n"
    "$NodeData\n1\n\"t\"\n0\n3\n0\n1\n5\n10 1\n11 2\n12 3\n13 4\n14 5\n$EndNodeData\n";

GmshMesh readTwoTets(std::string bytes, ReadLimits limits = {}) {
  ReadBudget budget(limits);
  return readGmsh(std::move(bytes), "two.msh", budget);
}

std::string gmshErrorOf(const std::string& bytes) {
  try {
    readTwoTets(bytes);
  } catch (const MeshIoError& e) {
    return e.what();
  }
  return "no error";
}

// The same mesh written in binary, value by value (independent of the reader).
std::string binaryTwoTets() {
  std::string b = "$MeshFormat\n4.1 1 8\n";
  auto i32 = [&](std::int32_t v) { b.append(reinterpret_cast<const char*>(&v), 4); };
  auto u64 = [&](std::uint64_t v) { b.append(reinterpret_cast<const char*>(&v), 8); };
  auto f64 = [&](double v) { b.append(reinterpret_cast<const char*>(&v), 8); };
  i32(1);
  b += "\n$EndMeshFormat\n$Entities\n";
  u64(0), u64(0), u64(0), u64(1);
  i32(1);
  for (double v : {0., 0., 0., 1., 1., 1.}) f64(v);
  u64(1), i32(9), u64(0);
  b += "\n$EndEntities\n$Nodes\n";
  u64(1), u64(5), u64(10), u64(14);
  i32(3), i32(1), i32(0), u64(5);
  for (std::uint64_t t = 10; t <= 14; ++t) u64(t);
  for (double v : {0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1., 1., 1., 1.}) f64(v);
  b += "\n$EndNodes\n$Elements\n";
  u64(1), u64(2), u64(1), u64(5);
  i32(3), i32(1), i32(4), u64(2);
  for (std::uint64_t v : {1, 10, 11, 12, 13, 5, 11, 14, 12, 13}) u64(v);
  b += "\n$EndElements\n";
  return b;
}

TEST(Gmsh, ReadsNodesElementsAndTags) {
  const GmshMesh mesh = readTwoTets(kTwoTets);
  ASSERT_EQ(mesh.points.rows(), 5);
  EXPECT_EQ(mesh.nodeTags, (std::vector<std::int64_t>{10, 11, 12, 13, 14}));
  EXPECT_EQ(mesh.points.row(3), Eigen::RowVector3d(0, 0, 1));  // parametric u, v not taken as coordinates
  EXPECT_EQ(mesh.elementCount, 4);
  EXPECT_EQ(mesh.elementsByType.at(4), 2);
  EXPECT_EQ(mesh.elementsByType.at(2), 1);
  EXPECT_EQ(mesh.physicalNameCount, 2);
  EXPECT_EQ(mesh.entityCount, 2);
  ASSERT_EQ(mesh.cells.cellCount(), 2);
  EXPECT_EQ(mesh.cells.ids, (std::vector<std::int64_t>{1, 5}));
  EXPECT_EQ(mesh.cells.corners[4], 1);  // element 5's first node, tag 11, is row 1
  const ElementQuality q = checkElementCells(mesh.points, mesh.cells);
  EXPECT_TRUE(q.ok());
  EXPECT_NEAR(q.totalVolume, 1.0 / 6.0 + 1.0 / 3.0, 1e-15);
}

TEST(Gmsh, PassThroughGivesBackEveryByte) {
  const GmshMesh mesh = readTwoTets(kTwoTets);
  EXPECT_EQ(gmshBytes(mesh.file, mesh.points), kTwoTets);
  const GmshMesh binary = readTwoTets(binaryTwoTets());
  EXPECT_TRUE(binary.file.binary);
  EXPECT_EQ(binary.points, mesh.points);
  EXPECT_EQ(binary.cells.corners, mesh.cells.corners);
  EXPECT_EQ(gmshBytes(binary.file, binary.points), binaryTwoTets());
}

TEST(Gmsh, MovedNodesReadBackAndNothingElseChanges) {
  for (const std::string& original : {std::string(kTwoTets), binaryTwoTets()}) {
    const GmshMesh mesh = readTwoTets(original);
    Eigen::MatrixX3d moved = mesh.points;
    moved.row(4) << 1.25, 0.1 / 3.0, -2e-300;
    moved(0, 0) = -0.5;
    const std::string written = gmshBytes(mesh.file, moved);
    const GmshMesh again = readTwoTets(written);
    EXPECT_EQ(again.points, moved);
    EXPECT_EQ(again.cells.corners, mesh.cells.corners);
    EXPECT_EQ(again.elementsByType, mesh.elementsByType);
    // Everything from $Elements on is the same bytes.
    const std::size_t at = original.find("$Elements");
    EXPECT_EQ(written.substr(written.find("$Elements")), original.substr(at));
    EXPECT_EQ(written.substr(0, written.find("$Nodes")), original.substr(0, original.find("$Nodes")));
  }
}

TEST(Gmsh, ParametricCoordinatesStayAsTheyWere) {
  const GmshMesh mesh = readTwoTets(kTwoTets);
  Eigen::MatrixX3d moved = mesh.points;
  moved.row(2) << 7, 8, 9;
  const std::string written = gmshBytes(mesh.file, moved);
  EXPECT_NE(written.find("\n7 8 9 0.5 0.5\n"), std::string::npos) << written;
}

TEST(Gmsh, BadFilesGiveClearMessages) {
  auto replaced = [](std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  const std::string good = kTwoTets;
  EXPECT_NE(gmshErrorOf(replaced(good, "4.1 0 8", "2.2 0 8")).find("two.msh:2: $MeshFormat: version '2.2' is not supported"),
            std::string::npos);
  EXPECT_NE(gmshErrorOf(replaced(good, "2 5 10 14", "2 5000000000 10 14")).find("5000000000 nodes need at least"),
            std::string::npos);
  EXPECT_NE(gmshErrorOf(replaced(good, "5 11 14 12 13", "5 11 99 12 13")).find("element 5: node 99 is not in $Nodes"),
            std::string::npos);
  EXPECT_NE(gmshErrorOf(replaced(good, "1 1 1 1 1\n", "1 nan 1 1 1\n")).find("two.msh:27: $Nodes: node coordinates: non-finite"),
            std::string::npos);
  EXPECT_NE(gmshErrorOf(replaced(good, "\n13\n14\n", "\n13\n13\n")).find("node tag 13 appears twice"), std::string::npos);
  EXPECT_NE(gmshErrorOf(replaced(good, "3 1 4 2", "2 1 4 2")).find("element type 4 has dimension 3, its entity 2"),
            std::string::npos);
  EXPECT_NE(gmshErrorOf(replaced(good, "3 1 4 2", "3 1 77 2")).find("element type 77 is not one this reader knows"),
            std::string::npos);
  EXPECT_NE(gmshErrorOf(replaced(good, "$EndElements", "$EndElement")).find("expected $EndElements"), std::string::npos);
  EXPECT_NE(gmshErrorOf(good.substr(0, good.find("$Elements"))).find("no $Elements section"), std::string::npos);
  EXPECT_NE(gmshErrorOf("ply\n").find("must start with $MeshFormat"), std::string::npos);
  const std::string binary = binaryTwoTets();
  for (std::size_t cut : {std::size_t(30), binary.find("$Nodes") + 20, binary.find("$Nodes") + 100, binary.find("$Elements") + 60})
    EXPECT_NE(gmshErrorOf(binary.substr(0, cut)).find("two.msh"), std::string::npos) << cut;
  EXPECT_NE(gmshErrorOf(binary.substr(0, binary.find("$Nodes") + 100)).find("$Nodes: 5 nodes need at least 32 bytes"),
            std::string::npos);
  // A binary file's messages name byte offsets, not lines.
  EXPECT_NE(gmshErrorOf(binary.substr(0, binary.find("$Nodes") + 100)).find("two.msh: byte offset "), std::string::npos);
}

// A binary file of `n` nodes (tags 1..n at (i, i^2 mod 7, -i)) and n - 3 tetrahedra on nodes
// (i, i+1, i+2, i+3), in either byte order: large enough that its blocks are read on every core.
std::string binaryChain(std::uint64_t n, bool bigEndian) {
  std::string b = "$MeshFormat\n4.1 1 8\n";
  auto put = [&](auto v) {
    char raw[sizeof v];
    std::memcpy(raw, &v, sizeof v);
    if (bigEndian) std::reverse(raw, raw + sizeof v);
    b.append(raw, sizeof v);
  };
  put(std::int32_t(1));
  b += "\n$EndMeshFormat\n$Nodes\n";
  put(std::uint64_t(1)), put(n), put(std::uint64_t(1)), put(n);
  put(std::int32_t(3)), put(std::int32_t(1)), put(std::int32_t(0)), put(n);
  for (std::uint64_t t = 1; t <= n; ++t) put(t);
  for (std::uint64_t i = 0; i < n; ++i) put(double(i)), put(double((i * i) % 7)), put(-double(i));
  b += "\n$EndNodes\n$Elements\n";
  put(std::uint64_t(1)), put(n - 3), put(std::uint64_t(1)), put(n - 3);
  put(std::int32_t(3)), put(std::int32_t(1)), put(std::int32_t(4)), put(n - 3);
  for (std::uint64_t e = 1; e <= n - 3; ++e) put(e), put(e), put(e + 1), put(e + 2), put(e + 3);
  b += "\n$EndElements\n";
  return b;
}

// Overwrites the 8-byte value at `offset` of a little-endian file.
void poke(std::string& bytes, std::size_t offset, auto value) { std::memcpy(bytes.data() + offset, &value, 8); }

TEST(Gmsh, LargeBinaryBlocksReadInEitherByteOrderAndNameTheFirstBadRecord) {
  const std::uint64_t n = 100'000;
  for (bool big : {false, true}) {
    const GmshMesh mesh = readTwoTets(binaryChain(n, big));
    ASSERT_EQ(mesh.points.rows(), Eigen::Index(n));
    ASSERT_EQ(mesh.cells.cellCount(), std::int64_t(n - 3));
    bool same = true;
    for (std::uint64_t i = 0; i < n; ++i)
      same = same && mesh.nodeTags[i] == std::int64_t(i + 1) && mesh.points(Eigen::Index(i), 0) == double(i) &&
             mesh.points(Eigen::Index(i), 1) == double((i * i) % 7) && mesh.points(Eigen::Index(i), 2) == -double(i);
    for (std::int64_t c = 0; c < mesh.cells.cellCount(); ++c)
      same = same && mesh.cells.ids[std::size_t(c)] == c + 1 && mesh.cells.cornerStarts[std::size_t(c)] == 4 * c &&
             mesh.cells.corners[std::size_t(4 * c + 3)] == std::int32_t(c + 3);
    EXPECT_TRUE(same) << (big ? "big-endian" : "little-endian");
  }
  const std::string good = binaryChain(n, false);
  const std::size_t tags = good.find("$Nodes\n") + 7 + 32 + 20, xyz = tags + 8 * n;
  const std::size_t elements = good.find("$Elements\n") + 10 + 32 + 20;
  // Two bad element nodes, the later one in the first half of the block: the earlier is named.
  std::string bad = good;
  poke(bad, elements + 40 * 70'000 + 16, std::uint64_t(n + 5));
  poke(bad, elements + 40 * 20'000 + 24, std::uint64_t(n + 9));
  EXPECT_NE(gmshErrorOf(bad).find("element 20001: node 100009 is not in $Nodes (byte offset " +
                              std::to_string(elements + 40 * 20'000 + 24) + ")"),
            std::string::npos)
      << gmshErrorOf(bad);
  // A non-finite coordinate after a tag outside the header's range: the tag is named.
  bad = good;
  poke(bad, xyz + 24 * 80'000 + 8, std::numeric_limits<double>::quiet_NaN());
  poke(bad, tags + 8 * 60'000, std::uint64_t(n + 1));
  EXPECT_NE(gmshErrorOf(bad).find("node tag 100001 is outside the header's range 1..100000"), std::string::npos) << gmshErrorOf(bad);
  bad = good;
  poke(bad, xyz + 24 * 80'000 + 8, std::numeric_limits<double>::infinity());
  poke(bad, xyz + 24 * 90'000, std::numeric_limits<double>::quiet_NaN());
  EXPECT_NE(gmshErrorOf(bad).find("node 80001: non-finite coordinate"), std::string::npos) << gmshErrorOf(bad);
  // Finite coordinates whose sum would overflow are finite.
  bad = good;
  poke(bad, xyz + 24 * 50'000, 1e308), poke(bad, xyz + 24 * 50'000 + 8, 1e308);
  EXPECT_EQ(gmshErrorOf(bad), "no error");
}

TEST(Gmsh, ChargesTheBudgetBeforeAllocating) {
  ReadLimits limits;
  limits.maxPoints = 4;
  try {
    readTwoTets(kTwoTets, limits);
    FAIL() << "no error";
  } catch (const ReadLimitError& e) {
    EXPECT_NE(std::string(e.what()).find("--max-points"), std::string::npos) << e.what();
  }
}

TEST(Gmsh, WritesAFileAtomically) {
  const auto dir = std::filesystem::temp_directory_path() / ("ffdkit-gmsh-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto in = dir / "in.msh";
  std::ofstream(in, std::ios::binary) << binaryTwoTets();
  const GmshMesh mesh = readGmsh(in);
  Eigen::MatrixX3d moved = mesh.points * 2.0;
  writeGmsh(mesh, moved, dir / "out.msh", false);
  EXPECT_EQ(readGmsh(dir / "out.msh").points, moved);
  EXPECT_THROW(readGmsh(dir / "missing.msh"), MeshIoError);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ffdkit::meshio
