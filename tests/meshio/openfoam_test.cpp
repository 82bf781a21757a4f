// The OpenFOAM polyMesh reader and pass-through writer over blockMesh's own output
// (tests/data/openfoam: ASCII, and binary by foamFormatConvert), their refusals of bad input,
// and the cell check against exact volumes of affine maps of the cube.
#include "ffdkit/meshio/openfoam.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "scratch_folder.h"

#include "ffdkit/meshio/cell_quality.h"
#include "meshio_test_support.h"

namespace ffdkit::meshio {
namespace {
using test_support::fileText;

namespace fs = std::filesystem;

const fs::path kData = fs::path(FFDKIT_SOURCE_DIR) / "tests" / "data" / "openfoam";

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

class OpenFoam : public testing::ScratchFolderTest {
 protected:
  OpenFoam() : ScratchFolderTest("openfoam") {}
  // A copy of a test case to spoil.
  fs::path copyCase(const std::string& name) {
    const fs::path to = dir_ / name;
    fs::copy(kData / name, to, fs::copy_options::recursive);
    return to;
  }
};

TEST_F(OpenFoam, ReadsTheAsciiBlockMeshCube) {
  const OpenFoamMesh mesh = readOpenFoamMesh(kData / "cube");
  EXPECT_EQ(mesh.polyMesh, kData / "cube" / "constant" / "polyMesh");
  ASSERT_EQ(mesh.points.rows(), 7 * 7 * 7);
  EXPECT_EQ(mesh.cells.cellCount, 6 * 6 * 6);
  // Internal faces: 3 directions x 5 inner planes x 36; boundary: 6 sides x 36.
  EXPECT_EQ(mesh.cells.neighbour.size(), 3u * 5 * 36);
  EXPECT_EQ(mesh.cells.faceCount(), 3 * 5 * 36 + 6 * 36);
  ASSERT_EQ(mesh.patches.size(), 1u);
  EXPECT_EQ(mesh.patches[0].name, "walls");
  EXPECT_EQ(mesh.patches[0].type, "wall");
  EXPECT_EQ(mesh.patches[0].startFace, 540);
  EXPECT_EQ(mesh.patches[0].faceCount, 216);
  EXPECT_FALSE(mesh.pointsFile.layout.binary);
  // blockMesh numbers the points x fastest on a grid of 1/6.
  for (Eigen::Index k = 0, i = 0; k < 7; ++k)
    for (Eigen::Index j = 0; j < 7; ++j)
      for (Eigen::Index l = 0; l < 7; ++l, ++i)
        EXPECT_LT((mesh.points.row(i) - Eigen::RowVector3d(double(l), double(j), double(k)) / 6.0).norm(), 1e-9) << i;
  for (std::int64_t f = 0; f < mesh.cells.faceCount(); ++f)
    EXPECT_EQ(mesh.cells.faceStarts[std::size_t(f) + 1] - mesh.cells.faceStarts[std::size_t(f)], 4) << f;
}

TEST_F(OpenFoam, BinaryCaseHoldsTheSameMesh) {
  const OpenFoamMesh ascii = readOpenFoamMesh(kData / "cube");
  const OpenFoamMesh binary = readOpenFoamMesh(kData / "cube-binary");
  EXPECT_TRUE(binary.pointsFile.layout.binary);
  EXPECT_EQ(binary.pointsFile.layout.labelBytes, 4);
  EXPECT_EQ(binary.pointsFile.layout.scalarBytes, 8);
  ASSERT_EQ(ascii.points.rows(), binary.points.rows());
  // foamFormatConvert wrote the values it read from the ASCII file.
  EXPECT_EQ(ascii.points, binary.points);
  EXPECT_EQ(ascii.cells.faceStarts, binary.cells.faceStarts);
  EXPECT_EQ(ascii.cells.faceVertices, binary.cells.faceVertices);
  EXPECT_EQ(ascii.cells.owner, binary.cells.owner);
  EXPECT_EQ(ascii.cells.neighbour, binary.cells.neighbour);
}

TEST_F(OpenFoam, BinaryListsAreReadInPlaceAndKeptReadableByTheirCopies) {
  const OpenFoamMesh ascii = readOpenFoamMesh(kData / "cube");
  EXPECT_FALSE(ascii.cells.owner.readInPlace());
  PolyMeshCells kept;
  {
    const OpenFoamMesh binary = readOpenFoamMesh(kData / "cube-binary");
    for (const LabelList* list : {&binary.cells.faceStarts, &binary.cells.faceVertices, &binary.cells.owner, &binary.cells.neighbour})
      EXPECT_TRUE(list->readInPlace());
    kept = binary.cells;
  }
  // The mesh and its files' mappings are gone but for what the copy keeps: the lists still read
  // as the ASCII case's, and the check gives the same cells.
  EXPECT_EQ(kept.faceStarts, ascii.cells.faceStarts);
  EXPECT_EQ(kept.faceVertices, ascii.cells.faceVertices);
  EXPECT_EQ(kept.owner, ascii.cells.owner);
  EXPECT_EQ(kept.neighbour, ascii.cells.neighbour);
  const CellQuality fromKept = checkPolyMeshCells(ascii.points, kept);
  const CellQuality fromAscii = checkPolyMeshCells(ascii.points, ascii.cells);
  EXPECT_EQ(fromKept.totalVolume, fromAscii.totalVolume);
  EXPECT_EQ(fromKept.minPyramidVolume, fromAscii.minPyramidVolume);
  EXPECT_EQ(fromKept.maxSkewness, fromAscii.maxSkewness);
  // Changing a copy takes the labels into memory first; the list read in place is unchanged.
  PolyMeshCells changed = kept;
  changed.owner.held()[0] = 7;
  EXPECT_FALSE(changed.owner.readInPlace());
  EXPECT_EQ(changed.owner[0], 7);
  EXPECT_EQ(kept.owner[0], ascii.cells.owner[0]);
  EXPECT_EQ(changed.owner.size(), kept.owner.size());
}

TEST_F(OpenFoam, ACellWithFewerThanFourFacesIsNamed) {
  // Cell 0 (a corner of the cube) keeps its 3 internal faces; its 3 boundary faces go to cell 1.
  const fs::path copy = copyCase("cube");
  const OpenFoamMesh mesh = readOpenFoamMesh(copy);
  std::string owner = "FoamFile { version 2.0; format ascii; class labelList; object owner; }\n" +
                      std::to_string(mesh.cells.owner.size()) + "\n(\n";
  int moved = 0;
  for (std::size_t f = 0; f < mesh.cells.owner.size(); ++f) {
    const bool boundary = f >= mesh.cells.neighbour.size();
    moved += boundary && mesh.cells.owner[f] == 0 ? 1 : 0;
    owner += std::to_string(boundary && mesh.cells.owner[f] == 0 ? 1 : mesh.cells.owner[f]) + "\n";
  }
  ASSERT_EQ(moved, 3);
  writeText(copy / "constant" / "polyMesh" / "owner", owner + ")\n");
  const std::string message = testing::meshIoErrorOf([&] { readOpenFoamMesh(copy); });
  EXPECT_NE(message.find("owner: cell 0 has 3 face(s) in owner and neighbour; a cell needs at least 4"), std::string::npos)
      << message;
}

TEST(LabelList, ReadsLabelsInPlaceAtAnyByteOffset) {
  // Labels 5, -2, 70000 stored from byte 1 of a buffer (as a binary list after "3(" lies).
  const std::vector<std::int32_t> values{5, -2, 70000};
  auto buffer = std::make_shared<std::vector<char>>(1 + values.size() * sizeof(std::int32_t) + 1, 'x');
  std::memcpy(buffer->data() + 1, values.data(), values.size() * sizeof(std::int32_t));
  const LabelList list = LabelList::inPlace(buffer, buffer->data() + 1, values.size());
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[0], 5);
  EXPECT_EQ(list[1], -2);
  EXPECT_EQ(list.back(), 70000);
  EXPECT_EQ(std::vector<std::int32_t>(list.begin(), list.end()), values);
  EXPECT_EQ(list, LabelList(values));
  EXPECT_FALSE(list == LabelList({5, -2}));
  EXPECT_FALSE(list == LabelList({5, -2, 70001}));
  // The buffer stays as long as a list reads it.
  std::weak_ptr<std::vector<char>> watch = buffer;
  buffer.reset();
  EXPECT_FALSE(watch.expired());
  LabelList copy = list;
  EXPECT_EQ(copy.held(), values);
  EXPECT_EQ(list[2], 70000);
}

TEST_F(OpenFoam, PointsBytesAreTheFileWhenNothingMoved) {
  for (const char* name : {"cube", "cube-binary"}) {
    const OpenFoamMesh mesh = readOpenFoamMesh(kData / name);
    EXPECT_EQ(foamPointsBytes(mesh.pointsFile, mesh.points), fileText(mesh.polyMesh / "points")) << name;
  }
}

TEST_F(OpenFoam, MovedPointsReadBackExactlyAndTheRestKeepsItsBytes) {
  for (const char* name : {"cube", "cube-binary"}) {
    const OpenFoamMesh mesh = readOpenFoamMesh(kData / name);
    Eigen::MatrixX3d moved = mesh.points;
    moved.col(0) = moved.col(0) * 1.1 + Eigen::VectorXd::Constant(moved.rows(), 0.123456789012345);
    moved(5, 2) = -2.5e-7;
    const std::string bytes = foamPointsBytes(mesh.pointsFile, moved);
    ReadBudget budget;
    FoamPointsFile layout;
    const Eigen::MatrixX3d back = readFoamPoints(bytes, "moved", budget, &layout);
    EXPECT_EQ(back, moved) << name;  // shortest round-trip text, or the binary values themselves
    // Header before the list and everything after it: byte for byte.
    const std::string& original = mesh.pointsFile.bytes;
    EXPECT_EQ(bytes.substr(0, layout.listBegin), original.substr(0, mesh.pointsFile.listBegin)) << name;
    EXPECT_EQ(bytes.substr(layout.listEnd), original.substr(mesh.pointsFile.listEnd)) << name;
    if (!mesh.pointsFile.layout.binary) {
      // The y and z values did not move (but one): their text is the file's; one point per line.
      const std::string list = bytes.substr(layout.listBegin, layout.listEnd - layout.listBegin);
      EXPECT_EQ(std::count(list.begin(), list.end(), '\n'),
                std::count(original.begin() + std::ptrdiff_t(mesh.pointsFile.listBegin),
                           original.begin() + std::ptrdiff_t(mesh.pointsFile.listEnd), '\n'));
      EXPECT_NE(bytes.find("(0.123456789012345 0.1666666667 0)"), std::string::npos);
    }
  }
}

TEST_F(OpenFoam, GzipRoundTripAndTheBombIsRefused) {
  const std::string text = fileText(kData / "cube" / "constant" / "polyMesh" / "points");
  ReadBudget budget;
  EXPECT_EQ(gunzipBytes(gzipBytes(text, "points.gz"), "points.gz", budget), text);
  // 256 MiB of zeros compress to ~256 KiB; a 64 MiB limit refuses them while inflating.
  const std::string zeros(std::size_t(256) << 20, '\0');
  const std::string bomb = gzipBytes(zeros, "bomb.gz");
  EXPECT_LT(bomb.size(), std::size_t(1) << 20);
  ReadLimits limits;
  limits.maxMemoryBytes = std::uint64_t(64) << 20;
  ReadBudget small(limits);
  const std::string message = testing::meshIoErrorOf([&] { gunzipBytes(bomb, "points.gz", small); });
  EXPECT_NE(message.find("points.gz: the compressed file expands past"), std::string::npos) << message;
  EXPECT_NE(message.find("--max-memory"), std::string::npos) << message;
}

TEST_F(OpenFoam, ReadsGzipCompressedFiles) {
  const fs::path copy = copyCase("cube");
  const fs::path polyMesh = copy / "constant" / "polyMesh";
  for (const char* name : {"points", "faces", "owner"}) {
    writeText(polyMesh / (std::string(name) + ".gz"), gzipBytes(fileText(polyMesh / name), name));
    fs::remove(polyMesh / name);
  }
  const OpenFoamMesh gz = readOpenFoamMesh(copy);
  const OpenFoamMesh plain = readOpenFoamMesh(kData / "cube");
  EXPECT_TRUE(gz.pointsFile.gzip);
  EXPECT_EQ(gz.pointsFile.fileName, "points.gz");
  EXPECT_EQ(gz.points, plain.points);
  EXPECT_EQ(gz.cells.faceVertices, plain.cells.faceVertices);
  EXPECT_EQ(gz.cells.owner, plain.cells.owner);
}

TEST_F(OpenFoam, WritesTheCaseWithOnlyThePointsChanged) {
  for (const char* name : {"cube", "cube-binary"}) {
    const OpenFoamMesh mesh = readOpenFoamMesh(kData / name);
    const Eigen::MatrixX3d moved = mesh.points * 2.0;
    const fs::path out = dir_ / (std::string(name) + "-out");
    writeOpenFoamMesh(mesh, moved, out, {.durable = false});
    std::size_t files = 0;
    for (const auto& entry : fs::recursive_directory_iterator(kData / name)) {
      if (!entry.is_regular_file()) continue;
      ++files;
      const fs::path relative = fs::relative(entry.path(), kData / name);
      ASSERT_TRUE(fs::exists(out / relative)) << relative;
      if (relative.filename() != "points") {
        EXPECT_EQ(fileText(out / relative), fileText(entry.path())) << relative;
      }
    }
    std::size_t written = 0;
    for (const auto& entry : fs::recursive_directory_iterator(out)) written += entry.is_regular_file() ? 1 : 0;
    EXPECT_EQ(written, files) << name;
    EXPECT_EQ(readOpenFoamMesh(out).points, moved) << name;
    // No temporary folder is left beside the output.
    for (const auto& entry : fs::directory_iterator(dir_))
      EXPECT_NE(entry.path().filename().string()[0], '.') << entry.path();
  }
}

TEST_F(OpenFoam, AnExistingOutputIsReplacedWhole) {
  const OpenFoamMesh mesh = readOpenFoamMesh(kData / "cube");
  const fs::path out = dir_ / "out";
  fs::create_directories(out / "stale");
  writeText(out / "stale" / "file", "old");
  writeOpenFoamMesh(mesh, mesh.points, out, {.durable = false});
  EXPECT_FALSE(fs::exists(out / "stale"));
  EXPECT_EQ(fileText(out / "constant" / "polyMesh" / "points"), fileText(mesh.polyMesh / "points"));
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 1u);  // the old folder went with the exchange
}

