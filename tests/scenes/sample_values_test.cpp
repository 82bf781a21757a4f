// The committed sample files (scenes/examples/*/scene.json, widgets/examples/*.json) are written
// by code (make_examples.cpp, FFDKIT_WRITE_WIDGET_EXAMPLES), and the tests that compare them
// with that code only prove the code agrees with itself. These tests pin what the files hold to
// values written out here from the widget semantics (Kuriyama 1996, secs. 6.2.1, 6.2.2, 6.5): the rest
// grid, the moved cells, and the rings of the twist in closed form.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/widget_file.h"

namespace ffdkit::scenes {
namespace {

namespace fs = std::filesystem;
using std::numbers::pi;
using widgets::WidgetId;
using widgets::WidgetModel;
using widgets::WidgetType;

const fs::path kRoot = FFDKIT_SOURCE_DIR;

// The regular grid of the unit box with counts c, i fastest.
Eigen::MatrixX3d unitGrid(const Eigen::Vector3i& c) {
  Eigen::MatrixX3d p(c.prod(), 3);
  for (int k = 0; k < c.z(); ++k)
    for (int j = 0; j < c.y(); ++j)
      for (int i = 0; i < c.x(); ++i)
        p.row(i + c.x() * (j + c.y() * k)) << double(i) / (c.x() - 1), double(j) / (c.y() - 1), double(k) / (c.z() - 1);
  return p;
}

WidgetId onlyRoot(const WidgetModel& m) {
  EXPECT_FALSE(m.roots().empty());
  return m.roots().front();
}

Scene sample(const std::string& name) { return readScene(kRoot / "scenes" / "examples" / name / "scene.json"); }

// The sample scene taken from its stored pose (its first frame) to `frame` of its animation.
Scene sampleAtFrame(const std::string& name, double frame) {
  Scene s = sample(name);
  applyAnimationFrame(s, frame);
  return s;
}

std::vector<std::string> sampleNames() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kRoot / "scenes" / "examples"))
    if (fs::exists(entry.path() / "scene.json")) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(SampleValues, EveryStoredPoseIsItsAnimationsFirstFrame) {
  // What a sample file stores is what its timeline shows at the first frame: opening it and going
  // to that frame changes nothing, byte for byte (else the first frame change of a session would
  // jump, and undo after frame changes would be compared with a pose no frame shows).
  int animated = 0;
  for (const std::string& name : sampleNames()) {
    Scene s = sample(name);
    const std::string stored = sceneFileText(s);
    // Every keyed channel holds exactly its first frame's value.
    const widgets::WidgetModelState keyed = animationValues(s, frameTime(s.animation(), s.animation().firstFrame));
    for (const auto& [widget, value] : keyed.variations) EXPECT_EQ(s.widgets.variation(widget), value) << name;
    for (const auto& [widget, frame] : keyed.latticeFrames)
      EXPECT_EQ(s.widgets.latticeFrame(widget).matrix(), frame.matrix()) << name;
    for (const auto& [widget, points] : keyed.controlPoints) EXPECT_EQ(s.widgets.controlPoints(widget), points) << name;
    applyAnimationFrame(s, s.animation().firstFrame);
    EXPECT_EQ(sceneFileText(s), stored) << name << ": the stored pose is not the first frame's";
    if (!s.animation().channels.empty()) ++animated;
  }
  EXPECT_GE(animated, 3);  // default, press, mirror
}

TEST(SampleValues, AnimatedSamplesStoreTheRestPoseAndMoveLater) {
  // Frame 0 is the rest pose; the keys (make_examples.cpp) move the scenes by then.
  const Scene press = sample("press"), mirror = sample("mirror"), pose = sample("default");
  EXPECT_EQ(press.widgets.variation(press.widgets.find("handle")), 0.0);
  EXPECT_EQ(press.widgets.variation(press.widgets.find("press")), 0.0);
  EXPECT_EQ(mirror.widgets.variation(mirror.widgets.find("push-front")), 0.0);
  EXPECT_EQ(mirror.widgets.variation(mirror.widgets.find("pull-front")), 0.0);
  EXPECT_EQ(pose.widgets.variation(pose.widgets.find("pull")), 0.0);
  const Scene mirror36 = sampleAtFrame("mirror", 36);
  EXPECT_NEAR(mirror36.widgets.variation(mirror36.widgets.find("push-front")), 0.2, 1e-15);
  EXPECT_NEAR(mirror36.widgets.variation(mirror36.widgets.find("pull-front")), 0.15, 1e-15);
}

