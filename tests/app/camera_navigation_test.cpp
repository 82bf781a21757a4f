// The camera maths of the 3D view (app/interaction camera_navigation.h), headless: turntable
// orbit keeps the horizon level, trackball does not; framing puts a box inside the view and
// fills it; the keypad views look exactly along the axes; orthographic toggling keeps the size.
#include "ffdkit/interaction/camera_navigation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace ffdkit::app {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

Eigen::Vector3d dirOf(const ViewCamera& v) { return (v.camera.focalPoint - v.camera.position).normalized(); }
Eigen::Vector3d rightOf(const ViewCamera& v) { return dirOf(v).cross(v.camera.viewUp).normalized(); }

ViewCamera start() {
  ViewCamera v;  // scenes::Camera's default: (2.4, -3, 2) looking at the origin, z up
  v.camera.focalPoint = {0.3, -0.2, 0.1};
  return v;
}

// Normalised device coordinates of world point p in the view (x right, y up, [-1, 1] inside),
// from the camera's own basis: independent of frame()'s sphere argument.
Eigen::Vector2d ndc(const ViewCamera& v, double aspect, const Eigen::Vector3d& p) {
  const Eigen::Vector3d dir = dirOf(v), right = rightOf(v), up = right.cross(dir);
  const Eigen::Vector3d q = p - v.camera.position;
  const double halfHeight = v.parallel ? v.parallelScale : std::tan(0.5 * v.camera.viewAngleDegrees * kDegree);
  const double depth = v.parallel ? 1.0 : q.dot(dir);
  return {q.dot(right) / depth / (halfHeight * aspect), q.dot(up) / depth / halfHeight};
}

TEST(CameraNavigation, TurntableKeepsTheHorizonLevelAndTheDistance) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> pixels(-120.0, 120.0);
  ViewCamera v = start();
  const double distance = (v.camera.position - v.camera.focalPoint).norm();
  for (int step = 0; step < 200; ++step) {
    v = orbit(v, pixels(random), pixels(random));
    // No roll: the camera's horizontal axis stays horizontal, and up stays up.
    EXPECT_NEAR(rightOf(v).z(), 0.0, 1e-12);
    EXPECT_GT(v.camera.viewUp.z(), 0.0);
    EXPECT_NEAR(v.camera.viewUp.norm(), 1.0, 1e-12);
    EXPECT_NEAR(v.camera.viewUp.dot(dirOf(v)), 0.0, 1e-12);
    EXPECT_NEAR((v.camera.position - v.camera.focalPoint).norm(), distance, 1e-9);
    EXPECT_EQ(v.camera.focalPoint, start().camera.focalPoint);
  }
}

TEST(CameraNavigation, TurntableTurnsAboutWorldUpByTheDragAngle) {
  const ViewCamera v = start();
  const ViewCamera turned = orbit(v, 50.0, 0.0);  // 50 px * 0.4 deg/px = 20 deg
  const Eigen::Vector3d a = v.camera.position - v.camera.focalPoint, b = turned.camera.position - turned.camera.focalPoint;
  EXPECT_NEAR(a.z(), b.z(), 1e-12);  // same height: a turn about z
  // Dragging right turns the camera clockwise seen from above (the scene turns with the pointer).
  const double angle = std::atan2(b.y(), b.x()) - std::atan2(a.y(), a.x());
  EXPECT_NEAR(angle, -20.0 * kDegree, 1e-12);
  // Dragging down raises the camera by the drag angle.
  const ViewCamera raised = orbit(v, 0.0, 25.0);
  const double before = std::asin(-dirOf(v).z()), after = std::asin(-dirOf(raised).z());
  EXPECT_NEAR(after - before, 10.0 * kDegree, 1e-12);
}

TEST(CameraNavigation, TurntableStopsShortOfThePoles) {
  const ViewCamera top = orbit(start(), 0.0, 10000.0);
  EXPECT_NEAR(std::asin(-dirOf(top).z()), 89.9 * kDegree, 1e-9);
  EXPECT_NEAR(rightOf(top).z(), 0.0, 1e-12);
  const ViewCamera bottom = orbit(start(), 0.0, -10000.0);
  EXPECT_NEAR(std::asin(-dirOf(bottom).z()), -89.9 * kDegree, 1e-9);
}