// The write split in two (what ffdkit-cli deform does beside the cell check): the staged case is
// complete in a hidden folder and invisible until committed; dropped, it leaves nothing behind.
TEST_F(OpenFoam, AStagedCaseIsInPlaceOnlyWhenCommitted) {
  const OpenFoamMesh mesh = readOpenFoamMesh(kData / "cube-binary");
  const Eigen::MatrixX3d moved = mesh.points * 3.0;
  const fs::path out = dir_ / "out";
  fs::create_directories(out / "old");
  writeText(out / "old" / "file", "old");
  auto entriesOf = [](const fs::path& folder) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  };
  const OpenFoamWriteOptions oneThread{.durable = false, .everyCore = false};
  {
    StagedOpenFoamMesh staged = stageOpenFoamMesh(mesh, moved, out, oneThread);
    // Written in full beside the output, which is untouched.
    EXPECT_EQ(readOpenFoamMesh(staged.temporary()).points, moved);
    EXPECT_EQ(entriesOf(dir_), (std::vector<std::string>{staged.temporary().filename().string(), "out"}));
    EXPECT_EQ(entriesOf(out), std::vector<std::string>{"old"});
  }
  EXPECT_EQ(entriesOf(dir_), std::vector<std::string>{"out"});  // dropped: the hidden folder removed
  EXPECT_EQ(fileText(out / "old" / "file"), "old");

  StagedOpenFoamMesh staged = stageOpenFoamMesh(mesh, moved, out, oneThread);
  StagedOpenFoamMesh taken = std::move(staged);  // the moved-from one removes nothing
  EXPECT_TRUE(staged.temporary().empty());
  taken.commit();
  EXPECT_EQ(entriesOf(dir_), std::vector<std::string>{"out"});
  EXPECT_FALSE(fs::exists(out / "old"));
  EXPECT_EQ(readOpenFoamMesh(out).points, moved);
  for (const char* name : {"faces", "owner", "neighbour", "boundary"})
    EXPECT_EQ(fileText(out / "constant" / "polyMesh" / name), fileText(mesh.polyMesh / name)) << name;
}