TEST(SampleValues, PressSceneLowersTheTopFaceByHalfThePitch) {
  // make_examples: pitch 0.4 per turn; at frame 36 the handle is half a turn round (its keys: 0 at
  // frame 0, one turn at frame 72, linear) -> the top face 0.2 down.
  const Scene s = sampleAtFrame("press", 36);
  EXPECT_NEAR(s.widgets.variation(s.widgets.find("handle")), pi, 1e-15);
  const WidgetId lattice = onlyRoot(s.widgets);
  Eigen::MatrixX3d expected = unitGrid({2, 2, 2});
  expected.bottomRows(4).col(2).array() -= 0.2;
  EXPECT_LE((s.widgets.controlPoints(lattice) - expected).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_NEAR(s.widgets.variation(s.widgets.find("press")), 0.2, 1e-15);
}

TEST(SampleValues, ViseSceneClosesBothJawsByOneAndAHalfTurnsOfPitch) {
  // 1.5 turns at 0.1 per turn: each jaw 0.15 inwards (inside the clamp 0.3); the middle plane stays.
  const Scene s = sample("vise");
  const WidgetId lattice = onlyRoot(s.widgets);
  Eigen::MatrixX3d expected = unitGrid({3, 2, 2});
  for (Eigen::Index r = 0; r < expected.rows(); ++r) {
    if (r % 3 == 0) expected(r, 0) += 0.15;
    if (r % 3 == 2) expected(r, 0) -= 0.15;
  }
  EXPECT_LE((s.widgets.controlPoints(lattice) - expected).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(SampleValues, DefaultScenePullsTheTopCentrePointUpByHalf) {
  // The 3x3x3 lattice fitted to the sphere; at frame 24 (the pull's key of 0.5) only point
  // (1, 1, 2) moved, by 0.5 along world +z.
  const Scene s = sampleAtFrame("default", 24);
  const WidgetId lattice = onlyRoot(s.widgets);
  const Eigen::MatrixX3d moved = s.widgets.worldControlPoints(lattice);
  const Eigen::Affine3d frame = s.widgets.latticeFrame(lattice);
  const Eigen::MatrixX3d& rest = s.widgets.restPoints(lattice);
  for (Eigen::Index r = 0; r < rest.rows(); ++r) {
    const Eigen::Vector3d restWorld = frame * Eigen::Vector3d(rest.row(r).transpose());
    const Eigen::Vector3d shift = r == 1 + 3 * (1 + 3 * 2) ? Eigen::Vector3d(0, 0, 0.5) : Eigen::Vector3d::Zero();
    EXPECT_LE((moved.row(r).transpose() - restWorld - shift).norm(), 1e-14) << r;
  }
}

TEST(SampleValues, HierarchySceneLiftsTheFaceAndPushesTheChildEdge) {
  // The parent's top face lifted by 0.2; the child's edge (0,0,0)/x pushed 0.15 along world +y
  // (its points 0 and 1), which the binding gives to the parent's edge (0,1,0)/x (points 2, 3).
  // Written relative to the child's own frame, so it holds wherever the child sits.
  const Scene s = sample("hierarchy");
  const WidgetModel& m = s.widgets;
  const WidgetId parent = m.find("parent"), child = m.find("child");
  Eigen::MatrixX3d expected = unitGrid({2, 2, 2});
  expected.bottomRows(4).col(2).array() += 0.2;
  expected(2, 1) += 0.15;
  expected(3, 1) += 0.15;
  EXPECT_LE((m.controlPoints(parent) - expected).cwiseAbs().maxCoeff(), 1e-14);
  const Eigen::Affine3d frame = m.latticeFrame(child);
  for (Eigen::Index r = 0; r < 8; ++r) {
    const Eigen::Vector3d d = frame * Eigen::Vector3d(m.controlPoints(child).row(r).transpose()) -
                              frame * Eigen::Vector3d(m.restPoints(child).row(r).transpose());
    EXPECT_LE((d - Eigen::Vector3d(0, r < 2 ? 0.15 : 0.0, 0)).norm(), 1e-14) << r;
  }
}

TEST(SampleValues, CylinderTwistSceneTurnsRingKByKPiOverSix) {
  // Fig. 6-11 sample: the top ring turned pi/2 drives the rings below by 2/3 and 1/3: ring k of
  // the 2 x 12 x 4 lattice is its rest ring turned by k pi / 6 counter-clockwise about +z.
  const Scene s = sample("cylinder-twist");
  const WidgetId lattice = onlyRoot(s.widgets);
  const Eigen::MatrixX3d& p = s.widgets.controlPoints(lattice);
  const Eigen::MatrixX3d& rest = s.widgets.restPoints(lattice);
  ASSERT_EQ(p.rows(), 2 * 12 * 4);
  for (Eigen::Index r = 0; r < p.rows(); ++r) {
    const int k = static_cast<int>(r / 24);
    const Eigen::Vector3d expected = Eigen::AngleAxisd(k * pi / 6, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d(rest.row(r).transpose());
    EXPECT_LE((p.row(r).transpose() - expected).norm(), 1e-14) << r;
  }
}

TEST(SampleValues, WidgetExamplesHoldTheThesisFiguresValues) {
  const fs::path dir = kRoot / "widgets" / "examples";
  // Fig. 6-2: face (k = 2, i, j in {0, 1}) turned 5 degrees about its centroid (0.25, 0.25, 1),
  // edge (0,2,0)-(1,2,0) moved +0.5 in x, point (2,2,0) +0.25 in z, the rest on the grid.
  const WidgetModel fig62 = readWidgetFile(dir / "fig6-2.json");
  Eigen::MatrixX3d expected = unitGrid({3, 3, 3});
  const double c = std::cos(5.0 * pi / 180.0), sn = std::sin(5.0 * pi / 180.0);
  for (Eigen::Index idx : {18, 19, 21, 22}) {
    const double x = expected(idx, 0) - 0.25, y = expected(idx, 1) - 0.25;
    expected.row(idx) << 0.25 + c * x - sn * y, 0.25 + sn * x + c * y, 1.0;
  }
  expected(6, 0) += 0.5;
  expected(7, 0) += 0.5;
  expected(8, 2) += 0.25;
  EXPECT_LE((fig62.controlPoints(onlyRoot(fig62)) - expected).cwiseAbs().maxCoeff(), 1e-15);
  // Figs. 6-8, 6-9, 6-10 are stored at rest: the unit grid, the child a half-size box on top.
  const WidgetModel fig68 = readWidgetFile(dir / "fig6-8.json");
  EXPECT_LE((fig68.controlPoints(onlyRoot(fig68)) - unitGrid({2, 3, 2})).cwiseAbs().maxCoeff(), 0.0);
  const WidgetModel fig69 = readWidgetFile(dir / "fig6-9.json");
  EXPECT_LE((fig69.controlPoints(fig69.find("parent")) - unitGrid({2, 2, 2})).cwiseAbs().maxCoeff(), 0.0);
  const WidgetModel fig610 = readWidgetFile(dir / "fig6-10-press.json");
  EXPECT_LE((fig610.controlPoints(onlyRoot(fig610)) - unitGrid({2, 2, 2})).cwiseAbs().maxCoeff(), 0.0);
  // The press's screw: 0.1 per turn (gain 0.1 / (2 pi)), clamped to [0, 0.15].
  bool screwFound = false;
  for (widgets::BindingId b : fig610.bindings()) {
    const widgets::Binding& binding = fig610.binding(b);
    if (binding.kind != widgets::BindingKind::Variation) continue;
    screwFound = true;
    EXPECT_NEAR(binding.rule.gain, 0.1 / (2.0 * pi), 1e-17);
    ASSERT_TRUE(binding.rule.clamp.has_value());
    EXPECT_EQ(binding.rule.clamp->min, 0.0);
    EXPECT_EQ(binding.rule.clamp->max, 0.15);
  }
  EXPECT_TRUE(screwFound);
}

}  // namespace
}  // namespace ffdkit::scenes
