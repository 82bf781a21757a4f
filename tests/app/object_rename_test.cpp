// A rename is a label change (scenes/object_id.h): renaming an object during a drag, between keyed
// frames and under undo / redo makes the deformer embed nothing and build no lattice. The same
// session is played twice, with and without the renames; the deformer's embedding counters
// (SceneDeformer::totals) and the deformed points must come out the same, and the renamed
// document's file round-trips byte for byte and equals the other's but for the name.
#include <gtest/gtest.h>

#include <sstream>

#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/interaction/timeline.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::app {
namespace {

using widgets::WidgetId;

struct Document {
  scenes::Scene scene = scenes::readScene(FFDKIT_SOURCE_DIR "/scenes/examples/default");
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  InteractionController controller{scene, deformer, commands};
  Timeline timeline{scene, commands, controller};
};

// A ray down the glyph's z through its arrow, shifted `shift` glyph sizes along its x and y.
widgets::Ray glyphRay(const widgets::WidgetModel& model, WidgetId affine, double shift = 0.0) {
  const widgets::WidgetFrame f = model.affineFrame(affine);
  const Eigen::Vector3d x = f.frame.linear().col(0), y = f.frame.linear().col(1), z = f.frame.linear().col(2);
  widgets::Ray ray;
  ray.origin = f.frame.translation() + f.size * ((0.5 + shift) * x + shift * y) + 5.0 * z;
  ray.direction = -z;
  return ray;
}

struct Session {
  std::uint64_t embeds = 0;  // SceneDeformer::totals().reembeddedStages at the end
  std::uint64_t built = 0;   // totals().latticesBuilt at the end
  std::string file;
  Eigen::MatrixX3d points;
};

// The embedding counters do not move across `step` (a rename and the evaluation after it).
template <class Step>
void expectNoEmbedding(Document& d, const char* what, Step step) {
  const scenes::SceneDeformer::Totals before = d.deformer.totals();
  step();
  EXPECT_EQ(d.deformer.totals().reembeddedStages, before.reembeddedStages) << what;
  EXPECT_EQ(d.deformer.totals().latticesBuilt, before.latticesBuilt) << what;
}

Session play(bool rename) {
  Document d;
  d.controller.refresh();
  const WidgetId pull = d.scene.widgets.find("pull");
  const scenes::ObjectId sphere = d.scene.objectId("sphere");
  const double size = d.scene.widgets.affineFrame(pull).size;
  const widgets::Ray start = glyphRay(d.scene.widgets, pull);

  // A drag of the glyph, with a rename in its middle as a script makes it (the scene's own
  // edit: the gesture goes on) and an evaluation after it, as the event loop's next tick.
  EXPECT_EQ(d.controller.press(start, 0.05 * size), InteractionController::PressResult::Widget);
  const Eigen::Vector3d along = d.scene.widgets.affineFrame(pull).frame.linear().col(0);
  auto moved = [&](double by) {
    widgets::Ray ray = start;
    ray.origin += by * size * along;
    return ray;
  };
  d.controller.drag(moved(0.2));
  if (rename) {
    expectNoEmbedding(d, "rename during the drag", [&] {
      d.scene.renameObject(sphere, "ball");
      d.controller.refresh();
    });
  }
  d.controller.drag(moved(0.4));
  d.controller.release();
  EXPECT_TRUE(d.deformer.evaluate(d.scene) == false);  // the release evaluated everything

  // A rename as the user makes it (one undoable command), undone and redone, between keyed frames.
  d.timeline.setFrame(10);
  if (rename) {
    expectNoEmbedding(d, "rename command", [&] { d.controller.renameObject("ball", "planet"); });
    expectNoEmbedding(d, "undo of the rename", [&] { d.commands.undo(); });
    EXPECT_EQ(d.scene.findObject(sphere)->name, "ball");
    expectNoEmbedding(d, "redo of the rename", [&] { d.commands.redo(); });
    EXPECT_EQ(d.scene.findObject(sphere)->name, "planet");
  }
  d.controller.setSelection({pull});
  EXPECT_EQ(d.timeline.insertKeys(), 1);
  d.timeline.setFrame(30);
  d.commands.undo();  // the key
  d.commands.redo();
  d.timeline.setFrame(20);
  EXPECT_EQ(d.scene.objects().front().id, sphere);

  Session s;
  s.embeds = d.deformer.totals().reembeddedStages;
  s.built = d.deformer.totals().latticesBuilt;
  s.file = scenes::sceneFileText(d.scene);
  s.points = d.deformer.points(sphere);
  // The change-driven deformer equals an evaluation from scratch.
  const auto fresh = scenes::deformScene(d.scene);
  EXPECT_LE((s.points - fresh.at(d.scene.objectName(sphere))).cwiseAbs().maxCoeff(), 1e-9);
  return s;
}

TEST(ObjectRename, DuringADragWithKeysUnderUndoRedoNothingIsEmbeddedAgain) {
  const Session plain = play(false);
  const Session renamed = play(true);
  EXPECT_GT(plain.embeds, 0u);  // the counter counts (the first evaluation embeds; keyed frames move the lattice)
  EXPECT_EQ(renamed.embeds, plain.embeds);
  EXPECT_EQ(renamed.built, plain.built);
  EXPECT_EQ(renamed.points, plain.points);

  // The file names the object by its new name, and reads back to the same bytes.
  std::istringstream in(renamed.file);
  scenes::SceneReadOptions options;
  options.baseDirectory = FFDKIT_SOURCE_DIR "/scenes/examples/default";
  EXPECT_EQ(scenes::sceneFileText(scenes::readScene(in, "renamed.json", options)), renamed.file);
  std::string back = renamed.file;
  for (std::size_t at = back.find("\"planet\""); at != std::string::npos; at = back.find("\"planet\"", at))
    back.replace(at, 8, "\"sphere\"");
  EXPECT_EQ(back, plain.file);
}

}  // namespace
}  // namespace ffdkit::app
