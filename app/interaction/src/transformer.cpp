#include "ffdkit/interaction/transformer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "wrap_angle.h"

namespace ffdkit::app {
namespace {

using L = TransformerLayout;

enum class Group { Move, Turn, Size };

Group groupOf(TransformerHandle h) {
  switch (h) {
    case TransformerHandle::MoveX:
    case TransformerHandle::MoveY:
    case TransformerHandle::MoveZ: return Group::Move;
    case TransformerHandle::TurnX:
    case TransformerHandle::TurnY:
    case TransformerHandle::TurnZ: return Group::Turn;
    default: return Group::Size;
  }
}

TransformerHandle handleOf(Group g, int axis) {
  const int base = g == Group::Move ? 0 : g == Group::Turn ? 3 : 6;
  return static_cast<TransformerHandle>(base + axis);
}

using detail::wrapAngle;

// Samples per ring when picking: the chord sagitta of a 64-gon is 0.12 % of the radius.
constexpr int kRingSegments = 64;

}  // namespace

int transformerAxis(TransformerHandle handle) { return static_cast<int>(handle) % 3; }

const char* transformerHandleName(TransformerHandle handle) {
  static const char* const names[] = {"move x", "move y", "move z", "turn x", "turn y",
                                      "turn z", "size x", "size y", "size z"};
  return names[static_cast<int>(handle)];
}

std::optional<TransformerHandle> pickTransformer(const Transformer& transformer, const widgets::Ray& ray,
                                                 double tolerance) {
  const Eigen::Vector3d o = transformer.frame.translation();
  const Eigen::Matrix3d axes = transformer.frame.linear();
  const double s = transformer.size;
  const Eigen::Vector3d dir = ray.direction.normalized();
  std::optional<TransformerHandle> best;
  double bestT = std::numeric_limits<double>::infinity();
  auto offer = [&](TransformerHandle h, double t) {
    if (t < bestT) {
      bestT = t;
      best = h;
    }
  };
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d a = axes.col(i);
    // Move: the shaft and its cone (radius up to 0.08 size).
    if (auto hit = widgets::closestRaySegment(ray, o + L::moveFrom * s * a, o + L::moveTip * s * a))
      if (hit->distance <= tolerance + 0.06 * s) offer(handleOf(Group::Move, i), hit->t);
    // Size: a cube, picked as a sphere around it.
    const Eigen::Vector3d c = o + L::sizeAt * s * a;
    const double along = (c - ray.origin).dot(dir);
    if (along > 0.0 && (ray.origin + along * dir - c).norm() <= tolerance + 1.5 * L::sizeHalf * s)
      offer(handleOf(Group::Size, i), along);
    // Turn: the ring about axis i, as a polygon (robust when seen edge-on).
    const Eigen::Vector3d e1 = axes.col((i + 1) % 3), e2 = axes.col((i + 2) % 3);
    const double r = L::turnRadius * s;
    Eigen::Vector3d previous = o + r * e1;
    for (int k = 1; k <= kRingSegments; ++k) {
      const double phi = 2.0 * std::numbers::pi * k / kRingSegments;
      const Eigen::Vector3d next = o + r * (std::cos(phi) * e1 + std::sin(phi) * e2);
      if (auto hit = widgets::closestRaySegment(ray, previous, next))
        if (hit->distance <= tolerance + 0.03 * s) offer(handleOf(Group::Turn, i), hit->t);
      previous = next;
    }
  }
  return best;
}

TransformerDrag::TransformerDrag(const Transformer& atPress, TransformerHandle handle, const widgets::Ray& pressRay)
    : start_(atPress), handle_(handle), axis_(atPress.frame.linear().col(transformerAxis(handle))) {
  switch (groupOf(handle)) {
    case Group::Move:
      value_ = 0.0;
      startParameter_ = axisParameter(pressRay).value_or(0.0);
      break;
    case Group::Size:
      value_ = 1.0;
      // The press was on the cube: its axis parameter is about sizeAt * size, never near zero.
      startParameter_ = axisParameter(pressRay).value_or(L::sizeAt * start_.size);
      if (!(std::abs(startParameter_) > 1e-9 * start_.size)) startParameter_ = L::sizeAt * start_.size;
      break;
    case Group::Turn: {
      value_ = 0.0;
      if (auto angle = planeAngle(pressRay)) {
        lastAngle_ = *angle;
      } else {
        // Seen edge-on: take the direction of the ray's closest approach to the centre.
        const Eigen::Vector3d o = start_.frame.translation();
        const Eigen::Vector3d dir = pressRay.direction.normalized();
        const Eigen::Vector3d p = pressRay.origin + (o - pressRay.origin).dot(dir) * dir - o;
        const int i = transformerAxis(handle);
        lastAngle_ = std::atan2(p.dot(start_.frame.linear().col((i + 2) % 3)), p.dot(start_.frame.linear().col((i + 1) % 3)));
      }
      break;
    }
  }
}

std::optional<double> TransformerDrag::axisParameter(const widgets::Ray& ray) const {
  return widgets::closestLineParameter(ray, start_.frame.translation(), axis_);
}

std::optional<double> TransformerDrag::planeAngle(const widgets::Ray& ray) const {
  const Eigen::Vector3d o = start_.frame.translation();
  // A plane seen almost edge-on gives wild hit points: treat it as parallel.
  if (std::abs(ray.direction.normalized().dot(axis_)) < 1e-3) return std::nullopt;
  const auto t = widgets::intersectPlane(ray, o, axis_);
  if (!t) return std::nullopt;
  const Eigen::Vector3d p = ray.at(*t) - o;
  const int i = transformerAxis(handle_);
  const Eigen::Vector3d e1 = start_.frame.linear().col((i + 1) % 3), e2 = start_.frame.linear().col((i + 2) % 3);
  if (p.norm() < 1e-12 * start_.size) return std::nullopt;
  return std::atan2(p.dot(e2), p.dot(e1));
}

Eigen::Affine3d TransformerDrag::motion(const widgets::Ray& ray) {
  switch (groupOf(handle_)) {
    case Group::Move:
      if (auto s = axisParameter(ray)) value_ = *s - startParameter_;
      break;
    case Group::Size:
      if (auto s = axisParameter(ray)) value_ = std::max(minFactor, *s / startParameter_);
      break;
    case Group::Turn:
      if (auto angle = planeAngle(ray)) {
        value_ += wrapAngle(*angle - lastAngle_);  // unwrap: several turns accumulate
        lastAngle_ = *angle;
      }
      break;
  }
  return motionFor(value_);
}

Eigen::Affine3d TransformerDrag::motionFor(double value) const {
  const Eigen::Vector3d o = start_.frame.translation();
  switch (groupOf(handle_)) {
    case Group::Move: return Eigen::Affine3d(Eigen::Translation3d(value * axis_));
    case Group::Turn:
      return Eigen::Translation3d(o) * Eigen::AngleAxisd(value, axis_) * Eigen::Translation3d(-o);
    case Group::Size: {
      // About the origin: uniformly, or along the axis only (I + (f - 1) a a^T).
      const Eigen::Matrix3d linear = start_.uniformSize
                                         ? Eigen::Matrix3d(value * Eigen::Matrix3d::Identity())
                                         : Eigen::Matrix3d(Eigen::Matrix3d::Identity() + (value - 1.0) * axis_ * axis_.transpose());
      Eigen::Affine3d m = Eigen::Affine3d::Identity();
      m.linear() = linear;
      m.translation() = o - linear * o;
      return m;
    }
  }
  return Eigen::Affine3d::Identity();
}

}  // namespace ffdkit::app