TEST(CameraNavigation, TrackballCanRollWhereTurntableCannot) {
  OrbitOptions trackball;
  trackball.style = OrbitStyle::Trackball;
  ViewCamera t = start(), u = start();
  // A closed square path of the pointer.
  for (const auto& [dx, dy] : {std::pair{100.0, 0.0}, {0.0, 100.0}, {-100.0, 0.0}, {0.0, -100.0}}) {
    t = orbit(t, dx, dy, trackball);
    u = orbit(u, dx, dy);
  }
  EXPECT_GT(std::abs(rightOf(t).z()), 0.05);  // rolled
  EXPECT_NEAR(rightOf(u).z(), 0.0, 1e-12);
}

TEST(CameraNavigation, FrameShowsTheWholeBoxAndFillsTheView) {
  const Eigen::AlignedBox3d box(Eigen::Vector3d(4.0, 5.0, -1.0), Eigen::Vector3d(6.0, 5.5, 2.0));
  for (double aspect : {0.6, 1.0, 1.7}) {
    for (bool parallel : {false, true}) {
      ViewCamera v = start();
      v.parallel = parallel;
      const ViewCamera f = frame(v, box, {aspect});
      EXPECT_NEAR((f.camera.focalPoint - box.center()).norm(), 0.0, 1e-12);
      EXPECT_NEAR((dirOf(f) - dirOf(v)).norm(), 0.0, 1e-12);  // looks the same way
      double most = 0.0;
      for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector2d p = ndc(f, aspect, box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
        EXPECT_LT(std::abs(p.x()), 1.0) << "aspect " << aspect << " parallel " << parallel;
        EXPECT_LT(std::abs(p.y()), 1.0) << "aspect " << aspect << " parallel " << parallel;
        most = std::max({most, std::abs(p.x()), std::abs(p.y())});
      }
      EXPECT_GT(most, 0.5) << "aspect " << aspect << " parallel " << parallel;  // not a speck
    }
  }
  EXPECT_THROW(frame(start(), Eigen::AlignedBox3d()), std::invalid_argument);
  // A point: centred at the current distance.
  const ViewCamera p = frame(start(), Eigen::AlignedBox3d(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 2, 3)));
  EXPECT_NEAR((p.camera.position - p.camera.focalPoint).norm(), (start().camera.position - start().camera.focalPoint).norm(), 1e-12);
}

TEST(CameraNavigation, KeypadViewsLookExactlyAlongTheAxes) {
  struct Expected {
    ViewPreset preset;
    Eigen::Vector3d dir, up;
  };
  for (const Expected& e : {Expected{ViewPreset::Front, {0, 1, 0}, {0, 0, 1}}, Expected{ViewPreset::Back, {0, -1, 0}, {0, 0, 1}},
                            Expected{ViewPreset::Right, {-1, 0, 0}, {0, 0, 1}}, Expected{ViewPreset::Left, {1, 0, 0}, {0, 0, 1}},
                            Expected{ViewPreset::Top, {0, 0, -1}, {0, 1, 0}}, Expected{ViewPreset::Bottom, {0, 0, 1}, {0, -1, 0}}}) {
    const ViewCamera v = viewFrom(start(), e.preset);
    EXPECT_NEAR((dirOf(v) - e.dir).norm(), 0.0, 1e-15);
    EXPECT_EQ(v.camera.viewUp, e.up);
    EXPECT_EQ(v.camera.focalPoint, start().camera.focalPoint);
    EXPECT_NEAR((v.camera.position - v.camera.focalPoint).norm(), (start().camera.position - start().camera.focalPoint).norm(), 1e-12);
  }
}

TEST(CameraNavigation, OrthographicToggleKeepsTheSizeAtTheFocalPoint) {
  const ViewCamera v = start();
  const double distance = (v.camera.position - v.camera.focalPoint).norm();
  const ViewCamera o = toggledProjection(v);
  EXPECT_TRUE(o.parallel);
  EXPECT_NEAR(o.parallelScale, distance * std::tan(15.0 * kDegree), 1e-12);
  ViewCamera zoomed = o;
  zoomed.parallelScale *= 0.5;  // a zoom in parallel
  const ViewCamera back = toggledProjection(zoomed);
  EXPECT_FALSE(back.parallel);
  EXPECT_NEAR((back.camera.position - back.camera.focalPoint).norm(), 0.5 * distance, 1e-12);
  EXPECT_NEAR((dirOf(back) - dirOf(v)).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace ffdkit::app
