// A decomposed OpenFOAM case (meshio/openfoam_decomposed.h): its pieces in order, the layouts it
// refuses, and the all-or-nothing write from pieces into one hidden folder. The processor folders
// here are copies of the committed cube (each a whole mesh); tests/cli/openfoam_mpi_test.sh runs
// decomposePar and reconstructParMesh themselves.
#include "ffdkit/meshio/openfoam_decomposed.h"

#include <unistd.h>

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "scratch_folder.h"
#include "meshio_test_support.h"

namespace ffdkit::meshio {
namespace {
using test_support::fileText;

namespace fs = std::filesystem;

const fs::path kCube = fs::path(FFDKIT_SOURCE_DIR) / "tests" / "data" / "openfoam" / "cube";

class DecomposedOpenFoam : public testing::ScratchFolderTest {
 protected:
  DecomposedOpenFoam() : ScratchFolderTest("decomposed") {}
  void SetUp() override {
    ScratchFolderTest::SetUp();
    case_ = dir_ / "case";
    fs::copy(kCube, case_, fs::copy_options::recursive);
    for (int p = 0; p < 3; ++p) {
      const fs::path processor = case_ / ("processor" + std::to_string(p));
      fs::create_directories(processor / "constant");
      fs::copy(kCube / "constant" / "polyMesh", processor / "constant" / "polyMesh", fs::copy_options::recursive);
      fs::create_directories(processor / "0");
      std::ofstream(processor / "0" / "U") << "a field of processor " << p << "\n";
    }
  }
  // Only the output folder is beside the case: no hidden staging folder is left.
  void expectNoTemporaries() {
    for (const auto& entry : fs::directory_iterator(dir_))
      EXPECT_NE(entry.path().filename().string()[0], '.') << entry.path();
  }
  fs::path case_;
};

TEST_F(DecomposedOpenFoam, FindsTheReconstructedMeshThenTheProcessorsInNumberOrder) {
  fs::rename(case_ / "processor2", case_ / "processor10");  // 10 sorts before 2 as text
  fs::rename(case_ / "processor1", case_ / "processor2");
  fs::rename(case_ / "processor10", case_ / "processor1");
  ASSERT_TRUE(isDecomposedOpenFoamCase(case_));
  EXPECT_FALSE(isDecomposedOpenFoamCase(kCube));
  const DecomposedCase decomposed = findDecomposedCase(case_);
  ASSERT_EQ(decomposed.pieces.size(), 4u);
  EXPECT_EQ(decomposed.processorCount, 3u);
  EXPECT_TRUE(decomposed.pieces[0].reconstructed);
  EXPECT_EQ(decomposed.pieces[0].relative, fs::path("constant") / "polyMesh");
  for (int p = 0; p < 3; ++p) {
    EXPECT_EQ(decomposed.pieces[p + 1].name, "processor" + std::to_string(p));
    EXPECT_FALSE(decomposed.pieces[p + 1].reconstructed);
  }
  // Without the reconstructed mesh, only the processors.
  fs::remove_all(case_ / "constant" / "polyMesh");
  EXPECT_EQ(findDecomposedCase(case_).pieces.size(), 3u);
}

TEST_F(DecomposedOpenFoam, RefusesAGapInTheNumbering) {
  fs::remove_all(case_ / "processor1");
  const std::string message = testing::meshIoErrorOf([&] { findDecomposedCase(case_); });
  EXPECT_NE(message.find("processor1 is missing (found processor2"), std::string::npos) << message;
}

TEST_F(DecomposedOpenFoam, RefusesTheCollatedLayoutAndAProcessorWithoutMesh) {
  fs::create_directories(case_ / "processors3");
  std::string message = testing::meshIoErrorOf([&] { findDecomposedCase(case_); });
  EXPECT_NE(message.find("processors3: not a processor folder"), std::string::npos) << message;
  EXPECT_NE(message.find("collated"), std::string::npos) << message;
  fs::remove_all(case_ / "processors3");
  fs::remove_all(case_ / "processor2" / "constant");
  message = testing::meshIoErrorOf([&] { findDecomposedCase(case_); });
  EXPECT_NE(message.find("processor2: no constant/polyMesh/points"), std::string::npos) << message;
}

TEST_F(DecomposedOpenFoam, PiecesWrittenIntoTheStagingFolderMakeTheWholeCase) {
  const DecomposedCase decomposed = findDecomposedCase(case_);
  const fs::path out = dir_ / "out";
  const fs::path staging = stageDecomposedCase(decomposed, out, {.durable = false});
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(staging / "processor0"));
  EXPECT_FALSE(fs::exists(staging / "constant" / "polyMesh" / "points"));
  EXPECT_TRUE(fs::exists(staging / "constant" / "polyMesh" / "faces"));
  std::vector<Eigen::MatrixX3d> moved;
  for (std::size_t i = 0; i < decomposed.pieces.size(); ++i) {
    const OpenFoamMesh mesh = readDecomposedCasePiece(decomposed.pieces[i]);
    moved.push_back(mesh.points * double(i + 2));
    writeDecomposedCasePiece(decomposed.pieces[i], mesh, moved.back(), staging, {.durable = false});
  }
  commitDecomposedCase(staging, out, {.durable = false});
  expectNoTemporaries();
  // Every file is the case's but the points, which hold each piece's new values.
  std::size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(case_)) {
    if (!entry.is_regular_file()) continue;
    ++files;
    const fs::path relative = fs::relative(entry.path(), case_);
    ASSERT_TRUE(fs::exists(out / relative)) << relative;
    if (relative.filename() != "points") {
      EXPECT_EQ(fileText(out / relative), fileText(entry.path())) << relative;
    }
  }
  std::size_t written = 0;
  for (const auto& entry : fs::recursive_directory_iterator(out)) written += entry.is_regular_file() ? 1 : 0;
  EXPECT_EQ(written, files);
  EXPECT_EQ(readOpenFoamMesh(out / "constant" / "polyMesh").points, moved[0]);
  for (int p = 0; p < 3; ++p)
    EXPECT_EQ(readOpenFoamMesh(out / ("processor" + std::to_string(p))).points, moved[std::size_t(p) + 1]) << p;
}

