// Objects read from STEP and IGES files (scenes/cad_objects.h): a scene names the part like a mesh
// file and its triangles come from the reader the program registers; without one the scene is
// refused naming the object and the file; the path is confined like a mesh path, before any
// reader runs; a written scene keeps the path and reads back.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "ffdkit/scenes/cad_objects.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::scenes {
namespace {

namespace fs = std::filesystem;

struct CadObjects : ::testing::Test {
  fs::path folder = fs::temp_directory_path() / ("ffdkit-cad-objects-" + std::to_string(::getpid()));
  int reads = 0;
  fs::path readPath;

  void SetUp() override {
    fs::remove_all(folder);
    fs::create_directories(folder);
    std::ofstream(folder / "part.step") << "ISO-10303-21;\n";  // the stub reader does not parse it
    std::ofstream(folder / "scene.json") << R"({"format": "ffdkit-scene", "version": 2,
      "objects": [{"name": "part", "mesh": {"path": "part.step"}}]})";
  }
  void TearDown() override {
    setCadMeshReader({});
    fs::remove_all(folder);
  }
  // A reader that gives a tetrahedron and counts its calls.
  void registerTetrahedron() {
    setCadMeshReader([this](const fs::path& path, meshio::ReadBudget& budget) {
      ++reads;
      readPath = path;
      budget.chargePoints(4, "tetrahedron");
      MeshData mesh;
      mesh.points.resize(4, 3);
      mesh.points << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
      mesh.triangles.resize(4, 3);
      mesh.triangles << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
      return mesh;
    });
  }
};

TEST(CadFiles, KnownByTheirExtensionInAnyCase) {
  for (const char* name : {"a.step", "b.STP", "c.Iges", "d.igs"}) EXPECT_TRUE(isCadFile(name)) << name;
  for (const char* name : {"a.stl", "b.step.bak", "step", "c.obj"}) EXPECT_FALSE(isCadFile(name)) << name;
}

TEST_F(CadObjects, WithoutAReaderTheSceneIsRefusedNamingTheObjectAndTheFile) {
  ASSERT_FALSE(hasCadMeshReader());
  try {
    readScene(folder / "scene.json");
    FAIL() << "read a STEP object without a reader";
  } catch (const SceneFileError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/objects/0"), std::string::npos) << what;
    EXPECT_NE(what.find("object 'part'"), std::string::npos) << what;
    EXPECT_NE(what.find("part.step: a STEP or IGES part; this program reads none"), std::string::npos) << what;
  }
}

TEST_F(CadObjects, TheRegisteredReaderGivesTheTrianglesAndTheWrittenSceneKeepsThePath) {
  registerTetrahedron();
  const Scene scene = readScene(folder / "scene.json");
  EXPECT_EQ(reads, 1);
  EXPECT_EQ(fs::weakly_canonical(readPath), fs::weakly_canonical(folder / "part.step"));
  ASSERT_EQ(scene.objects().size(), 1u);
  EXPECT_EQ(scene.objects().front().mesh.points.rows(), 4);
  EXPECT_EQ(scene.objects().front().mesh.triangles.rows(), 4);
  EXPECT_EQ(std::get<MeshFileSource>(scene.objects().front().source).path, "part.step");
  writeScene(folder / "again.json", scene);
  const Scene again = readScene(folder / "again.json");
  EXPECT_EQ(reads, 2);
  EXPECT_EQ(std::get<MeshFileSource>(again.objects().front().source).path, "part.step");
  EXPECT_TRUE(again.objects().front().mesh.points == scene.objects().front().mesh.points);
}

TEST_F(CadObjects, APathOutsideTheFolderIsRefusedBeforeTheReaderRuns) {
  registerTetrahedron();
  std::ofstream(folder / "outside.json") << R"({"format": "ffdkit-scene", "version": 2,
    "objects": [{"name": "part", "mesh": {"path": "../elsewhere/part.step"}}]})";
  EXPECT_THROW(readScene(folder / "outside.json"), SceneFileError);
  EXPECT_EQ(reads, 0);
}

}  // namespace
}  // namespace ffdkit::scenes
