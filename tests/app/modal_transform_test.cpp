// The maths of G / R / S (app/interaction/modal_transform.h): pointer rays, axis constraints,
// typed values and snapping give motions checked against hand-made expectations.
#include <gtest/gtest.h>

#include <numbers>

#include "ffdkit/interaction/modal_transform.h"
#include "edit_test_document.h"

namespace ffdkit::app {
namespace {
using test::kView;

using std::numbers::pi;

// A camera looking down -z from above: the ray through the point (x, y) of the plane z = 0.
widgets::Ray down(double x, double y) {
  widgets::Ray r;
  r.origin = {x, y, 10.0};
  r.direction = {0.0, 0.0, -1.0};
  return r;
}
TEST(ModalTransform, FreeMoveFollowsThePointerInTheViewPlane) {
  ModalTransform t(TransformMode::Move, {1, 1, 0}, down(1.2, 1.0), kView);
  const Eigen::Affine3d m = t.motion(down(1.5, 0.7), false);
  EXPECT_TRUE(m.linear().isIdentity());
  EXPECT_TRUE(m.translation().isApprox(Eigen::Vector3d(0.3, -0.3, 0.0), 1e-14));
}

TEST(ModalTransform, AxisAndPlaneConstraints) {
  ModalTransform t(TransformMode::Move, {0, 0, 0}, down(0.0, 0.0), kView);
  t.setConstraint(t.constraint().pressed(0, false));
  EXPECT_EQ(t.constraint().describe(), "along x");
  EXPECT_TRUE(t.motion(down(0.4, 0.9), false).translation().isApprox(Eigen::Vector3d(0.4, 0, 0), 1e-14));
  t.setConstraint(t.constraint().pressed(1, true));  // Shift+Y: the xz plane
  EXPECT_EQ(t.constraint().describe(), "in the xz plane");
  // Seen from above the xz plane is edge-on: the last motion stays.
  EXPECT_TRUE(t.motion(down(0.9, 0.9), false).translation().isApprox(Eigen::Vector3d(0.4, 0, 0), 1e-14));
  t.setConstraint(t.constraint().pressed(1, true));  // the same key again frees it
  EXPECT_TRUE(t.constraint().free());
}

TEST(ModalTransform, TypedValuesMoveExactly) {
  ModalTransform t(TransformMode::Move, {0.3, 0.2, 0.1}, down(0.3, 0.2), kView);
  t.setConstraint({2, false});
  for (char c : std::string("0.5")) EXPECT_TRUE(t.typed().type(c));
  EXPECT_FALSE(t.typed().type('x'));
  const Eigen::Affine3d m = t.motion(down(3.0, 3.0), false);  // the pointer no longer matters
  EXPECT_EQ(m.translation(), Eigen::Vector3d(0.0, 0.0, 0.5));
  t.typed().clear();
  for (char c : std::string("0.1,-0.2,0.25")) t.typed().type(c);
  t.setConstraint({});
  EXPECT_EQ(t.motion(down(0, 0), false).translation(), Eigen::Vector3d(0.1, -0.2, 0.25));
  t.typed().clear();
  t.typed().type('-');
  EXPECT_FALSE(t.typed().components().has_value());  // not a number yet: the pointer rules
}

TEST(ModalTransform, RotateFollowsThePointerAndTypedDegreesTurnAboutTheAxis) {
  const Eigen::Vector3d pivot(1, 1, 0);
  ModalTransform t(TransformMode::Rotate, pivot, down(2.0, 1.0), kView);
  // A quarter turn counter-clockwise seen from above (the viewer looks down -z): about +z.
  Eigen::Affine3d m = t.motion(down(1.0, 2.0), false);
  EXPECT_TRUE((m * Eigen::Vector3d(2, 1, 0)).isApprox(Eigen::Vector3d(1, 2, 0), 1e-12));
  EXPECT_TRUE((m * pivot).isApprox(pivot, 1e-14));
  // Snapped to 5 degrees: a pointer at 47 degrees gives 45.
  ModalTransform s(TransformMode::Rotate, pivot, down(2.0, 1.0), kView);
  const double a = 47.0 * pi / 180.0;
  m = s.motion(down(1.0 + std::cos(a), 1.0 + std::sin(a)), true);
  EXPECT_NEAR(Eigen::AngleAxisd(m.linear()).angle(), 45.0 * pi / 180.0, 1e-12);
  // Typed: 5 degrees about +x, whatever the view.
  t.setConstraint({0, false});
  t.typed().type('5');
  m = t.motion(down(0, 0), false);
  const Eigen::Matrix3d expected = Eigen::AngleAxisd(5.0 * pi / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_LE((m.linear() - expected).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_TRUE((m * pivot).isApprox(pivot, 1e-14));
}

TEST(ModalTransform, ScaleByDistanceRatioAlongAnAxisOrTyped) {
  const Eigen::Vector3d pivot(0, 0, 0);
  ModalTransform t(TransformMode::Scale, pivot, down(1.0, 0.0), kView);
  Eigen::Affine3d m = t.motion(down(0.0, 2.0), false);
  EXPECT_TRUE(m.linear().isApprox(2.0 * Eigen::Matrix3d::Identity(), 1e-14));
  t.setConstraint({1, false});
  m = t.motion(down(0.0, 1.5), false);
  EXPECT_TRUE(m.linear().isApprox(Eigen::Vector3d(1, 1.5, 1).asDiagonal().toDenseMatrix(), 1e-14));
  t.setConstraint({1, true});
  for (char c : std::string("0.5")) t.typed().type(c);
  m = t.motion(down(0, 0), false);
  EXPECT_TRUE(m.linear().isApprox(Eigen::Vector3d(0.5, 1, 0.5).asDiagonal().toDenseMatrix(), 1e-15));
  t.typed().clear();
  t.setConstraint({});
  m = t.motion(down(0.0, 1.26), true);  // snapped to 0.1
  EXPECT_NEAR(m.linear()(0, 0), 1.3, 1e-12);
}

}  // namespace
}  // namespace ffdkit::app
