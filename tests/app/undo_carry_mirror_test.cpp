// Frame changes and undo after them on the mirror sample, headless. Its keyed push moves the
// front face along the face's fitted frame, and its keyed pull tilts that face (it moves the
// face's top edge): the push's direction depends on the pull. Winding the variations straight
// from one frame's values to the next left the front face up to 0.03 off after a frame change
// there and back (scenes::applyAnimatedValues now unwinds and winds them in order), which the
// monkey test met with seed 3 as an undo to the start that missed the file.
#include <gtest/gtest.h>

#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "ffdkit/interaction/edit_controller.h"
#include "ffdkit/interaction/timeline.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"
#include "number_text_difference.h"

namespace ffdkit::app {
namespace {

using widgets::WidgetId;

const std::string kMirror = FFDKIT_SOURCE_DIR "/scenes/examples/mirror";
/// Undo after frame changes carries the written-back values through the bindings; rounding only.
constexpr double kTolerance = 1e-9;

struct Document {
  scenes::Scene scene = scenes::readScene(kMirror);
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  InteractionController controller{scene, deformer, commands};
  EditController edit{scene, deformer, commands, controller};
  Timeline timeline{scene, commands, controller};
};

widgets::Ray downAt(const Eigen::Vector3d& p) {
  widgets::Ray r;
  r.origin = p + Eigen::Vector3d(0, 0, 10);
  r.direction = {0, 0, -1};
  return r;
}

struct Trial {
  int turnFrame = 0, dragFrame = 0, lastFrame = 0;
  std::vector<Eigen::Index> points;
  int axis = 0;
  double degrees = 0;
  std::string widget;
  double value = 0;
};

/// The largest difference of the lattice's points and every variation from the file at frame 0
/// after the trial's edits and undoing them all at frame 0.
double undoneDifference(const Trial& t) {
  Document d;
  const WidgetId lattice = d.scene.widgets.find("lattice");
  d.timeline.setFrame(t.turnFrame);
  d.edit.setMirror(1);
  d.edit.enter(lattice);
  if (!t.points.empty()) {
    d.edit.pickMany(t.points, SelectMode::Replace);
    d.edit.beginModal(TransformMode::Rotate, downAt(*d.edit.pivotPoint()), {0, 0, -1});
    d.edit.modal()->setConstraint({t.axis, false});
    for (char c : std::to_string(t.degrees)) d.edit.modal()->typed().type(c);
    d.edit.update(downAt(*d.edit.pivotPoint()), false);
    d.edit.confirm();
  }
  d.edit.exit();
  d.timeline.setFrame(t.dragFrame);
  if (!t.widget.empty()) {
    const WidgetId w = d.scene.widgets.find(t.widget);
    d.controller.setVariation(w, d.scene.widgets.variation(w) + t.value);
  }
  d.timeline.setFrame(t.lastFrame);
  d.timeline.setFrame(0);
  while (d.commands.canUndo()) d.commands.undo();
  scenes::Scene file = scenes::readScene(kMirror);
  scenes::applyAnimationFrame(file, 0);
  double worst = (d.scene.widgets.controlPoints(lattice) - file.widgets.controlPoints(file.widgets.find("lattice")))
                     .cwiseAbs()
                     .maxCoeff();
  for (WidgetId w : file.widgets.widgets(widgets::WidgetType::Affine))
    worst = std::max(worst, std::abs(d.scene.widgets.variation(d.scene.widgets.find(file.widgets.name(w))) -
                                     file.widgets.variation(w)));
  return worst;
}

TEST(AnimationRoundTrip, AFrameChangeThereAndBackIsExactOnTheMirrorSample) {
  scenes::Scene scene = scenes::readScene(kMirror);
  const WidgetId lattice = scene.widgets.find("lattice");
  scenes::applyAnimationFrame(scene, 0);
  const Eigen::MatrixX3d atZero = scene.widgets.controlPoints(lattice);
  // Frames where both the push (smooth, 0 at frames 0 and 72) and the pull (0.15 from frame 24)
  // are not 0, reached from 0 and from one another.
  for (int frame : {30, 36, 50, 71}) {
    scenes::applyAnimationFrame(scene, frame);
    const Eigen::MatrixX3d there = scene.widgets.controlPoints(lattice);
    scenes::applyAnimationFrame(scene, 72);
    scenes::applyAnimationFrame(scene, frame);
    EXPECT_LE((scene.widgets.controlPoints(lattice) - there).cwiseAbs().maxCoeff(), 1e-12) << "frame " << frame << " from 72";
    scenes::applyAnimationFrame(scene, 0);
    EXPECT_LE((scene.widgets.controlPoints(lattice) - atZero).cwiseAbs().maxCoeff(), 1e-12) << "back to 0 from " << frame;
  }
}

TEST(UndoCarryMirror, TurnsAndBoundWidgetChangesBetweenFrameChangesUndoToTheFile) {
  // The monkey's case: a mirrored turn of lattice points in the edit mode and a change of a
  // bound widget, each at a frame of its own, frame changes after them, then undo at frame 0.
  std::mt19937 rng(5);
  const std::vector<std::string> names{"", "push-front", "push-back", "turn-front", "turn-back", "pull-front", "pull-back"};
  double worst = 0.0;
  for (int trial = 0; trial < 100; ++trial) {
    Trial t;
    t.turnFrame = static_cast<int>(rng() % 73);
    t.dragFrame = static_cast<int>(rng() % 73);
    t.lastFrame = static_cast<int>(rng() % 73);
    const int count = 1 + static_cast<int>(rng() % 4);
    for (int i = 0; i < count; ++i) t.points.push_back(static_cast<Eigen::Index>(rng() % 12));
    t.axis = static_cast<int>(rng() % 3);
    t.degrees = 5.0 + static_cast<double>(rng() % 40);
    t.widget = names[rng() % names.size()];
    t.value = 0.05 + 0.01 * static_cast<double>(rng() % 20);
    const double off = undoneDifference(t);
    worst = std::max(worst, off);
    EXPECT_LE(off, kTolerance) << "trial " << trial << ": turn at frame " << t.turnFrame << " about axis " << t.axis << " by "
                               << t.degrees << " degrees; " << (t.widget.empty() ? "no widget" : t.widget) << " +" << t.value
                               << " at frame " << t.dragFrame << "; then frames " << t.lastFrame << " and 0";
  }
  std::cerr << "largest difference from the file at frame 0: " << worst << "\n";
}

/// The largest difference of two scenes' texts (numbers relative to 1 + their size); 1 when
/// more than numbers differ.
double textDifference(const scenes::Scene& a, const std::string& b) {
  return testing::largestNumberDifference(scenes::sceneFileText(a), b).value_or(1.0);
}

TEST(UndoCarryMirror, AKeyedBoundPairUndoneAndRedoneAroundAScrubToTheFrameShownGivesTheSceneBeforeTheUndo) {
  // The monkey's case (seed 1, 10,000 actions, the mirror segment): push-back, bound two-way to
  // the keyed push-front, is changed and keyed too; frame changes follow. A frame then winds
  // push-front to its key and push-back to its own, which takes push-front with it: the model
  // shows push-front where the binding puts it, not at its key. An undo carried to the frame
  // shown used to set the channels back to the values shown before it, so the undo of the key
  // left push-front at the binding's value, a pose no frame change gives: a scrub to the same
  // frame then moved the scene (0.3 here), and the redo after it, carried from that other state,
  // missed the scene before the undo. Now a carried undo or redo ends at the animation's pose for
  // the time shown, as a frame change does: the scrub changes nothing, and redo gives the scene
  // before the undo.
  Document d;
  const WidgetId pushBack = d.scene.widgets.find("push-back");
  const WidgetId pushFront = d.scene.widgets.find("push-front");
  const WidgetId lattice = d.scene.widgets.find("lattice");
  d.timeline.setFrame(0);
  d.controller.setVariation(pushBack, 0.3);  // push-front follows (variation binding, gain 1)
  ASSERT_NEAR(d.scene.widgets.variation(pushFront), 0.3, 1e-12);
  d.controller.setSelection({pushBack});
  ASSERT_EQ(d.timeline.insertKeys(), 1);
  // A mirrored turn of two lattice points at frame 36, where the keyed push and pull are set.
  d.timeline.setFrame(36);
  d.edit.setMirror(1);
  d.edit.enter(lattice);
  d.edit.pickMany({0, 6}, SelectMode::Replace);
  d.edit.beginModal(TransformMode::Rotate, downAt(*d.edit.pivotPoint()), {0, 0, -1});
  d.edit.modal()->setConstraint({2, false});
  for (char c : std::string("25")) d.edit.modal()->typed().type(c);
  d.edit.update(downAt(*d.edit.pivotPoint()), false);
  d.edit.confirm();
  d.edit.exit();
  d.timeline.setFrame(50);
  d.timeline.setFrame(0);
  ASSERT_EQ(d.commands.position(), 3u);
  const std::string edited = scenes::sceneFileText(d.scene);
  ASSERT_GT(std::abs(d.scene.widgets.variation(pushFront)), 0.1) << "push-front shows the binding's value, not its key's 0";

  // The monkey's walk: undo all, one scrub to the frame shown, redo all. Every undo leaves a pose
  // a frame change gives (checked on a copy of the scene, so the walk is not changed by it).
  std::vector<std::string> before;  // the scene before each undo
  std::vector<std::string> undone;  // the scene after each undo
  std::vector<std::string> moved;   // undos whose pose a scrub to the frame shown moves
  while (d.commands.canUndo()) {
    before.push_back(scenes::sceneFileText(d.scene));
    const std::string description = d.commands.undoDescription();
    d.commands.undo();
    undone.push_back(scenes::sceneFileText(d.scene));
    scenes::Scene scrubbed = d.scene;
    scenes::applyAnimationFrame(scrubbed, 0);
    if (textDifference(scrubbed, scenes::sceneFileText(d.scene)) > 1e-12) moved.push_back(description);
  }
  EXPECT_TRUE(moved.empty()) << "a scrub to frame 0 moves the scene after undoing '" << (moved.empty() ? "" : moved.front()) << "'";
  d.timeline.setFrame(0);  // the scrub
  scenes::Scene file = scenes::readScene(kMirror);
  scenes::applyAnimationFrame(file, 0);
  EXPECT_LE(textDifference(d.scene, scenes::sceneFileText(file)), kTolerance) << "undo to the start";
  while (d.commands.canRedo()) {
    const std::string description = d.commands.redoDescription();
    d.commands.redo();
    EXPECT_LE(textDifference(d.scene, before.back()), kTolerance) << "redo of '" << description << "'";
    before.pop_back();
  }
  EXPECT_LE(textDifference(d.scene, edited), kTolerance) << "redo to the end";
  // A scrub to the frame shown again (it winds push-back's key, which takes push-front with it),
  // then undo all again: each undo is the inverse of the redo before it (its record) and gives
  // the scene the first undo gave, exactly.
  d.timeline.setFrame(0);
  for (const std::string& want : undone) {
    const std::string description = d.commands.undoDescription();
    d.commands.undo();
    EXPECT_EQ(scenes::sceneFileText(d.scene), want) << "undo again of '" << description << "'";
  }
}

}  // namespace
}  // namespace ffdkit::app