// A flushed write copies its large files by direct I/O (from 4 MiB on), the last partial block
// through the page cache: the bytes and the permissions are the source's.
TEST_F(OpenFoam, LargeFilesOfAFlushedWriteAreCopiedWhole) {
  const fs::path copy = copyCase("cube-binary");
  std::string bytes(std::size_t(9) << 20 | 123, '\0');
  std::uint32_t state = 12345;
  for (char& b : bytes) b = char((state = state * 1664525u + 1013904223u) >> 24);
  writeText(copy / "constant" / "polyMesh" / "large", bytes);
  writeText(copy / "system" / "whole-blocks", bytes.substr(0, std::size_t(5) << 20));
  fs::permissions(copy / "constant" / "polyMesh" / "large", fs::perms::owner_read | fs::perms::group_read);
  const OpenFoamMesh mesh = readOpenFoamMesh(copy);
  const fs::path out = dir_ / "out";
  writeOpenFoamMesh(mesh, mesh.points * 2.0, out);
  EXPECT_EQ(fileText(out / "constant" / "polyMesh" / "large"), bytes);
  EXPECT_EQ(fileText(out / "system" / "whole-blocks"), bytes.substr(0, std::size_t(5) << 20));
  EXPECT_EQ(fs::status(out / "constant" / "polyMesh" / "large").permissions(), fs::perms::owner_read | fs::perms::group_read);
  EXPECT_EQ(fileText(out / "constant" / "polyMesh" / "faces"), fileText(copy / "constant" / "polyMesh" / "faces"));
  EXPECT_EQ(readOpenFoamMesh(out).points, mesh.points * 2.0);
  EXPECT_EQ(fileText(out / "constant" / "polyMesh" / "points"), foamPointsBytes(mesh.pointsFile, mesh.points * 2.0));
}

