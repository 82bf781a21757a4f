// The edit mode's point selection (app/interaction/point_selection.h): picks, boxes, all / none /
// invert, linked rows and planes, against index sets written out by hand.
#include <gtest/gtest.h>

#include "ffdkit/interaction/point_selection.h"

namespace ffdkit::app {
namespace {

using Indices = std::vector<Eigen::Index>;

PointSelection grid333() { return PointSelection(widgets::WidgetId(1), Eigen::Vector3i(3, 3, 3)); }

TEST(PointSelection, ClickReplacesShiftClickTogglesAndTheActivePointFollows) {
  PointSelection s = grid333();
  s.pick(4, SelectMode::Replace);
  s.pick(13, SelectMode::Replace);
  EXPECT_EQ(s.indices(), Indices{13});
  s.pick(4, SelectMode::Toggle);
  EXPECT_EQ(s.indices(), (Indices{4, 13}));
  EXPECT_EQ(s.active(), 4);
  s.pick(4, SelectMode::Toggle);
  EXPECT_EQ(s.indices(), Indices{13});
  EXPECT_FALSE(s.active().has_value());  // it left the selection
  EXPECT_EQ(s.count(), 1);
  EXPECT_THROW(s.pick(27, SelectMode::Add), std::out_of_range);
}

TEST(PointSelection, BoxesReplaceAddAndSubtract) {
  PointSelection s = grid333();
  s.pickMany({0, 1, 2}, SelectMode::Replace);
  s.pickMany({2, 5}, SelectMode::Add);
  EXPECT_EQ(s.indices(), (Indices{0, 1, 2, 5}));
  s.pickMany({1, 2}, SelectMode::Subtract);
  EXPECT_EQ(s.indices(), (Indices{0, 5}));
  s.pickMany({7}, SelectMode::Replace);
  EXPECT_EQ(s.indices(), Indices{7});
}

TEST(PointSelection, AllNoneInvert) {
  PointSelection s = grid333();
  s.selectAll();
  EXPECT_EQ(s.count(), 27);
  s.pick(0, SelectMode::Subtract);
  s.invert();
  EXPECT_EQ(s.indices(), Indices{0});
  s.selectNone();
  EXPECT_TRUE(s.empty());
}

TEST(PointSelection, LinkedRowsAndPlanes) {
  PointSelection s = grid333();
  s.pick(s.flatIndex({1, 2, 0}), SelectMode::Replace);
  s.selectLinked(0, /*plane=*/false);  // the row along i through (1,2,0): (0..2, 2, 0)
  EXPECT_EQ(s.indices(), (Indices{6, 7, 8}));
  s.pick(s.flatIndex({0, 0, 2}), SelectMode::Replace);
  s.selectLinked(2, /*plane=*/true);  // the plane k = 2: flat 18..26
  Indices plane;
  for (Eigen::Index i = 18; i < 27; ++i) plane.push_back(i);
  EXPECT_EQ(s.indices(), plane);
  EXPECT_THROW(s.selectLinked(3, true), std::invalid_argument);
  EXPECT_EQ(s.gridIndex(23), Eigen::Vector3i(2, 1, 2));
}

TEST(PointSelection, PointsInARectangleInAnyCornerOrder) {
  Eigen::MatrixX2d screen(4, 2);
  screen << 10, 10, 20, 20, 30, 5, 15, 25;
  EXPECT_EQ(pointsInRectangle(screen, {21, 21}, {9, 9}), (Indices{0, 1}));
  EXPECT_EQ(pointsInRectangle(screen, {0, 0}, {100, 100}).size(), 4u);
  EXPECT_TRUE(pointsInRectangle(screen, {40, 40}, {50, 50}).empty());
}

}  // namespace
}  // namespace ffdkit::app
