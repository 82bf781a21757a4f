// The headless timeline (app/timeline.h): keys of the selection as one delta command each,
// scrubbing and playback that set the model through the animation, looping at the range's end.
#include <gtest/gtest.h>

#include "ffdkit/interaction/timeline.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::app {
namespace {

using scenes::ChannelKind;

struct Document {
  scenes::Scene scene = scenes::readScene(FFDKIT_SOURCE_DIR "/scenes/examples/default");
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  InteractionController controller{scene, deformer, commands};
  Timeline timeline{scene, commands, controller};
};

TEST(Timeline, InsertAndDeleteKeyAreOneDeltaCommandEach) {
  Document d;
  const auto pull = d.scene.widgets.find("pull");
  const auto lattice = d.scene.widgets.find("lattice");
  d.controller.setSelection({pull, lattice});
  d.timeline.setFrame(10);
  EXPECT_EQ(d.scene.widgets.variation(pull), scenes::evaluateVariation(d.scene.animation().channels[0].keys, 10.0 / 24));
  d.scene.widgets.setVariation(pull, 0.7);
  const std::string before = scenes::sceneFileText(d.scene);
  EXPECT_EQ(d.timeline.insertKeys(), 2);  // pull's variation, the lattice's frame
  EXPECT_EQ(d.commands.size(), 1u);
  EXPECT_LT(d.commands.bytes(), 2000u);  // two keys, not a document
  EXPECT_EQ(scenes::keyAt(d.scene.animation(), pull, ChannelKind::Variation, 10.0 / 24)->variation, 0.7);
  EXPECT_TRUE(scenes::keyAt(d.scene.animation(), lattice, ChannelKind::LatticeFrame, 10.0 / 24));
  EXPECT_EQ(d.timeline.keyFrames(), (std::vector<double>{0, 10, 24, 48, 72}));
  d.commands.undo();
  EXPECT_EQ(scenes::sceneFileText(d.scene), before);
  d.commands.redo();
  EXPECT_EQ(d.timeline.deleteKeys(), 2);
  EXPECT_EQ(scenes::sceneFileText(d.scene), before);
  d.commands.undo();
  EXPECT_EQ(d.timeline.keyFrames(), (std::vector<double>{0, 10, 24, 48, 72}));
  EXPECT_EQ(d.timeline.previousKey(), 0.0);
  EXPECT_EQ(d.timeline.nextKey(), 24.0);
}

TEST(Timeline, APickedPointKeysItsLatticesControlPoints) {
  Document d;
  const auto lattice = d.scene.widgets.find("lattice");
  d.controller.setPickedPoint(LatticePointRef{lattice, 4});
  ASSERT_EQ(d.timeline.selectedChannels().size(), 1u);
  EXPECT_EQ(d.timeline.selectedChannels()[0].second, ChannelKind::ControlPoints);
  EXPECT_EQ(d.timeline.insertKeys(), 1);
}

TEST(Timeline, UndoOfAKeyAfterAFrameChangeGivesThePoseTheAnimationGivesWithoutIt) {
  // A key changes no value, but the frame changes after it apply the animation with it: keyed
  // control points hold the lattice at the key's points at every frame. Undoing the key there
  // must give the pose the animation gives without it, not keep the points the key put there.
  Document keyed, unkeyed;
  const auto lattice = keyed.scene.widgets.find("lattice");
  keyed.controller.setPickedPoint(LatticePointRef{lattice, 4});
  keyed.timeline.setFrame(24);  // the pull at 0.5
  const Eigen::MatrixX3d atKey = keyed.scene.widgets.controlPoints(lattice);
  ASSERT_EQ(keyed.timeline.insertKeys(), 1);
  keyed.timeline.setFrame(0);  // the pull back at 0, the points held by their key
  ASSERT_EQ(keyed.scene.widgets.controlPoints(lattice), atKey);
  unkeyed.timeline.setFrame(24);
  unkeyed.timeline.setFrame(0);
  const Eigen::MatrixX3d without = unkeyed.scene.widgets.controlPoints(lattice);
  ASSERT_GT((atKey - without).cwiseAbs().maxCoeff(), 0.1);  // the case under test
  keyed.commands.undo();
  EXPECT_LE((keyed.scene.widgets.controlPoints(lattice) - without).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(keyed.scene.widgets.variation(keyed.scene.widgets.find("pull")), 0.0);
  // Redo gives the keyed pose again, exactly (the carried undo's record).
  keyed.commands.redo();
  EXPECT_EQ(keyed.scene.widgets.controlPoints(lattice), atKey);
  // Delete Key likewise: removing the key at frame 24, then frame 0 shows the unkeyed pose; its undo
  // there brings back the key's points.
  keyed.timeline.setFrame(24);
  keyed.controller.setPickedPoint(LatticePointRef{lattice, 4});
  ASSERT_EQ(keyed.timeline.deleteKeys(), 1);
  keyed.timeline.setFrame(0);
  EXPECT_LE((keyed.scene.widgets.controlPoints(lattice) - without).cwiseAbs().maxCoeff(), 1e-12);
  keyed.commands.undo();
  EXPECT_LE((keyed.scene.widgets.controlPoints(lattice) - atKey).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Timeline, NothingKeyableIsRefusedWithoutACommand) {
  Document d;
  d.controller.setSelection({d.scene.widgets.find("top")});
  EXPECT_THROW(d.timeline.insertKeys(), std::invalid_argument);
  EXPECT_THROW(d.timeline.deleteKeys(), std::invalid_argument);
  EXPECT_EQ(d.commands.size(), 0u);
}

TEST(Timeline, SteppedPlaybackMovesByWholeFramesAndLoops) {
  // The frame-step source a test drives instead of the wall clock: the same frames every run.
  Document d;
  const auto pull = d.scene.widgets.find("pull");
  d.timeline.setFrame(70);
  EXPECT_FALSE(d.timeline.advanceFrames(1));  // not playing
  d.timeline.setPlaying(true);
  EXPECT_FALSE(d.timeline.advanceFrames(0));
  EXPECT_FALSE(d.timeline.advanceFrames(-3));
  EXPECT_EQ(d.timeline.frame(), 70);
  EXPECT_TRUE(d.timeline.advanceFrames(1));
  EXPECT_EQ(d.timeline.frame(), 71);
  EXPECT_TRUE(d.timeline.advanceFrames(2));  // 73 is past the range 0..72: frame 0
  EXPECT_EQ(d.timeline.frame(), 0);
  EXPECT_EQ(d.scene.widgets.variation(pull), 0.0);
  for (int step = 0; step < 12; ++step) EXPECT_TRUE(d.timeline.advanceFrames(1));  // no rounding drift
  EXPECT_EQ(d.timeline.frame(), 12);
  EXPECT_NEAR(d.scene.widgets.variation(pull), 0.25, 1e-12);  // as advance(0.5) gives
  EXPECT_FALSE(d.timeline.advanceFrames(3 * 73));  // whole loops come back to the same frame: no change
  EXPECT_EQ(d.timeline.frame(), 12);
  EXPECT_TRUE(d.timeline.advanceFrames(73 + 5));
  EXPECT_EQ(d.timeline.frame(), 17);
}

TEST(Timeline, PlaybackFollowsWallTimeAndLoops) {
  Document d;
  const auto pull = d.scene.widgets.find("pull");
  d.timeline.setFrame(70);
  EXPECT_FALSE(d.timeline.advance(1.0));  // not playing
  d.timeline.setPlaying(true);
  EXPECT_FALSE(d.timeline.advance(0.01));  // a quarter frame: still frame 70
  EXPECT_TRUE(d.timeline.advance(1.0 / 24));
  EXPECT_EQ(d.timeline.frame(), 71);
  EXPECT_TRUE(d.timeline.advance(2.0 / 24 + 1e-9));  // past 72: back to the start of the range
  EXPECT_EQ(d.timeline.frame(), 0);
  EXPECT_EQ(d.scene.widgets.variation(pull), 0.0);
  EXPECT_TRUE(d.timeline.advance(0.5));  // a slow frame skips frames, it does not slow down
  EXPECT_EQ(d.timeline.frame(), 12);
  EXPECT_NEAR(d.scene.widgets.variation(pull), 0.25, 1e-12);
  // A drag under way is left alone; the frame catches up after it.
  d.scene.widgets.beginGesture(pull);
  EXPECT_FALSE(d.timeline.advance(1.0 / 24));
  EXPECT_EQ(d.timeline.frame(), 12);
  d.scene.widgets.endGesture();
  EXPECT_TRUE(d.timeline.advance(0.0));
  EXPECT_EQ(d.timeline.frame(), 13);
  d.timeline.setFrame(12);
  // The deformer follows: the sphere equals a fresh evaluation of the scene at frame 12.
  const auto fresh = scenes::deformScene(d.scene);
  EXPECT_LT((d.deformer.points("sphere") - fresh.at("sphere")).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace ffdkit::app
