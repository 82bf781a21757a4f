// writeScene follows the reader's confinement rule (meshio/path_confinement.h): a scene written to
// folder F whose mesh paths or widget file lead outside F is refused before anything is written
// (the reader would refuse the file by default, and a widget file would land outside F), with a
// message naming the object, its JSON pointer and the path; PathConfinement::allowOutside writes
// it, and the file then reads back under the same opt-out.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "ffdkit/scenes/scene_file.h"
#include "scenes_test_support.h"

namespace ffdkit::scenes {
namespace {
using test_support::kExamples;
using test_support::contains;

namespace fs = std::filesystem;

// A folder of its own under the temporary directory, removed at the end of the test.
struct ConfinementFolder {
  fs::path root;
  explicit ConfinementFolder(const std::string& name)
      : root(fs::temp_directory_path() / ("ffdkit-write-confinement-" + name + "-" + std::to_string(::getpid()))) {
    fs::remove_all(root);
    fs::create_directories(root);
  }
  ~ConfinementFolder() { fs::remove_all(root); }
};

// The default sample with a point cloud read from `meshPath` (relative to `folder`, or absolute)
// added as its second object, 'cloud'.
Scene withCloud(const fs::path& folder, const std::string& meshPath) {
  Scene scene = readScene(kExamples / "default");
  SceneObject cloud;
  cloud.name = "cloud";
  cloud.source = MeshFileSource{meshPath};
  cloud.mesh = buildObjectMesh(cloud.source, folder, ObjectMeshOptions{.confinement = {.allowOutside = true}});
  scene.addObject(std::move(cloud));
  return scene;
}

std::string writeError(const fs::path& path, const Scene& scene, const SceneWriteOptions& options = {}) {
  try {
    writeScene(path, scene, options);
  } catch (const SceneFileError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneWriteConfinement, AMeshPathOutsideTheFolderIsRefusedNamingTheObjectAndNothingIsWritten) {
  ConfinementFolder dir("mesh");
  fs::create_directories(dir.root / "shared" / "out");
  fs::create_directories(dir.root / "private");
  std::ofstream(dir.root / "private" / "cloud.xyz") << "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  const fs::path out = dir.root / "shared" / "out" / "scene.json";
  for (const std::string& named : {std::string("../../private/cloud.xyz"), (dir.root / "private" / "cloud.xyz").string()}) {
    SCOPED_TRACE(named);
    const Scene scene = withCloud(dir.root / "shared" / "out", named);
    const std::string e = writeError(out, scene);
    EXPECT_TRUE(contains(e, out.string() + " /objects/1/mesh/path: object 'cloud': mesh file '" + named +
                                "' is outside the folder of the file that names it"))
        << e;
    EXPECT_TRUE(contains(e, "nothing written")) << e;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(std::distance(fs::directory_iterator(out.parent_path()), fs::directory_iterator()), 0);  // no temporary
  }
}

TEST(SceneWriteConfinement, AWidgetFileOutsideTheFolderIsNeverWritten) {
  ConfinementFolder dir("widgets");
  fs::create_directories(dir.root / "out");
  Scene scene = readScene(kExamples / "default");
  scene.widgetFile = "../tool.json";
  const fs::path out = dir.root / "out" / "scene.json";
  const std::string e = writeError(out, scene);
  EXPECT_TRUE(contains(e, out.string() + " /widgetFile: widget file '../tool.json' is outside the folder")) << e;
  EXPECT_FALSE(fs::exists(dir.root / "tool.json"));
  EXPECT_FALSE(fs::exists(out));
}

TEST(SceneWriteConfinement, PathsInsideTheFolderAreWrittenAndReadBack) {
  ConfinementFolder dir("inside");
  fs::create_directories(dir.root / "meshes");
  std::ofstream(dir.root / "meshes" / "cloud.xyz") << "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  for (const std::string& named : {std::string("meshes/cloud.xyz"), std::string("meshes/../meshes/cloud.xyz"),
                                   (dir.root / "meshes" / "cloud.xyz").string()}) {
    SCOPED_TRACE(named);
    Scene scene = withCloud(dir.root, named);
    scene.widgetFile = "tool.json";
    ASSERT_EQ(writeError(dir.root / "scene.json", scene), "");
    EXPECT_TRUE(fs::exists(dir.root / "tool.json"));
    const Scene back = readScene(dir.root / "scene.json");  // the reader's default rule
    ASSERT_NE(back.findObject("cloud"), nullptr);
    EXPECT_EQ(back.findObject("cloud")->mesh.points.rows(), 4);
  }
}

TEST(SceneWriteConfinement, AllowOutsideWritesWhatTheReaderReadsWithTheSameOptOut) {
  ConfinementFolder dir("allowed");
  fs::create_directories(dir.root / "out");
  std::ofstream(dir.root / "cloud.xyz") << "0 0 0\n1 0 0\n0 1 0\n";
  const Scene scene = withCloud(dir.root / "out", "../cloud.xyz");
  const fs::path out = dir.root / "out" / "scene.json";
  ASSERT_EQ(writeError(out, scene, SceneWriteOptions{.confinement = {.allowOutside = true}}), "");
  EXPECT_THROW(readScene(out), SceneFileError);  // the default rule still refuses it
  SceneReadOptions allowed;
  allowed.confinement.allowOutside = true;
  const Scene back = readScene(out, allowed);
  EXPECT_EQ(back.findObject("cloud")->mesh.points.rows(), 3);
}

}  // namespace
}  // namespace ffdkit::scenes
