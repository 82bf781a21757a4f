#include "ffdkit/interaction/camera_navigation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ffdkit::app {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

Eigen::Vector3d direction(const scenes::Camera& c) { return (c.focalPoint - c.position).normalized(); }

// The camera turned rigidly by `turn` about its focal point (position and view up).
scenes::Camera turned(scenes::Camera c, const Eigen::Matrix3d& turn) {
  c.position = c.focalPoint + turn * (c.position - c.focalPoint);
  c.viewUp = turn * c.viewUp;
  return c;
}

// `up` made orthogonal to the direction of view, unit length (a roll-free view up); when `up`
// is along the direction, any unit vector orthogonal to it.
Eigen::Vector3d orthogonalUp(const Eigen::Vector3d& dir, const Eigen::Vector3d& up) {
  const Eigen::Vector3d u = up - up.dot(dir) * dir;
  if (u.norm() > 1e-12) return u.normalized();
  return dir.unitOrthogonal();
}

}  // namespace

ViewCamera orbit(const ViewCamera& view, double dx, double dy, const OrbitOptions& options) {
  ViewCamera out = view;
  scenes::Camera& c = out.camera;
  const double k = options.degreesPerPixel * kDegree;
  const Eigen::Vector3d dir = direction(c);
  if (options.style == OrbitStyle::Trackball) {
    // VTK's vtkInteractorStyleTrackballCamera: Azimuth about the view up, then Elevation about
    // the camera's right axis, both carried by the camera.
    const Eigen::Vector3d up = orthogonalUp(dir, c.viewUp);
    const Eigen::Vector3d right = dir.cross(up).normalized();
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(-dy * k, right).toRotationMatrix() *
                                 Eigen::AngleAxisd(-dx * k, up).toRotationMatrix();
    c = turned(c, turn);
    c.viewUp = orthogonalUp(direction(c), c.viewUp);
    return out;
  }
  const Eigen::Vector3d up = options.worldUp.normalized();
  // Elevation: the angle of the line of sight below the horizon (looking down is positive),
  // kept short of the poles so that the horizontal axis stays defined.
  const double limit = 89.9 * kDegree;
  const double elevation = std::asin(std::clamp(-dir.dot(up), -1.0, 1.0));
  const double target = std::clamp(elevation + dy * k, -limit, limit);
  Eigen::Vector3d right = dir.cross(up);
  if (right.norm() < 1e-12) right = dir.cross(orthogonalUp(dir, c.viewUp));  // started at a pole
  right.normalize();
  // A turn by -a about `right` raises the camera by a (the offset from the focal point is -dir).
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(-dx * k, up).toRotationMatrix() *
                               Eigen::AngleAxisd(-(target - elevation), right).toRotationMatrix();
  c = turned(c, turn);
  c.viewUp = orthogonalUp(direction(c), up);
  return out;
}

ViewCamera frame(const ViewCamera& view, const Eigen::AlignedBox3d& box, const FrameOptions& options) {
  if (box.isEmpty()) throw std::invalid_argument("frame: the box is empty");
  if (!(options.aspect > 0.0) || !(options.margin > 0.0))
    throw std::invalid_argument("frame: aspect and margin must be positive, got " + std::to_string(options.aspect) +
                                " and " + std::to_string(options.margin));
  ViewCamera out = view;
  scenes::Camera& c = out.camera;
  const Eigen::Vector3d dir = direction(c);
  const double radius = 0.5 * box.diagonal().norm() * options.margin;
  const double halfHeight = 0.5 * c.viewAngleDegrees * kDegree;
  // The narrower of the two half-angles of the view (a tall view: the horizontal one).
  const double halfWidth = std::atan(std::tan(halfHeight) * options.aspect);
  const double half = std::min(halfHeight, halfWidth);
  double distance = (c.position - c.focalPoint).norm();
  if (radius > 0.0) {
    // A sphere of radius r seen from distance D fills a half-angle asin(r / D).
    distance = radius / std::sin(half);
    out.parallelScale = radius / std::min(1.0, options.aspect);
  }
  c.focalPoint = box.center();
  c.position = c.focalPoint - distance * dir;
  return out;
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> viewPresetAxes(ViewPreset preset) {
  using V = Eigen::Vector3d;
  switch (preset) {
    case ViewPreset::Front: return {V::UnitY(), V::UnitZ()};
    case ViewPreset::Back: return {-V::UnitY(), V::UnitZ()};
    case ViewPreset::Right: return {-V::UnitX(), V::UnitZ()};
    case ViewPreset::Left: return {V::UnitX(), V::UnitZ()};
    case ViewPreset::Top: return {-V::UnitZ(), V::UnitY()};
    case ViewPreset::Bottom: return {V::UnitZ(), -V::UnitY()};
  }
  throw std::invalid_argument("unknown view preset");
}

ViewCamera viewFrom(const ViewCamera& view, ViewPreset preset) {
  ViewCamera out = view;
  scenes::Camera& c = out.camera;
  const auto [dir, up] = viewPresetAxes(preset);
  const double distance = (c.position - c.focalPoint).norm();
  c.position = c.focalPoint - distance * dir;
  c.viewUp = up;
  return out;
}

ViewCamera toggledProjection(const ViewCamera& view) {
  ViewCamera out = view;
  scenes::Camera& c = out.camera;
  const double tanHalf = std::tan(0.5 * c.viewAngleDegrees * kDegree);
  if (!view.parallel) {
    out.parallelScale = (c.position - c.focalPoint).norm() * tanHalf;
  } else {
    c.position = c.focalPoint - (view.parallelScale / tanHalf) * direction(c);
  }
  out.parallel = !view.parallel;
  return out;
}

}  // namespace ffdkit::app