TEST_F(DecomposedOpenFoam, AFailedPieceLeavesTheOutputAsItWas) {
  const DecomposedCase decomposed = findDecomposedCase(case_);
  const fs::path out = dir_ / "out";
  fs::create_directories(out);
  std::ofstream(out / "old") << "the previous output";
  const fs::path staging = stageDecomposedCase(decomposed, out, {.durable = false});
  const OpenFoamMesh mesh = readDecomposedCasePiece(decomposed.pieces[1]);
  const Eigen::MatrixX3d tooFew = mesh.points.topRows(10);
  const std::string message =
      testing::meshIoErrorOf([&] { writeDecomposedCasePiece(decomposed.pieces[1], mesh, tooFew, staging, {.durable = false}); });
  EXPECT_EQ(message.rfind(decomposed.pieces[1].folder.string() + ": ", 0), 0u) << message;
  EXPECT_NE(message.find("10 points given for a file with more"), std::string::npos) << message;
  fs::remove_all(staging);  // what the batch does when a piece fails
  expectNoTemporaries();
  EXPECT_EQ(fileText(out / "old"), "the previous output");
}

TEST_F(DecomposedOpenFoam, RefusesAnOutputInsideTheCaseBeforeCopying) {
  const std::string message = testing::meshIoErrorOf([&] { stageDecomposedCase(findDecomposedCase(case_), case_ / "out"); });
  EXPECT_NE(message.find("inside the folder it copies"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(case_ / "out"));
  for (const auto& entry : fs::directory_iterator(case_))
    EXPECT_NE(entry.path().filename().string()[0], '.') << entry.path();
}

TEST_F(DecomposedOpenFoam, AProcessorFolderIsReadAsACase) {
  const DecomposedCase decomposed = findDecomposedCase(case_);
  const OpenFoamMesh mesh = readDecomposedCasePiece(decomposed.pieces[2]);
  EXPECT_EQ(mesh.points.rows(), 343);
  EXPECT_EQ(mesh.cells.cellCount, 216);
  // The case itself is refused by the one-mesh reader, with a message that says what to do.
  const std::string message = testing::meshIoErrorOf([&] { readOpenFoamMesh(case_); });
  EXPECT_NE(message.find("a decomposed case (processor"), std::string::npos) << message;
}

}  // namespace
}  // namespace ffdkit::meshio
