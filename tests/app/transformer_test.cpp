// The transformer manipulator's geometry: which handle a ray hits and which world motion a drag
// of it means. Rays are aimed at the handles of TransformerLayout; motions are checked against
// the exact ray geometry.
#include "ffdkit/interaction/transformer.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace ffdkit::app {
namespace {

using L = TransformerLayout;
using std::numbers::pi;

// A transformer at (1, 2, 3), turned 30 degrees about z, of size 2.
Transformer tilted() {
  Transformer t;
  t.frame = Eigen::Translation3d(1, 2, 3) * Eigen::AngleAxisd(pi / 6, Eigen::Vector3d::UnitZ());
  t.size = 2.0;
  return t;
}

// A ray from `from` through `to`.
widgets::Ray ray(const Eigen::Vector3d& from, const Eigen::Vector3d& to) { return {from, to - from}; }

// A ray looking along -view at the world point p.
widgets::Ray looking(const Eigen::Vector3d& p, const Eigen::Vector3d& view) { return ray(p + 10.0 * view, p); }

TEST(Transformer, EachHandleIsPickedWhereItIsDrawn) {
  const Transformer t = tilted();
  const Eigen::Vector3d o = t.frame.translation();
  const Eigen::Vector3d oblique = Eigen::Vector3d(0.3, -0.5, 1.0).normalized();
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d a = t.frame.linear().col(i);
    const Eigen::Vector3d b = t.frame.linear().col((i + 1) % 3);
    const Eigen::Vector3d c = t.frame.linear().col((i + 2) % 3);
    // The shaft, seen from between the other two axes.
    const auto move = pickTransformer(t, looking(o + 0.6 * t.size * a, (b + c).normalized()), 1e-3);
    ASSERT_TRUE(move.has_value());
    EXPECT_EQ(*move, static_cast<TransformerHandle>(i)) << transformerHandleName(*move);
    // A point of the ring about a, between the other two axes, seen along a (face-on).
    const Eigen::Vector3d onRing = o + L::turnRadius * t.size * (std::cos(0.7) * b + std::sin(0.7) * c);
    const auto turn = pickTransformer(t, looking(onRing, a), 1e-3);
    ASSERT_TRUE(turn.has_value());
    EXPECT_EQ(*turn, static_cast<TransformerHandle>(3 + i)) << transformerHandleName(*turn);
    // The same ring seen edge-on still picks.
    const auto edgeOn = pickTransformer(t, looking(onRing, (onRing - o).cross(a).normalized().cross(a) + 1e-9 * a), 1e-3);
    ASSERT_TRUE(edgeOn.has_value());
    EXPECT_EQ(*edgeOn, static_cast<TransformerHandle>(3 + i));
    // The size cube, seen along the shaft's side.
    const auto size = pickTransformer(t, looking(o + L::sizeAt * t.size * a, b + c), 1e-3);
    ASSERT_TRUE(size.has_value());
    EXPECT_EQ(*size, static_cast<TransformerHandle>(6 + i)) << transformerHandleName(*size);
  }
  // The inner part of the axes is free (the widget's own glyph lives there), and so is the
  // space beyond the handles.
  EXPECT_FALSE(pickTransformer(t, looking(o + 0.3 * t.size * t.frame.linear().col(0), oblique), 1e-3).has_value());
  EXPECT_FALSE(pickTransformer(t, looking(o + 3.0 * t.size * Eigen::Vector3d(1, 1, 1).normalized(), oblique), 1e-3));
  // Tolerance widens the pick: 0.1 beside the cube misses at 1e-3 and hits at 0.2.
  const Eigen::Vector3d beside = o + L::sizeAt * t.size * t.frame.linear().col(2) +
                                 (1.5 * L::sizeHalf * t.size + 0.1) * t.frame.linear().col(0);
  EXPECT_FALSE(pickTransformer(t, looking(beside, t.frame.linear().col(1)), 1e-3).has_value());
  EXPECT_TRUE(pickTransformer(t, looking(beside, t.frame.linear().col(1)), 0.2).has_value());
}