// A writer killed while its case was staged leaves a hidden folder; the next write removes it.
TEST_F(OpenFoam, TheHiddenFolderOfAKilledWriterIsRemovedByTheNextWrite) {
  const OpenFoamMesh mesh = readOpenFoamMesh(kData / "cube");
  const fs::path out = dir_ / "out";
  const pid_t child = ::fork();
  if (child == 0) {
    // On this thread alone: OpenMP's threads do not survive a fork.
    auto* leaked = new StagedOpenFoamMesh(stageOpenFoamMesh(mesh, mesh.points, out, {.durable = false, .everyCore = false}));
    (void)leaked;
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
  ASSERT_EQ(names.size(), 1u);
  EXPECT_EQ(names[0].rfind(".out.tmp-" + std::to_string(child) + "-", 0), 0u) << names[0];
  EXPECT_TRUE(fs::exists(dir_ / names[0] / "constant" / "polyMesh" / "points"));
  writeOpenFoamMesh(mesh, mesh.points * 2.0, out, {.durable = false});
  names.clear();
  for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"out"});
  EXPECT_EQ(readOpenFoamMesh(out).points, mesh.points * 2.0);
}

TEST_F(OpenFoam, RefusesAnOutputInsideTheCase) {
  const fs::path copy = copyCase("cube");
  const OpenFoamMesh mesh = readOpenFoamMesh(copy);
  const std::string message = testing::meshIoErrorOf([&] { writeOpenFoamMesh(mesh, mesh.points, copy / "system" / "out"); });
  EXPECT_NE(message.find("inside the folder it copies"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(copy / "system" / "out"));
}

// --- bad input: each a clear message naming the file and the place ---

TEST_F(OpenFoam, LyingPointCountIsRefusedWithFileAndLine) {
  const fs::path copy = copyCase("cube");
  const fs::path points = copy / "constant" / "polyMesh" / "points";
  std::string text = fileText(points);
  text.replace(text.find("\n343\n"), 5, "\n344\n");
  writeText(points, text);
  const std::string message = testing::meshIoErrorOf([&] { readOpenFoamMesh(copy); });
  // Point 343 meets the list's closing ')' on the last line of the list.
  EXPECT_NE(message.find(points.string() + ":364: point 343: expected '('"), std::string::npos) << message;
}

TEST_F(OpenFoam, TruncatedPointsAreRefused) {
  for (const char* name : {"cube", "cube-binary"}) {
    const fs::path copy = copyCase(name);
    const fs::path points = copy / "constant" / "polyMesh" / "points";
    const std::string text = fileText(points);
    writeText(points, text.substr(0, text.size() / 2));
    const std::string message = testing::meshIoErrorOf([&] { readOpenFoamMesh(copy); });
    EXPECT_EQ(message.rfind(points.string() + ":", 0), 0u) << message;
    EXPECT_NE(message.find(std::string(name) == "cube" ? "expected a number, got the end of the file" : "point: a list of 343 needs at least 8232 bytes, the file has"),
              std::string::npos)
        << message;
  }
}

TEST_F(OpenFoam, FaceWithAnOutOfRangePointIsRefused) {
  const fs::path copy = copyCase("cube");
  const fs::path faces = copy / "constant" / "polyMesh" / "faces";
  std::string text = fileText(faces);
  text.replace(text.find("4(1 8 57 50)"), 12, "4(1 8 343 50)");
  writeText(faces, text);
  const std::string message = testing::meshIoErrorOf([&] { readOpenFoamMesh(copy); });
  EXPECT_NE(message.find(faces.string() + ":"), std::string::npos) << message;
  EXPECT_NE(message.find(": 343 is outside 0..342"), std::string::npos) << message;
  EXPECT_NE(message.find("face 0"), std::string::npos) << message;
}

TEST_F(OpenFoam, BinaryFaceWithAnOutOfRangePointIsRefused) {
  const fs::path copy = copyCase("cube-binary");
  const fs::path faces = copy / "constant" / "polyMesh" / "faces";
  std::string text = fileText(faces);
  // The second list (the points of the faces) starts after "3024\n(".
  const std::size_t data = text.find("3024\n(") + 6;
  const std::int32_t bad = 1000;
  std::memcpy(text.data() + data, &bad, sizeof bad);
  writeText(faces, text);
  const std::string message = testing::meshIoErrorOf([&] { readOpenFoamMesh(copy); });
  EXPECT_NE(message.find("face point 0 (binary, offset " + std::to_string(data) + "): 1000 is outside 0..342"),
            std::string::npos)
      << message;
}

TEST_F(OpenFoam, MissingOwnerIsRefused) {
  const fs::path copy = copyCase("cube");
  fs::remove(copy / "constant" / "polyMesh" / "owner");
  const std::string message = testing::meshIoErrorOf([&] { readOpenFoamMesh(copy); });
  EXPECT_NE(message.find("no 'owner' file"), std::string::npos) << message;
}

TEST_F(OpenFoam, OwnerOfTheWrongSizeIsRefused) {
  const fs::path copy = copyCase("cube");
  const fs::path owner = copy / "constant" / "polyMesh" / "owner";
  std::string text = fileText(owner);
  const std::size_t at = text.find("\n756\n(\n");
  text.replace(at, 7, "\n755\n(\n");
  text.erase(text.rfind("\n)") - 4, 4);  // the last label ("215\n" before the ')')
  writeText(owner, text);
  const std::string message = testing::meshIoErrorOf([&] { readOpenFoamMesh(copy); });
  EXPECT_NE(message.find("755 owner cells for the 756 faces"), std::string::npos) << message;
}

TEST_F(OpenFoam, SymbolicLinkOutsideTheCaseIsRefused) {
  const fs::path copy = copyCase("cube");
  const fs::path outside = dir_ / "elsewhere-points";
  fs::copy_file(copy / "constant" / "polyMesh" / "points", outside);
  fs::remove(copy / "constant" / "polyMesh" / "points");
  fs::create_symlink(outside, copy / "constant" / "polyMesh" / "points");
  const std::string message = testing::meshIoErrorOf([&] { readOpenFoamMesh(copy); });
  EXPECT_NE(message.find("a symbolic link that leads outside the folder"), std::string::npos) << message;
  // Allowed explicitly, it reads; a link elsewhere in the case still refuses the copy.
  OpenFoamReadOptions allow;
  allow.confinement.allowOutside = true;
  const OpenFoamMesh mesh = readOpenFoamMesh(copy, allow);
  EXPECT_EQ(mesh.points.rows(), 343);
  fs::create_symlink(outside, copy / "system" / "extra");
  const std::string copyMessage = testing::meshIoErrorOf([&] { writeOpenFoamMesh(mesh, mesh.points, dir_ / "out"); });
  EXPECT_NE(copyMessage.find((copy / "system" / "extra").string() + ": a symbolic link that leads outside"),
            std::string::npos)
      << copyMessage;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(OpenFoam, DecomposedCaseIsRefused) {
  const fs::path copy = copyCase("cube");
  fs::create_directories(copy / "processor0");
  const std::string message = testing::meshIoErrorOf([&] { readOpenFoamMesh(copy); });
  EXPECT_NE(message.find("a decomposed case (processor0/)"), std::string::npos) << message;
}

TEST_F(OpenFoam, BinaryPointsFileIsKeptWithoutItsCoordinates) {
  const OpenFoamMesh mesh = readOpenFoamMesh(kData / "cube-binary");
  const std::string file = fileText(mesh.polyMesh / "points");
  // The 343 points' doubles are left out (the writer puts new ones there); the rest is the file's.
  EXPECT_EQ(mesh.pointsFile.omittedBytes, 343u * 3 * sizeof(double));
  EXPECT_EQ(mesh.pointsFile.listEnd, mesh.pointsFile.listBegin);
  EXPECT_EQ(mesh.pointsFile.bytes, file.substr(0, mesh.pointsFile.listBegin) +
                                       file.substr(mesh.pointsFile.listBegin + mesh.pointsFile.omittedBytes));
  // An ASCII file is kept whole: its unchanged values keep their text.
  const OpenFoamMesh ascii = readOpenFoamMesh(kData / "cube");
  EXPECT_EQ(ascii.pointsFile.omittedBytes, 0u);
  EXPECT_EQ(ascii.pointsFile.bytes, fileText(ascii.polyMesh / "points"));
}

// A binary polyMesh of `count` separate tetrahedra (4 points, 4 boundary faces each, one patch):
// files of several MB, whose lists the reader copies out of the mapped file run by run.
fs::path writeTetrahedraCase(const fs::path& root, int count) {
  const fs::path polyMesh = root / "constant" / "polyMesh";
  fs::create_directories(polyMesh);
  auto header = [](const char* className, const char* object) {
    return std::string("FoamFile\n{\n    version     2.0;\n    format      binary;\n    class       ") + className +
           ";\n    arch        \"LSB;label=32;scalar=64\";\n    object      " + object + ";\n}\n\n";
  };
  // N items of `perItem` values each.
  auto list = [](const auto& values, std::size_t perItem = 1) {
    std::string out = std::to_string(values.size() / perItem) + "\n(";
    out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(values[0]));
    return out + ")\n";
  };
  std::vector<double> points;
  std::vector<std::int32_t> starts{0}, vertices, owner;
  for (int t = 0; t < count; ++t) {
    const double x = t % 1000, y = t / 1000;
    points.insert(points.end(), {x, y, 0, x + 1, y, 0, x, y + 1, 0, x, y, 1});
    const std::int32_t p = 4 * t;
    // Outward normals (right-hand rule): bottom, front, left, slanted.
    for (const auto& face : {std::array{p, p + 2, p + 1}, std::array{p, p + 1, p + 3}, std::array{p, p + 3, p + 2},
                             std::array{p + 1, p + 2, p + 3}}) {
      vertices.insert(vertices.end(), face.begin(), face.end());
      starts.push_back(std::int32_t(vertices.size()));
      owner.push_back(t);
    }
  }
  writeText(polyMesh / "points", header("vectorField", "points") + list(points, 3));
  writeText(polyMesh / "faces", header("faceCompactList", "faces") + list(starts) + list(vertices));
  writeText(polyMesh / "owner", header("labelList", "owner") + list(owner));
  writeText(polyMesh / "neighbour", header("labelList", "neighbour") + list(std::vector<std::int32_t>{}));
  writeText(polyMesh / "boundary", "FoamFile { version 2.0; format ascii; class polyBoundaryMesh; object boundary; }\n1\n(\n"
                                   "tetrahedra { type wall; nFaces " + std::to_string(owner.size()) + "; startFace 0; }\n)\n");
  return root;
}

TEST_F(OpenFoam, LargeBinaryFilesReadRunByRunEqualTheirBytesParsedInMemory) {
  // 300,000 tetrahedra: 1.2M points (29 MB, five runs of the points reader), 3.6M face points
  // (14 MB, two runs of 8 MiB).
  const fs::path root = writeTetrahedraCase(dir_ / "tetrahedra", 300'000);
  const OpenFoamMesh mesh = readOpenFoamMesh(root);
  const fs::path polyMesh = root / "constant" / "polyMesh";
  ReadBudget budget;
  EXPECT_EQ(mesh.points, readFoamPoints(fileText(polyMesh / "points"), "points", budget));
  PolyMeshCells cells;
  readFoamFaces(fileText(polyMesh / "faces"), "faces", mesh.points.rows(), budget, cells);
  EXPECT_EQ(mesh.cells.faceStarts, cells.faceStarts);
  EXPECT_EQ(mesh.cells.faceVertices, cells.faceVertices);
  EXPECT_EQ(mesh.cells.owner, readFoamLabels(fileText(polyMesh / "owner"), "owner", 300'000, budget));
  EXPECT_EQ(mesh.cells.cellCount, 300'000);
  EXPECT_EQ(mesh.pointsFile.omittedBytes, 1'200'000u * 24);
  EXPECT_EQ(foamPointsBytes(mesh.pointsFile, mesh.points), fileText(polyMesh / "points"));
  const CellQuality q = checkPolyMeshCells(mesh.points, mesh.cells);
  EXPECT_TRUE(q.ok());
  // Each tetrahedron holds 1/6 (rounding: its points lie up to 1000 from the origin).
  EXPECT_NEAR(q.minVolume, 1.0 / 6, 1e-12);
  EXPECT_NEAR(q.maxVolume, 1.0 / 6, 1e-12);
  EXPECT_NEAR(q.totalVolume, 300'000.0 / 6, 1e-6);

  // The written points file (from the points, 64 Ki at a time) is foamPointsBytes's, byte for byte,
  // through the page cache and, flushed, by direct I/O (the buffer written out several times).
  Eigen::MatrixX3d moved = mesh.points * 1.25;
  moved(1'199'999, 2) = -0.1;
  for (const bool durable : {false, true}) {
    const fs::path out = dir_ / (durable ? "moved-flushed" : "moved");
    writeOpenFoamMesh(mesh, moved, out, {.durable = durable});
    const fs::path written = out / "constant" / "polyMesh";
    EXPECT_EQ(fileText(written / "points"), foamPointsBytes(mesh.pointsFile, moved)) << durable;
    EXPECT_EQ(readOpenFoamMesh(out, {.readCells = false}).points, moved) << durable;
    EXPECT_EQ(fileText(written / "faces"), fileText(polyMesh / "faces")) << durable;
  }

  // A bad point index in the second run (after the first 8 MiB given back) is found and named.
  const fs::path faces = polyMesh / "faces";
  std::string text = fileText(faces);
  const std::size_t data = text.find("3600000\n(") + 9;
  const std::size_t at = data + 3'000'000 * sizeof(std::int32_t);
  const std::int32_t bad = 1'200'000;
  std::memcpy(text.data() + at, &bad, sizeof bad);
  writeText(faces, text);
  const std::string message = testing::meshIoErrorOf([&] { readOpenFoamMesh(root); });
  EXPECT_NE(message.find("face point 3000000 (binary, offset " + std::to_string(at) + "): 1200000 is outside 0..1199999"),
            std::string::npos)
      << message;
}

TEST_F(OpenFoam, HugeListSizeIsRefusedBeforeAllocating) {
  ReadBudget budget;
  const std::string text = "FoamFile { format ascii; class vectorField; }\n3000000000\n((0 0 0))\n";
  const std::string message = testing::meshIoErrorOf([&] { readFoamPoints(text, "points", budget); });
  EXPECT_NE(message.find("points:2: point (list size): 3000000000 is outside 0..2147483647"), std::string::npos) << message;
  const std::string fits = "FoamFile { format ascii; class vectorField; }\n200000000\n((0 0 0))\n";
  const std::string fitsMessage = testing::meshIoErrorOf([&] { readFoamPoints(fits, "points", budget); });
  EXPECT_NE(fitsMessage.find("points:2: point: a list of 200000000 needs at least 1400000000 bytes, the file has 10 left"),
            std::string::npos)
      << fitsMessage;
  EXPECT_EQ(budget.pointsCharged(), 0u);
}

// --- the cell check ---

// The cube's points as exact sixths, in blockMesh's order (x fastest; ReadsTheAsciiBlockMeshCube
// checks the order), for volumes known to the last bit.
Eigen::MatrixX3d exactCube() {
  Eigen::MatrixX3d points(343, 3);
  for (Eigen::Index k = 0, i = 0; k < 7; ++k)
    for (Eigen::Index j = 0; j < 7; ++j)
      for (Eigen::Index l = 0; l < 7; ++l, ++i) points.row(i) << double(l) / 6, double(j) / 6, double(k) / 6;
  return points;
}

TEST(CellQuality, UnitCubeCellsAreExact) {
  const OpenFoamMesh mesh = readOpenFoamMesh(kData / "cube-binary");
  const CellQuality q = checkPolyMeshCells(exactCube(), mesh.cells);
  EXPECT_TRUE(q.ok());
  EXPECT_EQ(q.cellCount, 216);
  EXPECT_NEAR(q.minVolume, 1.0 / 216, 1e-17);
  EXPECT_NEAR(q.maxVolume, 1.0 / 216, 1e-17);
  EXPECT_NEAR(q.totalVolume, 1.0, 1e-14);
  // A face pyramid of a cube cell: a face (1/36) times half the cell's width (1/12), over 3.
  EXPECT_NEAR(q.minPyramidVolume, 1.0 / 36 / 12 / 3, 1e-17);
  EXPECT_NEAR(q.maxNonOrthogonality, 0.0, 1e-6);
  EXPECT_LT(q.maxSkewness, 1e-12);
}

TEST(CellQuality, AffineMapScalesVolumesByItsDeterminant) {
  const OpenFoamMesh mesh = readOpenFoamMesh(kData / "cube-binary");
  Eigen::Matrix3d a;
  a << 1.2, 0.3, 0.0, 0.0, 0.8, 0.1, 0.2, 0.0, 1.5;
  const Eigen::MatrixX3d mapped = exactCube() * a.transpose();
  const CellQuality q = checkPolyMeshCells(mapped, mesh.cells);
  EXPECT_TRUE(q.ok());
  EXPECT_NEAR(q.minVolume, a.determinant() / 216, 1e-16);
  EXPECT_NEAR(q.maxVolume, a.determinant() / 216, 1e-16);
  EXPECT_NEAR(q.totalVolume, a.determinant(), 1e-14);
  EXPECT_GT(q.maxNonOrthogonality, 1.0);  // a shear tilts the faces against the centre lines
}

TEST(CellQuality, MirroredMeshHasEveryCellAndPyramidInverted) {
  const OpenFoamMesh mesh = readOpenFoamMesh(kData / "cube");
  Eigen::MatrixX3d mirrored = mesh.points;
  mirrored.col(2) *= -1.0;
  const CellQuality q = checkPolyMeshCells(mirrored, mesh.cells, {.listedIds = 3});
  EXPECT_FALSE(q.ok());
  EXPECT_EQ(q.negativeVolumeCells, 216);
  EXPECT_EQ(q.badCells, 216);
  // Every face pyramid: both sides of the 540 internal faces and the 216 boundary faces.
  EXPECT_EQ(q.incorrectlyOrientedFaces, 2 * 540 + 216);
  EXPECT_EQ(q.firstBadCells, (std::vector<std::int64_t>{0, 1, 2}));
  EXPECT_NEAR(q.minVolume, -1.0 / 216, 1e-9);
  EXPECT_NE(badCellsText(q).find("216 of 216 cells inverted or of zero volume (first: 0, 1, 2, ...)"), std::string::npos)
      << badCellsText(q);
}

TEST(CellQuality, CollapsedCellHasZeroVolume) {
  const OpenFoamMesh mesh = readOpenFoamMesh(kData / "cube-binary");
  Eigen::MatrixX3d squashed = mesh.points;
  // The plane z = 1/6 moved onto z = 0: the bottom layer of 36 cells is flat.
  for (Eigen::Index i = 0; i < squashed.rows(); ++i)
    if (std::abs(squashed(i, 2) - 1.0 / 6) < 1e-9) squashed(i, 2) = 0.0;
  const CellQuality q = checkPolyMeshCells(squashed, mesh.cells);
  EXPECT_EQ(q.negativeVolumeCells, 36);
  EXPECT_EQ(q.badCells, 36);
  EXPECT_NEAR(q.minVolume, 0.0, 1e-18);
}

}  // namespace
}  // namespace ffdkit::meshio
