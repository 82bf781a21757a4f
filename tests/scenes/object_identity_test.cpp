// Object identity (scenes/object_id.h): an object is held by its ObjectId everywhere (attachments,
// the deformer's pipelines, the change set); its name is a label. A rename changes the name only:
// no pipeline is rebuilt and nothing is embedded again, in the middle of a gesture too; the scene
// file still names objects and reads and writes byte for byte as before.
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include "ffdkit/scenes/scene_changes.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"
#include "scenes_test_support.h"

namespace ffdkit::scenes {
namespace {
using test_support::kExamples;
using test_support::sphereObject;

TEST(ObjectIdentity, TheSceneGivesEachObjectAnIdThatARenameKeeps) {
  Scene scene;
  const ObjectId a = scene.addObject(sphereObject("a"));
  const ObjectId b = scene.addObject(sphereObject("b"));
  EXPECT_TRUE(a.valid());
  EXPECT_NE(a, b);
  EXPECT_EQ(scene.objectId("a"), a);
  EXPECT_EQ(scene.findObject(b)->name, "b");
  const widgets::WidgetId lattice = attachNewLattice(scene, {"a", "b"});
  scene.renameObject(a, "c");
  EXPECT_EQ(scene.objectId("c"), a);
  EXPECT_EQ(scene.findObject("a"), nullptr);
  EXPECT_EQ(scene.attachments().front().objects, (std::vector<ObjectId>{a, b}));
  EXPECT_EQ(scene.latticesDeforming("c"), std::vector<widgets::WidgetId>{lattice});
  EXPECT_THROW(scene.renameObject(b, "c"), std::invalid_argument);  // names stay unique
  EXPECT_THROW(scene.objectName(ObjectId{99}), std::invalid_argument);
}

TEST(ObjectIdentity, AnObjectTakenOutAndPutBackKeepsItsIdAndANewObjectGetsAFreshOne) {
  Scene scene;
  const ObjectId a = scene.addObject(sphereObject("a"));
  const ObjectId b = scene.addObject(sphereObject("b"));
  SceneObject taken = scene.takeObject(a);
  EXPECT_EQ(taken.id, a);
  EXPECT_EQ(scene.insertObject(0, std::move(taken)), a);  // an undo puts the same object back
  const ObjectId c = scene.addObject(sphereObject("c"));
  EXPECT_NE(c, a);
  EXPECT_NE(c, b);
  SceneObject copy = *scene.findObject(b);
  copy.name = "copy of b";
  EXPECT_NE(scene.addObject(std::move(copy)), b);  // an id another object holds is not taken over
  EXPECT_NO_THROW(validateScene(scene));
}

TEST(ObjectIdentity, TheChangeSetNamesObjectsById) {
  Scene scene;
  const ObjectId a = scene.addObject(sphereObject("a"));
  const SceneMark mark = markOf(scene);
  scene.renameObject(a, "b");
  scene.setObjectMesh("b", sphereObject("b", 8).mesh);
  const SceneChanges changes = changesSince(scene, mark);
  EXPECT_TRUE(changes.structure);  // the outliner shows the new name
  EXPECT_EQ(changes.meshes, std::vector<ObjectId>{a});
}

// A drag (gesture steps of one lattice) with a rename in the middle: the object keeps its pipeline,
// nothing is embedded and no lattice is built after the first evaluation, and the result is that
// of a scene evaluated from scratch under the new name.
TEST(ObjectIdentity, ARenameDuringAGestureEmbedsNothingAndBuildsNoLattice) {
  Scene scene;
  scene.addObject(sphereObject("ball", 24));
  scene.addObject(sphereObject("moon", 8));
  AttachOptions options;
  options.counts = {4, 4, 4};
  const widgets::WidgetId lattice = attachNewLattice(scene, {"ball", "moon"}, options);
  SceneDeformer deformer;
  deformer.update(scene, lattice);
  const SceneDeformer::Totals before = deformer.totals();
  EXPECT_GT(before.reembeddedStages, 0u);  // the counter counts: the first evaluation embeds
  const std::uint64_t revisionBefore = deformer.revision(scene.objectId("ball"));

  const Eigen::Index corner = scene.widgets.controlPoints(lattice).rows() - 1;
  for (int step = 1; step <= 6; ++step) {
    Eigen::MatrixX3d control = scene.widgets.controlPoints(lattice);
    control.row(corner) += Eigen::RowVector3d(0.02, 0.01, 0.03);
    scene.widgets.setControlPoints(lattice, control);
    if (step == 3) scene.renameObject("ball", "sphere");
    if (step == 5) scene.renameObject("sphere", "ball 2");
    deformer.updateGesture(scene, lattice);
    EXPECT_EQ(deformer.lastStats().reembeddedStages, 0) << "step " << step;
    EXPECT_EQ(deformer.lastStats().latticesBuilt, 0) << "step " << step;
  }
  deformer.finishGesture(scene);
  EXPECT_EQ(deformer.totals().reembeddedStages, before.reembeddedStages);
  EXPECT_EQ(deformer.totals().latticesBuilt, before.latticesBuilt);
  EXPECT_GT(deformer.revision(scene.objectId("ball 2")), revisionBefore);  // it did move

  // The same scene from scratch (a fresh deformer reads it anew): the same points, bit for bit
  // (finishGesture evaluates exactly).
  const std::map<std::string, Eigen::MatrixX3d> fresh = deformScene(scene);
  for (const SceneObject& object : scene.objects()) {
    ASSERT_TRUE(fresh.count(object.name)) << object.name;
    EXPECT_EQ(deformer.points(object.id), fresh.at(object.name)) << object.name;
  }
  EXPECT_EQ(deformer.points("ball 2"), deformer.points(scene.objectId("ball 2")));  // the label reads the same object
  EXPECT_THROW((void)deformer.points("ball"), std::invalid_argument);  // the old name is gone
}

TEST(ObjectIdentity, ARenamedSceneRoundTripsThroughItsFileByteForByte) {
  Scene scene;
  scene.addObject(sphereObject("a"));
  scene.addObject(sphereObject("b"));
  attachNewLattice(scene, {"a", "b"});
  attachNewLattice(scene, {"b"});
  scene.renameObject("a", "renamed");
  const std::string text = sceneFileText(scene);
  EXPECT_NE(text.find("\"renamed\""), std::string::npos);  // the file names objects
  std::istringstream in(text);
  const Scene read = readScene(in, "renamed.json");
  EXPECT_EQ(sceneFileText(read), text);
  ASSERT_EQ(read.attachments().size(), 2u);
  EXPECT_EQ(read.objectName(read.attachments()[0].objects[0]), "renamed");
  EXPECT_EQ(read.objectName(read.attachments()[1].objects[0]), "b");
}

// Every sample scene (written before objects had ids) reads, gives ids in file order and writes
// back byte for byte what a second read and write give.
TEST(ObjectIdentity, SampleScenesReadWithIdsInFileOrderAndRoundTrip) {
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kExamples)) {
    if (!std::filesystem::exists(entry.path() / "scene.json")) continue;
    const Scene scene = readScene(entry.path() / "scene.json");
    for (std::size_t i = 0; i < scene.objects().size(); ++i)
      EXPECT_EQ(scene.objects()[i].id, ObjectId{static_cast<std::uint32_t>(i)}) << entry.path();
    const std::string once = sceneFileText(scene);
    std::istringstream in(once);
    SceneReadOptions options;
    options.baseDirectory = entry.path();
    EXPECT_EQ(sceneFileText(readScene(in, (entry.path() / "scene.json").string(), options)), once) << entry.path();
    ++scenes;
  }
  EXPECT_GE(scenes, 10);
}

TEST(ObjectIdentity, AFileAttachingAnUnknownObjectNamesItsPlace) {
  Scene scene;
  scene.addObject(sphereObject("ball", 6));
  scene.addObject(sphereObject("moon", 6));
  attachNewLattice(scene, {"ball", "moon"});
  // The object is renamed in the file but not in its attachment.
  std::string text = sceneFileText(scene);
  const std::size_t named = text.find("\"name\": \"moon\"");
  ASSERT_NE(named, std::string::npos);
  text.replace(named, 14, "\"name\": \"mars\"");
  std::istringstream in(text);
  try {
    (void)readScene(in, "moon.json");
    FAIL() << "read a scene attaching an unknown object";
  } catch (const SceneFileError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("moon.json /attachments/0/objects/1"), std::string::npos) << message;
    EXPECT_NE(message.find("unknown object 'moon'"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace ffdkit::scenes
