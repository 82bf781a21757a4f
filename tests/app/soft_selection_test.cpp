// Soft selection (app/interaction/soft_selection.h): Blender's falloff curves against their
// formulas written out here, distances straight and along the grid, the weights a transform
// gives, and a partial motion against a hand-made one.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "ffdkit/interaction/soft_selection.h"

namespace ffdkit::app {
namespace {

// A grid of l x m x n points at integer coordinates (i, j, k), flat index i + l*(j + m*k).
Eigen::MatrixX3d integerGrid(int l, int m, int n) {
  Eigen::MatrixX3d p(l * m * n, 3);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < l; ++i) p.row(i + l * (j + m * k)) << i, j, k;
  return p;
}

TEST(SoftSelection, FalloffsAreBlendersCurves) {
  const double radius = 2.0;
  for (double d : {0.0, 0.3, 0.5, 1.0, 1.37, 1.9, 2.0}) {
    const double f = (radius - d) / radius;
    EXPECT_NEAR(falloffWeight(Falloff::Smooth, d, radius), f * f * (3.0 - 2.0 * f), 1e-15) << d;
    EXPECT_NEAR(falloffWeight(Falloff::Sphere, d, radius), std::sqrt(f * (2.0 - f)), 1e-15) << d;
    EXPECT_NEAR(falloffWeight(Falloff::Root, d, radius), std::pow(f, 0.5), 1e-15) << d;
    EXPECT_NEAR(falloffWeight(Falloff::Linear, d, radius), 1.0 - d / radius, 1e-15) << d;
    EXPECT_NEAR(falloffWeight(Falloff::Sharp, d, radius), std::pow(1.0 - d / radius, 2.0), 1e-15) << d;
    EXPECT_EQ(falloffWeight(Falloff::Constant, d, radius), 1.0) << d;
  }
  // Ends: 1 at the selection, 0 at the radius (except constant) and beyond it (every curve).
  for (Falloff f : kFalloffs) {
    EXPECT_EQ(falloffWeight(f, 0.0, radius), 1.0) << falloffName(f);
    if (f != Falloff::Constant) {
      EXPECT_EQ(falloffWeight(f, radius, radius), 0.0) << falloffName(f);
    }
    EXPECT_EQ(falloffWeight(f, 2.0001, radius), 0.0) << falloffName(f);
    EXPECT_EQ(falloffWeight(f, std::numeric_limits<double>::infinity(), radius), 0.0) << falloffName(f);
  }
  // Half-way values, worked by hand: smooth 0.5, sphere sqrt(0.75), root sqrt(0.5), sharp 0.25.
  EXPECT_DOUBLE_EQ(falloffWeight(Falloff::Smooth, 1.0, 2.0), 0.5);
  EXPECT_DOUBLE_EQ(falloffWeight(Falloff::Sphere, 1.0, 2.0), std::sqrt(0.75));
  EXPECT_DOUBLE_EQ(falloffWeight(Falloff::Root, 1.0, 2.0), std::sqrt(0.5));
  EXPECT_DOUBLE_EQ(falloffWeight(Falloff::Sharp, 1.0, 2.0), 0.25);
}

TEST(SoftSelection, DistancesAreStraightOrAlongTheGrid) {
  const Eigen::MatrixX3d p = integerGrid(4, 3, 2);
  const std::vector<Eigen::Index> corner{0};  // (0, 0, 0)
  const Eigen::VectorXd straight = selectionDistances(p, {4, 3, 2}, corner, false);
  const Eigen::VectorXd along = selectionDistances(p, {4, 3, 2}, corner, true);
  for (Eigen::Index q = 0; q < p.rows(); ++q) {
    EXPECT_NEAR(straight(q), p.row(q).norm(), 1e-15);
    EXPECT_NEAR(along(q), p.row(q).lpNorm<1>(), 1e-15);  // unit edges: the Manhattan length
  }
  // Two selected points: the nearer one counts.
  const Eigen::VectorXd two = selectionDistances(p, {4, 3, 2}, {0, 3}, true);
  EXPECT_DOUBLE_EQ(two(2), 1.0);  // (2,0,0): one edge from (3,0,0)
  EXPECT_DOUBLE_EQ(two(1), 1.0);
  EXPECT_DOUBLE_EQ(two(23), 2.0 + 1.0 + 0.0);  // (3,2,1): from (3,0,0) two edges along j, one along k
  // Nothing selected: every point is infinitely far.
  EXPECT_TRUE(std::isinf(selectionDistances(p, {4, 3, 2}, {}, false).minCoeff()));
  EXPECT_THROW(selectionDistances(p, {4, 3, 3}, corner, false), std::invalid_argument);
  EXPECT_THROW(selectionDistances(p, {4, 3, 2}, {24}, false), std::invalid_argument);
}

// A lattice bent back on itself: the two ends of a U are near in space, far along the grid.
TEST(SoftSelection, ConnectedOnlyFollowsTheGridRoundABend) {
  Eigen::MatrixX3d p(6, 3);  // 6 x 1 x 1: along x out to 2, back along y = 0.5
  p << 0, 0, 0, 1, 0, 0, 2, 0, 0, 2, 0.5, 0, 1, 0.5, 0, 0, 0.5, 0;
  SoftSelection soft;
  soft.enabled = true;
  soft.radius = 1.0;
  soft.falloff = Falloff::Linear;
  const Eigen::VectorXd near = softSelectionWeights(soft, p, {6, 1, 1}, {0});
  EXPECT_DOUBLE_EQ(near(5), 0.5);  // 0.5 away in space
  soft.connectedOnly = true;
  const Eigen::VectorXd along = softSelectionWeights(soft, p, {6, 1, 1}, {0});
  EXPECT_EQ(along(5), 0.0);  // 4.5 along the grid
  EXPECT_EQ(along(0), 1.0);
  EXPECT_EQ(along(1), 0.0);  // exactly at the radius
  soft.enabled = false;
  const Eigen::VectorXd off = softSelectionWeights(soft, p, {6, 1, 1}, {0});
  EXPECT_EQ(off, (Eigen::VectorXd(6) << 1, 0, 0, 0, 0, 0).finished());
  soft.enabled = true;
  soft.radius = 0.0;
  EXPECT_THROW(softSelectionWeights(soft, p, {6, 1, 1}, {0}), std::invalid_argument);
}

TEST(SoftSelection, PartialMotionsScaleTheMoveTheAngleAndTheFactor) {
  const Eigen::Vector3d pivot(1, 2, 3), x(2.5, -1, 0.25);
  // A move: w times the translation.
  const Eigen::Affine3d move(Eigen::Translation3d(0.4, -0.2, 1.0));
  EXPECT_LT((partialMotion(move, pivot, 0.25) * x - (x + 0.25 * Eigen::Vector3d(0.4, -0.2, 1.0))).norm(), 1e-15);
  // A turn of 80 degrees about z through the pivot: w times the angle, about the same line.
  const double a = 80.0 * std::numbers::pi / 180.0;
  const Eigen::Affine3d turn = Eigen::Translation3d(pivot) * Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) *
                               Eigen::Translation3d(-pivot);
  const Eigen::Affine3d expected = Eigen::Translation3d(pivot) * Eigen::AngleAxisd(0.3 * a, Eigen::Vector3d::UnitZ()) *
                                   Eigen::Translation3d(-pivot);
  EXPECT_LT((partialMotion(turn, pivot, 0.3) * x - expected * x).norm(), 1e-14);
  // A scale by 2 along x about the pivot: 1 + w (2 - 1) at weight w.
  Eigen::Affine3d size = Eigen::Translation3d(pivot) * Eigen::Scaling(2.0, 1.0, 1.0) * Eigen::Translation3d(-pivot);
  const Eigen::Vector3d sized = partialMotion(size, pivot, 0.5) * x;
  EXPECT_NEAR(sized.x(), pivot.x() + 1.5 * (x.x() - pivot.x()), 1e-15);
  EXPECT_NEAR(sized.y(), x.y(), 1e-15);
  // Ends: weight 1 is the motion, weight 0 the identity.
  for (const Eigen::Affine3d& m : {move, turn, size}) {
    EXPECT_LT((partialMotion(m, pivot, 1.0) * x - m * x).norm(), 1e-14);
    EXPECT_LT((partialMotion(m, pivot, 0.0) * x - x).norm(), 1e-14);
  }
}

}  // namespace
}  // namespace ffdkit::app