TEST(Transformer, MoveFollowsTheClosestPointOnTheAxis) {
  const Transformer t = tilted();
  const Eigen::Vector3d o = t.frame.translation();
  const Eigen::Vector3d a = t.frame.linear().col(1);
  const Eigen::Vector3d view = Eigen::Vector3d(0.2, 0.1, 1.0).normalized();
  TransformerDrag drag(t, TransformerHandle::MoveY, looking(o + 0.8 * t.size * a, view));
  // The mouse moves to a point 0.37 further along the axis, plus a sideways offset that a move
  // along the axis ignores.
  const Eigen::Vector3d sideways = view.cross(a).normalized();
  const Eigen::Affine3d m = drag.motion(looking(o + (0.8 * t.size + 0.37) * a + 0.3 * sideways, view));
  EXPECT_NEAR(drag.value(), 0.37, 1e-12);
  EXPECT_TRUE(m.linear().isIdentity(1e-15));
  EXPECT_TRUE(m.translation().isApprox(0.37 * a, 1e-12));
  // Computed from the press: back at the press ray, no motion.
  EXPECT_TRUE(drag.motion(looking(o + 0.8 * t.size * a, view)).matrix().isIdentity(1e-12));
  // A ray parallel to the axis keeps the last motion.
  drag.motion(looking(o + (0.8 * t.size - 0.2) * a, view));
  const Eigen::Affine3d kept = drag.motion(ray(o - 5.0 * a + Eigen::Vector3d(0, 0, 1), o + Eigen::Vector3d(0, 0, 1)));
  EXPECT_TRUE(kept.translation().isApprox(-0.2 * a, 1e-12));
}

TEST(Transformer, TurnAccumulatesTheAngleAboutTheAxisAcrossWholeTurns) {
  const Transformer t = tilted();
  const Eigen::Vector3d o = t.frame.translation();
  const Eigen::Vector3d z = t.frame.linear().col(2), x = t.frame.linear().col(0), y = t.frame.linear().col(1);
  auto at = [&](double angle) { return looking(o + L::turnRadius * t.size * (std::cos(angle) * x + std::sin(angle) * y), z); };
  TransformerDrag drag(t, TransformerHandle::TurnZ, at(0.2));
  const Eigen::Affine3d m = drag.motion(at(0.2 + pi / 2));
  EXPECT_NEAR(drag.value(), pi / 2, 1e-12);
  EXPECT_TRUE(m.linear().isApprox(Eigen::AngleAxisd(pi / 2, z).toRotationMatrix(), 1e-12));
  EXPECT_TRUE((m * o).isApprox(o, 1e-12));  // about the transformer's origin
  // Around one and a quarter turns, in small steps: the angle unwraps.
  for (int k = 1; k <= 50; ++k) drag.motion(at(0.2 + k * 2.5 * pi / 50));
  EXPECT_NEAR(drag.value(), 2.5 * pi, 1e-9);
  // The hit's distance from the centre does not matter, only its angle.
  drag.motion(looking(o + 0.1 * (std::cos(0.2 + pi) * x + std::sin(0.2 + pi) * y), z));
  EXPECT_NEAR(drag.value(), 3.0 * pi, 1e-9);
}

TEST(Transformer, SizeScalesAlongItsAxisOrUniformlyAboutTheOrigin) {
  Transformer t = tilted();
  const Eigen::Vector3d o = t.frame.translation();
  const Eigen::Vector3d a = t.frame.linear().col(0), b = t.frame.linear().col(1);
  const Eigen::Vector3d view = t.frame.linear().col(2);
  const double at = L::sizeAt * t.size;
  TransformerDrag drag(t, TransformerHandle::SizeX, looking(o + at * a, view));
  const Eigen::Affine3d m = drag.motion(looking(o + 1.5 * at * a + 0.3 * b, view));
  EXPECT_NEAR(drag.value(), 1.5, 1e-12);
  EXPECT_TRUE((m * o).isApprox(o, 1e-12));
  EXPECT_TRUE((m.linear() * a).isApprox(1.5 * a, 1e-12));
  EXPECT_TRUE((m.linear() * b).isApprox(b, 1e-12));
  // Dragged through the origin and beyond: the factor stops at minFactor, never flips.
  drag.motion(looking(o - at * a, view));
  EXPECT_EQ(drag.value(), TransformerDrag::minFactor);
  // Uniform (an affine widget's size).
  t.uniformSize = true;
  TransformerDrag uniform(t, TransformerHandle::SizeX, looking(o + at * a, view));
  const Eigen::Affine3d u = uniform.motion(looking(o + 0.5 * at * a, view));
  EXPECT_TRUE(u.linear().isApprox(0.5 * Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_TRUE((u * o).isApprox(o, 1e-12));
}

}  // namespace
}  // namespace ffdkit::app
