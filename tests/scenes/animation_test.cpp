#include "ffdkit/scenes/animation.h"

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <gtest/gtest.h>

#include "ffdkit/scenes/scene_changes.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/widgets/thesis_examples.h"
#include "scenes_test_support.h"

namespace ffdkit::scenes {
namespace {
using test_support::kExamples;

using widgets::WidgetId;

// A sample scene without the keys it ships with.
Scene sampleScene(const char* name) {
  Scene scene = readScene(kExamples / name);
  Animation unkeyed = scene.animation();
  unkeyed.channels.clear();
  scene.setAnimation(std::move(unkeyed));
  return scene;
}

Keyframe scalarKey(double time, double value, Interpolation interpolation) {
  Keyframe k;
  k.time = time;
  k.variation = value;
  k.interpolation = interpolation;
  return k;
}

std::vector<Keyframe> scalarKeys(const std::vector<std::pair<double, double>>& samples, Interpolation interpolation) {
  std::vector<Keyframe> keys;
  for (const auto& [t, v] : samples) keys.push_back(scalarKey(t, v, interpolation));
  return keys;
}

// Hand-computed Hermite values: keys (0, 0), (1, 1), (3, 4). Auto slopes: 0 at the ends, at
// t = 1 the Catmull-Rom slope (4 - 0) / (3 - 0) = 4/3. At t = 0.5 (h = 1, s = 1/2):
// h00 = h01 = 1/2, h10 = 1/8, h11 = -1/8 -> 0/2 + 1/2 - (1/8)(4/3) = 1/3. At t = 2 (h = 2, s = 1/2):
// 1/2 + (1/8)(2)(4/3) + 4/2 - 0 = 17/6.
TEST(Animation, SmoothSegmentsMatchHandComputedHermiteValues) {
  const auto keys = scalarKeys({{0, 0}, {1, 1}, {3, 4}}, Interpolation::Smooth);
  EXPECT_NEAR(evaluateVariation(keys, 0.5), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(evaluateVariation(keys, 2.0), 17.0 / 6.0, 1e-15);
  // Through every key, held outside them.
  EXPECT_EQ(evaluateVariation(keys, 1.0), 1.0);
  EXPECT_EQ(evaluateVariation(keys, -5.0), 0.0);
  EXPECT_EQ(evaluateVariation(keys, 9.0), 4.0);
  // The slopes themselves.
  const std::vector<double> t{0, 1, 3}, v{0, 1, 4};
  EXPECT_EQ(autoSlope(t, v, 0), 0.0);
  EXPECT_NEAR(autoSlope(t, v, 1), 4.0 / 3.0, 1e-15);
  EXPECT_EQ(autoSlope(t, v, 2), 0.0);
}

TEST(Animation, SmoothIsFlatAtAnExtremumAndDoesNotOvershoot) {
  const auto keys = scalarKeys({{0, 0}, {1, 1}, {2, 0}}, Interpolation::Smooth);
  EXPECT_EQ(autoSlope({0, 1, 2}, {0, 1, 0}, 1), 0.0);
  // Both slopes 0: p = h00 p0 + h01 p1, at s = 1/4: h01 = -2/64 + 3/16 = 10/64.
  EXPECT_NEAR(evaluateVariation(keys, 0.25), 10.0 / 64.0, 1e-15);
  for (double t = 0.0; t <= 2.0; t += 0.01) EXPECT_LE(evaluateVariation(keys, t), 1.0);
}

TEST(Animation, ConstantAndLinearSegments) {
  EXPECT_EQ(evaluateVariation(scalarKeys({{0, 0}, {1, 1}, {3, 4}}, Interpolation::Linear), 2.0), 2.5);
  EXPECT_EQ(evaluateVariation(scalarKeys({{0, 0}, {1, 1}, {3, 4}}, Interpolation::Constant), 2.9), 1.0);
  // The rule is the segment's first key's: linear then constant.
  auto keys = scalarKeys({{0, 0}, {1, 1}, {3, 4}}, Interpolation::Linear);
  keys[1].interpolation = Interpolation::Constant;
  EXPECT_EQ(evaluateVariation(keys, 0.5), 0.5);
  EXPECT_EQ(evaluateVariation(keys, 2.5), 1.0);
  EXPECT_THROW(evaluateVariation(keys, std::nan("")), AnimationError);
  EXPECT_THROW(evaluateVariation({}, 0.0), AnimationError);
}

TEST(Animation, LinearFramesSlerpTheRotationAndLerpTranslationAndStretch) {
  Keyframe a, b;
  a.interpolation = b.interpolation = Interpolation::Linear;
  b.time = 2.0;
  b.frame = Eigen::Translation3d(2, 0, 0) * Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()) *
            Eigen::Scaling(3.0, 1.0, 1.0);
  const Eigen::Affine3d mid = evaluateFrame({a, b}, 1.0);
  const Eigen::Affine3d expected = Eigen::Translation3d(1, 0, 0) *
                                   Eigen::AngleAxisd(std::numbers::pi / 4, Eigen::Vector3d::UnitZ()) * Eigen::Scaling(2.0, 1.0, 1.0);
  EXPECT_LT((mid.matrix() - expected.matrix()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(evaluateFrame({a, b}, 2.0).matrix(), b.frame.matrix());  // exactly the key
}

TEST(Animation, PointsInterpolatePerCoordinate) {
  Keyframe a, b;
  a.interpolation = Interpolation::Linear;
  a.points = Eigen::MatrixX3d::Zero(2, 3);
  b.time = 1.0;
  b.points = Eigen::MatrixX3d::Ones(2, 3);
  b.points(1, 2) = 3.0;
  const Eigen::MatrixX3d mid = evaluatePoints({a, b}, 0.25);
  EXPECT_EQ(mid(0, 0), 0.25);
  EXPECT_EQ(mid(1, 2), 0.75);
}

// Keying one widget of a bound pair and evaluating gives what the same drag gives (the model's
// own propagation), independent of the times evaluated before.
TEST(Animation, EvaluationPropagatesBindingsAsADragDoes) {
  Scene scene = sampleScene("mirror");
  const WidgetId a = scene.widgets.find("push-front");
  const Scene start = scene;
  Keyframe k0 = currentKey(scene, a, ChannelKind::Variation, 0.0);
  Keyframe k1 = k0;
  k1.time = 1.0;
  k1.variation = k0.variation + 0.3;
  setKey(scene, a, ChannelKind::Variation, k0);
  setKey(scene, a, ChannelKind::Variation, k1);

  widgets::WidgetModel dragged = start.widgets;  // the same value reached by a drag
  const double value = evaluateVariation(scene.animation().channels.front().keys, 0.4);
  dragged.beginGesture(a);
  dragged.updateGesture(value - dragged.variation(a));
  dragged.endGesture();

  for (double t : {0.9, 0.1, 0.4}) applyAnimation(scene, t);
  for (WidgetId lattice : scene.widgets.widgets(widgets::WidgetType::Lattice))
    EXPECT_LT((scene.widgets.controlPoints(lattice) - dragged.controlPoints(lattice)).cwiseAbs().maxCoeff(), 1e-12);
  for (WidgetId w : scene.widgets.widgets(widgets::WidgetType::Affine))
    EXPECT_NEAR(scene.widgets.variation(w), dragged.variation(w), 1e-12) << scene.widgets.name(w);
  // The bound partner moved too (mirror: it is not keyed).
  const WidgetId b = scene.widgets.find("push-back");
  EXPECT_NE(scene.widgets.variation(b), start.widgets.variation(b));
}

TEST(Animation, AChannelAlreadyAtItsValueIsNotTouched) {
  Scene scene = sampleScene("default");
  const WidgetId pull = scene.widgets.find("pull");
  setKey(scene, pull, ChannelKind::Variation, currentKey(scene, pull, ChannelKind::Variation, 0.0));
  const std::uint64_t revision = scene.widgets.revision();
  applyAnimation(scene, 3.0);
  EXPECT_EQ(scene.widgets.revision(), revision);
}

TEST(Animation, LatticeFramesAndControlPointsAreApplied) {
  Scene scene = sampleScene("default");
  const WidgetId lattice = scene.widgets.find("lattice");
  const Eigen::Affine3d frame0 = scene.widgets.latticeFrame(lattice);
  Keyframe f0 = currentKey(scene, lattice, ChannelKind::LatticeFrame, 0.0, Interpolation::Linear);
  Keyframe f1 = f0;
  f1.time = 2.0;
  f1.frame = Eigen::Translation3d(0, 0, 1) * frame0;
  setKey(scene, lattice, ChannelKind::LatticeFrame, f0);
  setKey(scene, lattice, ChannelKind::LatticeFrame, f1);
  applyAnimation(scene, 1.0);
  const Eigen::Affine3d expected = Eigen::Translation3d(0, 0, 0.5) * frame0;
  EXPECT_LT((scene.widgets.latticeFrame(lattice).matrix() - expected.matrix()).cwiseAbs().maxCoeff(), 1e-12);

  Keyframe p0 = currentKey(scene, lattice, ChannelKind::ControlPoints, 0.0, Interpolation::Linear);
  Keyframe p1 = p0;
  p1.time = 1.0;
  p1.points.col(2).array() += 0.2;
  setKey(scene, lattice, ChannelKind::ControlPoints, p0);
  setKey(scene, lattice, ChannelKind::ControlPoints, p1);
  applyAnimation(scene, 0.5);
  Eigen::MatrixX3d expectedPoints = p0.points;
  expectedPoints.col(2).array() += 0.1;
  EXPECT_LT((scene.widgets.controlPoints(lattice) - expectedPoints).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(Animation, KeyTimesAreSortedAndUnique) {
  Scene scene = sampleScene("mirror");
  const WidgetId a = scene.widgets.find("push-front");
  const WidgetId e = scene.widgets.find("pull-front");
  for (double t : {2.0, 0.5, 1.0}) setKey(scene, a, ChannelKind::Variation, currentKey(scene, a, ChannelKind::Variation, t));
  for (double t : {1.0, 3.0}) setKey(scene, e, ChannelKind::Variation, currentKey(scene, e, ChannelKind::Variation, t));
  EXPECT_EQ(keyTimes(scene), (std::vector<double>{0.5, 1.0, 2.0, 3.0}));
  EXPECT_EQ(keyTimes(scene, e), (std::vector<double>{1.0, 3.0}));
}

TEST(Animation, SetKeyReplacesAtTheSameTimeAndRemoveKeyDropsEmptyChannels) {
  Scene scene = sampleScene("default");
  const WidgetId pull = scene.widgets.find("pull");
  const SceneMark mark = markOf(scene);
  EXPECT_FALSE(setKey(scene, pull, ChannelKind::Variation, scalarKey(1.0, 0.1, Interpolation::Linear)));
  EXPECT_TRUE(changesSince(scene, mark).animation);
  const auto replaced = setKey(scene, pull, ChannelKind::Variation, scalarKey(1.0 + 1e-12, 0.2, Interpolation::Linear));
  ASSERT_TRUE(replaced);
  EXPECT_EQ(replaced->variation, 0.1);
  ASSERT_EQ(scene.animation().channels.size(), 1u);
  EXPECT_EQ(scene.animation().channels[0].keys.size(), 1u);
  EXPECT_FALSE(removeKey(scene, pull, ChannelKind::Variation, 2.0));
  EXPECT_EQ(removeKey(scene, pull, ChannelKind::Variation, 1.0)->variation, 0.2);
  EXPECT_TRUE(scene.animation().channels.empty());
}

TEST(Animation, RefusesBadKeysWithClearErrors) {
  Scene scene = sampleScene("default");
  const WidgetId pull = scene.widgets.find("pull");
  const WidgetId lattice = scene.widgets.find("lattice");
  const auto message = [&](auto f) {
    try {
      f();
    } catch (const AnimationError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message([&] { setKey(scene, pull, ChannelKind::Variation, scalarKey(std::nan(""), 0, Interpolation::Smooth)); })
                .find("key time must be finite"),
            std::string::npos);
  EXPECT_NE(message([&] { setKey(scene, scene.widgets.find("top"), ChannelKind::Variation, scalarKey(0, 0, Interpolation::Smooth)); })
                .find("a cell has no keyable value"),
            std::string::npos);
  Keyframe points;
  points.points = Eigen::MatrixX3d::Zero(5, 3);
  EXPECT_NE(message([&] { setKey(scene, lattice, ChannelKind::ControlPoints, points); }).find("expected 27 control points"),
            std::string::npos);
  Keyframe flat;
  flat.frame.linear().setZero();
  EXPECT_NE(message([&] { setKey(scene, lattice, ChannelKind::LatticeFrame, flat); }).find("finite and invertible"),
            std::string::npos);
  EXPECT_NE(message([&] { applyAnimation(scene, INFINITY); }).find("must be finite"), std::string::npos);
  EXPECT_TRUE(scene.animation().channels.empty());
}

TEST(Animation, AChildLatticeThatMovesItsParentCellCannotKeyItsFrame) {
  Scene scene = sampleScene("hierarchy");
  for (WidgetId lattice : scene.widgets.widgets(widgets::WidgetType::Lattice)) {
    const auto kinds = keyableKinds(scene.widgets, lattice);
    const bool twoWayChild = scene.widgets.parentCell(lattice) && kinds.size() == 1;
    if (!twoWayChild) continue;
    EXPECT_THROW(setKey(scene, lattice, ChannelKind::LatticeFrame, Keyframe{}), AnimationError);
  }
}

// ---- scene files ------------------------------------------------------------------------------

Scene animatedDefault() {
  Scene scene = sampleScene("default");
  const WidgetId pull = scene.widgets.find("pull");
  const WidgetId lattice = scene.widgets.find("lattice");
  scene.setFrameRate(30.0);
  scene.setFrameRange(-5, 90);
  setKey(scene, pull, ChannelKind::Variation, scalarKey(frameTime(scene.animation(), 0), 0.0, Interpolation::Smooth));
  setKey(scene, pull, ChannelKind::Variation, scalarKey(frameTime(scene.animation(), 7), 0.1 + 0.2, Interpolation::Constant));
  setKey(scene, pull, ChannelKind::Variation, scalarKey(frameTime(scene.animation(), 61), -1.0 / 3.0, Interpolation::Linear));
  Keyframe frame = currentKey(scene, lattice, ChannelKind::LatticeFrame, frameTime(scene.animation(), 11));
  frame.frame = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()) * frame.frame;
  setKey(scene, lattice, ChannelKind::LatticeFrame, frame);
  Keyframe points = currentKey(scene, lattice, ChannelKind::ControlPoints, frameTime(scene.animation(), 13), Interpolation::Linear);
  points.points(4, 1) += 1e-7;
  setKey(scene, lattice, ChannelKind::ControlPoints, points);
  return scene;
}

TEST(AnimationFile, KeysRoundTripByteForByte) {
  const Scene scene = animatedDefault();
  const std::string text = sceneFileText(scene);
  EXPECT_NE(text.find("\"animation\""), std::string::npos);
  std::istringstream in(text);
  const Scene again = readScene(in, "animated.json", {.baseDirectory = kExamples / "default"});
  EXPECT_EQ(sceneFileText(again), text);
  ASSERT_EQ(again.animation().channels.size(), scene.animation().channels.size());
  for (std::size_t c = 0; c < scene.animation().channels.size(); ++c) {
    EXPECT_EQ(again.animation().channels[c].kind, scene.animation().channels[c].kind);
    EXPECT_TRUE(again.animation().channels[c].keys == scene.animation().channels[c].keys);
  }
  EXPECT_EQ(again.animation().framesPerSecond, 30.0);
  EXPECT_EQ(again.animation().firstFrame, -5);
  EXPECT_EQ(again.animation().lastFrame, 90);
}

std::string animationErrorOf(const std::string& text) {
  std::istringstream in(text);
  try {
    readScene(in, "scene.json", {.baseDirectory = kExamples / "default"});
  } catch (const SceneFileError& e) {
    return e.what();
  }
  return "";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(AnimationFile, ParseErrorsSayWhatAndWhere) {
  const std::string good = sceneFileText(animatedDefault());
  ASSERT_EQ(animationErrorOf(good), "");
  const auto expectError = [&](const std::string& text, const std::string& part) {
    const std::string e = animationErrorOf(text);
    EXPECT_NE(e.find(part), std::string::npos) << "got: " << e;
  };
  expectError(replaced(good, "\"time\": 0.0,", "\"time\": \"soon\","), "/animation/channels/0/keys/0/time: expected a number");
  expectError(replaced(good, "\"time\": 0.0,", "\"time\": 1e400,"), "scene.json:");  // out of double range: a syntax error
  expectError(replaced(good, "\"time\": 0.0,", "\"time\": 5,"), "/animation/channels/0/keys/1/time: key times must increase");
  expectError(replaced(good, "\"time\": 0.0,", "\"time\": 0.23333333333333334,"), "key times must increase");  // a duplicate
  expectError(replaced(good, "\"widget\": \"pull\"", "\"widget\": \"pul\""), "/animation/channels/0/widget: ");
  expectError(replaced(good, "\"property\": \"variation\"", "\"property\": \"colour\""), "unknown property 'colour'");
  expectError(replaced(good, "\"interpolation\": \"constant\"", "\"interpolation\": \"cubic\""),
              "/animation/channels/0/keys/1/interpolation: unknown interpolation 'cubic'");
  expectError(replaced(good, "\"frameRate\": 30.0", "\"frameRate\": 0"), "/animation/frameRate: expected frames per second");
  expectError(replaced(good, "\"frames\": [-5, 90]", "\"frames\": [90, -5]"), "/animation/frames: the first frame 90 is after");
  expectError(replaced(good, "\"frames\": [-5, 90]", "\"frames\": [0, 18446744073709551615]"), "/animation/frames/1: expected an integer");
  expectError(replaced(good, "\"property\": \"frame\"", "\"property\": \"variation\""), "a lattice keys its frame or its control points");
  expectError(replaced(good, "\"version\": 2", "\"version\": 1"), "'animation' needs format version 2");
  expectError(replaced(good, "\"version\": 2", "\"version\": 3"), "/version: format version 3 is not supported");
  expectError(replaced(good, "\"channels\": [", "\"channels\": [{\"widget\": \"pull\", \"property\": \"variation\", \"keys\": []},"),
              "/animation/channels/0/keys: a channel needs at least one key");
}

TEST(AnimationFile, HugeCountsAreRefused) {
  std::string keys;
  for (std::size_t k = 0; k <= kMaxKeysPerChannel; ++k) {
    if (k > 0) keys += ',';
    keys += "{\"time\":";
    keys += std::to_string(k);
    keys += ",\"value\":0}";
  }
  const std::string good = sceneFileText(animatedDefault());
  const std::string text = replaced(good, "\"channels\": [", "\"channels\": [{\"widget\": \"pull\", \"property\": \"variation\", \"keys\": [" + keys + "]},");
  EXPECT_NE(animationErrorOf(text).find("at most 100000 keys per channel"), std::string::npos);
}

// Every older file still loads: the version-1 copies of the sample scenes kept as fuzz seeds.
TEST(AnimationFile, VersionOneFilesStillLoad) {
  int read = 0;
  for (const auto& entry : std::filesystem::directory_iterator(FFDKIT_SOURCE_DIR "/tests/fuzz/corpus/fuzz_scene_file")) {
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (entry.path().filename().string().find("-v2") != std::string::npos) continue;
    ASSERT_NE(text.find("\"format\": \"ffdkit-scene\",\n  \"version\": 1,"), std::string::npos);
    SCOPED_TRACE(entry.path().filename().string());
    std::istringstream stream(text);
    const Scene scene = readScene(stream, entry.path().string(), {.baseDirectory = entry.path().parent_path()});
    EXPECT_TRUE(scene.animation().empty());
    EXPECT_NE(sceneFileText(scene).find("\"version\": 2"), std::string::npos);
    ++read;
  }
  EXPECT_GE(read, 10);
}

// The version-2 seeds of the scene-file fuzz target (every channel kind) load and evaluate.
TEST(AnimationFile, VersionTwoFuzzSeedsLoadAndEvaluate) {
  int read = 0;
  for (const auto& entry : std::filesystem::directory_iterator(FFDKIT_SOURCE_DIR "/tests/fuzz/corpus/fuzz_scene_file")) {
    if (entry.path().filename().string().find("-v2") == std::string::npos) continue;
    SCOPED_TRACE(entry.path().filename().string());
    Scene scene = readScene(entry.path());
    ASSERT_FALSE(scene.animation().empty());
    for (double t : keyTimes(scene)) applyAnimation(scene, t);
    ++read;
  }
  EXPECT_GE(read, 3);
}

}  // namespace
}  // namespace ffdkit::scenes

namespace ffdkit::scenes {
namespace {

// The press sample as it ships: a handle keyed from 0 (frame 0) to one turn (frame 72), driving
// the press through a screw (0.4 per turn) clamped to [0, 0.3]. A clamp forgets how far a motion
// pushed past it, so a carry there and back (restoreAtEditValues after a frame change) does not
// return: only the stored values do.
struct PressEdit {
  Scene scene = readScene(kExamples / "press");
  WidgetId press = scene.widgets.find("press");
  widgets::WidgetModelState before, after;  // the edit's write-back (all of the model's values)
  widgets::WidgetModelState animatedBefore, animatedAfter;

  PressEdit() {
    applyAnimation(scene, 1.5);  // frame 36: the handle half a turn round, the press at 0.2
    before = scene.widgets.captureState();
    animatedBefore = animatedState(scene);
    scene.widgets.setVariation(press, 0.28);  // a drag of the press: the handle turns with it (two-way)
    after = scene.widgets.captureState();
    animatedAfter = animatedState(scene);
    applyAnimation(scene, 3.0);  // frame 72: the screw runs into the clamp
    applyAnimation(scene, 0.5);  // frame 12: shown when the undo runs
  }
  // `shown`: the time the model was last set to (frame 12 unless a test changes it).
  void undo(std::optional<CarriedStep>* last, double shown = 0.5) {
    restoreAtEditValues(scene, animatedAfter, shown, [&] { scene.widgets.restoreState(before); }, last);
  }
  void redo(std::optional<CarriedStep>* last, double shown = 0.5) {
    restoreAtEditValues(scene, animatedBefore, shown, [&] { scene.widgets.restoreState(after); }, last);
  }
};

bool sameValues(const widgets::WidgetModelState& a, const widgets::WidgetModelState& b) {
  if (a.variations != b.variations || a.controlPoints.size() != b.controlPoints.size()) return false;
  for (std::size_t i = 0; i < a.controlPoints.size(); ++i)
    if (a.controlPoints[i].first != b.controlPoints[i].first || a.controlPoints[i].second != b.controlPoints[i].second)
      return false;
  return true;
}

TEST(RestoreAtEditValues, ACarriedUndosRedoAndUndoAgainGiveTheStoredStatesExactly) {
  PressEdit e;
  const widgets::WidgetModelState edited = e.scene.widgets.captureState();
  std::optional<CarriedStep> last;
  e.undo(&last);
  const widgets::WidgetModelState undone = e.scene.widgets.captureState();
  ASSERT_TRUE(last.has_value());
  e.redo(&last);
  EXPECT_TRUE(sameValues(e.scene.widgets.captureState(), edited)) << "redo after a carried undo";
  e.undo(&last);
  EXPECT_TRUE(sameValues(e.scene.widgets.captureState(), undone)) << "undo again";
  e.redo(&last);
  EXPECT_TRUE(sameValues(e.scene.widgets.captureState(), edited)) << "redo again";
  // The handle shows frame 12's value throughout.
  EXPECT_NEAR(e.scene.widgets.variation(e.scene.widgets.find("handle")),
              evaluateVariation(e.scene.animation().channels[0].keys, 0.5), 1e-12);
}

TEST(RestoreAtEditValues, WithoutTheRecordARedoCarriedAgainGivesTheClampedPressToo) {
  // The same undo and redo, each carried through the bindings. Winding straight from one frame's
  // values to the next, the clamp forgot how far past it the screw was pushed, and this redo
  // missed the press by more than 1e-3; winding every frame change from 0 (applyAnimatedValues)
  // gives the same model at a frame from whatever frame it comes, so the carry alone is exact here.
  PressEdit e;
  const double pressEdited = e.scene.widgets.variation(e.press);
  e.undo(nullptr);
  e.redo(nullptr);
  EXPECT_LE(std::abs(e.scene.widgets.variation(e.press) - pressEdited), 1e-12);
}

TEST(RestoreAtEditValues, ARecordIsUsedOnlyFromTheStateItsStepLeft) {
  PressEdit e;
  std::optional<CarriedStep> last;
  e.undo(&last);
  applyAnimation(e.scene, 0.25);  // a frame change after the undo: the redo carries again
  const double handle = e.scene.widgets.variation(e.scene.widgets.find("handle"));
  e.redo(&last, 0.25);
  EXPECT_NEAR(e.scene.widgets.variation(e.scene.widgets.find("handle")), handle, 1e-12);  // the frame shown stays
  // Without a frame change since the edit, the write-back alone runs and the record is dropped.
  restoreAtEditValues(e.scene, e.animatedAfter, std::nullopt, [&] { e.scene.widgets.restoreState(e.before); }, &last);
  EXPECT_FALSE(last.has_value());
  EXPECT_TRUE(sameValues(e.scene.widgets.captureState(), e.before));
}

}  // namespace
}  // namespace ffdkit::scenes

namespace ffdkit::scenes {
namespace {

TEST(SceneFileAnimation, ARemovedKeyedWidgetLeavesNoEmptyAnimationBehind) {
  // The default sample keys only its pull widget: once that widget is removed, nothing of the
  // animation is written, and the text reads back to the same text (the monkey test saved such
  // a scene and found its reopened text differed: "channels": [] was written, then dropped).
  Scene scene = readScene(kExamples / "default");
  scene.widgets.remove(scene.widgets.find("pull"));
  const std::string text = sceneFileText(scene);
  EXPECT_EQ(text.find("\"animation\""), std::string::npos);
  std::istringstream in(text);
  const Scene again = readScene(in, "again.json", {.baseDirectory = kExamples / "default"});
  EXPECT_EQ(sceneFileText(again), text);
  // A changed frame range alone is still written, and reads back the same.
  Animation range = scene.animation();
  range.lastFrame = 48;
  scene.setAnimation(range);
  const std::string ranged = sceneFileText(scene);
  EXPECT_NE(ranged.find("\"frames\": [0, 48]"), std::string::npos);
  std::istringstream in2(ranged);
  EXPECT_EQ(sceneFileText(readScene(in2, "ranged.json", {.baseDirectory = kExamples / "default"})), ranged);
}

}  // namespace
}  // namespace ffdkit::scenes
