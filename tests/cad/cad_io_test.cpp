#include "ffdkit/cad/cad_io.h"

#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "cad_test_support.h"
#include "ffdkit/cad/cad_check.h"
#include "ffdkit/cad/cad_error.h"
#include "ffdkit/cad/sample_parts.h"

namespace ffdkit::cad {
namespace {

namespace fs = std::filesystem;
using test::ScratchFolder;

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// Reading `path` throws a CadError whose message contains the file name and `expected`.
void expectReadError(const fs::path& path, const std::string& expected, const CadReadOptions& options = {}) {
  try {
    readCad(path, options);
    FAIL() << path << " was read";
  } catch (const CadError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
}

TEST(CadIo, StepRoundTripKeepsPartsNamesPlacementsAndVolume) {
  ScratchFolder folder;
  const CadModel model = makeSamplePart(SamplePart::TwoPartAssembly);
  const fs::path file = folder / "assembly.step";
  writeStep(model, file);
  const CadModel back = readStep(file);
  ASSERT_EQ(back.partCount(), 2);
  EXPECT_EQ(back.partName(0), "plate");
  EXPECT_EQ(back.partName(1), "post");
  // plate 80 x 50 x 10, post r = 10, h = 40 standing on it at (40, 25, 10)
  const double expected = 80.0 * 50.0 * 10.0 + M_PI * 100.0 * 40.0;
  EXPECT_NEAR(checkModel(back).volume, expected, 1e-6 * expected);
  EXPECT_TRUE(checkModel(back).valid) << checkModel(back).firstProblem;
  const Eigen::AlignedBox3d box = back.bounds();
  EXPECT_NEAR(box.max().z(), 50.0, 1e-3);
  EXPECT_NEAR(box.min().x(), 0.0, 1e-3);
  EXPECT_NEAR(box.max().x(), 80.0, 1e-3);
}

TEST(CadIo, StepFileDeclaresAp214) {
  ScratchFolder folder;
  writeStep(makeSamplePart(SamplePart::FilletedBox), folder / "box.stp");
  const std::string text = readText(folder / "box.stp");
  EXPECT_NE(text.find("AUTOMOTIVE_DESIGN"), std::string::npos) << text.substr(0, 600);
}

TEST(CadIo, StepStreamReaderReadsWhatThePathReaderReads) {
  ScratchFolder folder;
  writeStep(makeSamplePart(SamplePart::Bottle), folder / "bottle.step");
  std::istringstream in(readText(folder / "bottle.step"));
  const CadModel fromStream = readStep(in, "bottle (stream)");
  const CadModel fromPath = readStep(folder / "bottle.step");
  EXPECT_EQ(fromStream.counts().faces, fromPath.counts().faces);
  EXPECT_NEAR(checkModel(fromStream).volume, checkModel(fromPath).volume, 1e-9 * checkModel(fromPath).volume);
}

TEST(CadIo, IgesRoundTripKeepsTheSolidsVolume) {
  ScratchFolder folder;
  const CadModel model = makeSamplePart(SamplePart::FilletedBox);
  writeIges(model, folder / "box.igs");
  const CadModel back = readIges(folder / "box.igs");
  ASSERT_GE(back.partCount(), 1);
  const double volume = checkModel(model).volume;
  EXPECT_GT(volume, 0.9 * 60 * 40 * 30);
  EXPECT_NEAR(checkModel(back).volume, volume, 1e-6 * volume);
}

TEST(CadIo, WriteFailureLeavesTheTargetAsItWas) {
  ScratchFolder folder;
  EXPECT_THROW(writeStep(makeSamplePart(SamplePart::FilletedBox), folder / "no-such-folder" / "x.step"), CadError);
  EXPECT_FALSE(fs::exists(folder / "no-such-folder"));
}

TEST(CadIo, MissingFileIsNamed) {
  ScratchFolder folder;
  expectReadError(folder / "absent.step", "no such file");
}

TEST(CadIo, FolderIsNotAFile) {
  ScratchFolder folder;
  fs::create_directories(folder / "dir.step");
  expectReadError(folder / "dir.step", "not a regular file");
}

TEST(CadIo, GarbageIsNotStep) {
  ScratchFolder folder;
  writeText(folder / "garbage.step", "this is not a STEP file\n\x01\x02\x03");
  expectReadError(folder / "garbage.step", "STEP");
}

TEST(CadIo, EmptyFilesAreRefused) {
  ScratchFolder folder;
  writeText(folder / "empty.step", "");
  writeText(folder / "empty.igs", "");
  expectReadError(folder / "empty.step", "STEP");
  expectReadError(folder / "empty.igs", "IGES");
}

TEST(CadIo, TruncatedStepIsAnErrorOrFewerShapesNeverACrash) {
  ScratchFolder folder;
  writeStep(makeSamplePart(SamplePart::Bottle), folder / "whole.step");
  const std::string text = readText(folder / "whole.step");
  for (double fraction : {0.1, 0.5, 0.9}) {
    const fs::path cut = folder / ("cut-" + std::to_string(int(fraction * 100)) + ".step");
    writeText(cut, text.substr(0, static_cast<std::size_t>(fraction * text.size())));
    try {
      const CadModel model = readStep(cut);
      EXPECT_LE(model.counts().faces, makeSamplePart(SamplePart::Bottle).counts().faces);
    } catch (const CadError& error) {
      EXPECT_NE(std::string(error.what()).find(cut.string()), std::string::npos) << error.what();
    }
  }
}

TEST(CadIo, StepWithDanglingReferencesIsAnError) {
  ScratchFolder folder;
  writeText(folder / "dangling.step",
            "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('x','',(''),(''),'','','');\n"
            "FILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n"
            "#1=MANIFOLD_SOLID_BREP('',#2);\n#2=CLOSED_SHELL('',(#3,#3,#1));\n#3=ADVANCED_FACE('',(#9),#1,.T.);\n"
            "ENDSEC;\nEND-ISO-10303-21;\n");
  expectReadError(folder / "dangling.step", "dangling.step");
}

TEST(CadIo, AFileThatCrashesOpenCascadeIsACadError) {
  // Found by fuzz_cad_step: OpenCASCADE dereferences a null point entity of this file (SIGSEGV).
  // The reading process dies, this one reports it.
  const fs::path file = "../fuzz/regressions/fuzz_cad_step/occt-null-cartesian-point.step";
  ASSERT_TRUE(fs::exists(file));
  expectReadError(file, "crashed");
}

TEST(CadIo, ReadingInThisProcessGivesTheSameModel) {
  ScratchFolder folder;
  writeStep(makeSamplePart(SamplePart::TwoPartAssembly), folder / "a.step");
  CadReadOptions here;
  here.isolate = false;
  const CadModel inProcess = readStep(folder / "a.step", here);
  const CadModel isolated = readStep(folder / "a.step");
  ASSERT_EQ(isolated.partCount(), inProcess.partCount());
  EXPECT_EQ(isolated.partName(1), inProcess.partName(1));
  EXPECT_NEAR(checkModel(isolated).volume, checkModel(inProcess).volume, 1e-9 * checkModel(inProcess).volume);
}

TEST(CadIo, LargerThanTheLimitIsRefusedBeforeParsing) {
  ScratchFolder folder;
  writeStep(makeSamplePart(SamplePart::FilletedBox), folder / "box.step");
  CadReadOptions options;
  options.maxFileBytes = 1000;
  expectReadError(folder / "box.step", "maxFileBytes", options);
}

TEST(CadIo, UnknownExtensionIsRefused) {
  ScratchFolder folder;
  writeText(folder / "part.obj", "v 0 0 0\n");
  expectReadError(folder / "part.obj", "not a CAD file name");
  EXPECT_FALSE(cadFormatOf("x.obj").has_value());
  EXPECT_EQ(cadFormatOf("X.STP"), CadFormat::Step);
  EXPECT_EQ(cadFormatOf("x.iges"), CadFormat::Iges);
}

}  // namespace
}  // namespace ffdkit::cad
