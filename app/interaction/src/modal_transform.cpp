#include "ffdkit/interaction/modal_transform.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "wrap_angle.h"

namespace ffdkit::app {

namespace {

using detail::wrapAngle;

double roundTo(double value, double step) { return step > 0.0 ? std::round(value / step) * step : value; }

const char* axisLetter(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

}  // namespace

AxisConstraint AxisConstraint::pressed(int key, bool shift) const {
  if (key < 0 || key > 2) return *this;
  if (axis == key && exclude == shift) return {};
  return {key, shift};
}

std::string AxisConstraint::describe() const {
  if (free()) return "";
  if (!exclude) return std::string("along ") + axisLetter(axis);
  std::string plane;
  for (int a = 0; a < 3; ++a)
    if (a != axis) plane += axisLetter(a);
  return "in the " + plane + " plane";
}

bool TypedValue::type(char c) {
  const bool digit = c >= '0' && c <= '9';
  if (!digit && c != '.' && c != '-' && c != ',') return false;
  if (c == ',' && std::count(text_.begin(), text_.end(), ',') >= 2) return false;
  text_.push_back(c);
  return true;
}

void TypedValue::backspace() {
  if (!text_.empty()) text_.pop_back();
}

std::optional<Eigen::Vector3d> TypedValue::components(int* count) const {
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  int n = 0;
  std::size_t from = 0;
  while (true) {
    const std::size_t comma = text_.find(',', from);
    const std::string part = text_.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
    if (part.empty()) return std::nullopt;
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (end != part.c_str() + part.size() || !std::isfinite(v)) return std::nullopt;
    out[n++] = v;
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  if (count != nullptr) *count = n;
  return out;
}

ModalTransform::ModalTransform(TransformMode mode, const Eigen::Vector3d& pivot, const widgets::Ray& startRay,
                               const Eigen::Vector3d& viewDirection, SnapSteps steps)
    : mode_(mode), pivot_(pivot), start_(startRay), view_(viewDirection.normalized()), steps_(steps) {}

Eigen::Affine3d ModalTransform::about(const Eigen::Matrix3d& linear) const {
  Eigen::Affine3d m = Eigen::Affine3d::Identity();
  m.linear() = linear;
  m.translation() = pivot_ - linear * pivot_;
  return m;
}

Eigen::Vector3d ModalTransform::rotationAxis() const {
  const Eigen::Vector3d towardViewer = -view_;
  if (constraint_.free()) return towardViewer;
  const Eigen::Vector3d a = Eigen::Vector3d::Unit(constraint_.axis);
  return a.dot(towardViewer) < 0.0 ? Eigen::Vector3d(-a) : a;
}

std::optional<Eigen::Vector3d> ModalTransform::moveHit(const widgets::Ray& ray) const {
  const Eigen::Vector3d normal = constraint_.free() ? view_ : Eigen::Vector3d::Unit(constraint_.axis);
  if (std::abs(ray.direction.normalized().dot(normal)) < 1e-6) return std::nullopt;
  const auto t = widgets::intersectPlane(ray, pivot_, normal);
  if (!t) return std::nullopt;
  return ray.at(*t);
}

Eigen::Affine3d ModalTransform::motion(const widgets::Ray& ray, bool snap) {
  int typedCount = 0;
  const std::optional<Eigen::Vector3d> typed = typed_.components(&typedCount);
  switch (mode_) {
    case TransformMode::Move: {
      if (typed) {
        Eigen::Vector3d d = Eigen::Vector3d::Zero();
        if (typedCount == 1) {
          // One number: along the constraint axis, else along the first axis the constraint allows.
          int axis = 0;
          if (!constraint_.free()) axis = constraint_.exclude ? (constraint_.axis == 0 ? 1 : 0) : constraint_.axis;
          d[axis] = (*typed)[0];
        } else {
          d = *typed;
          if (!constraint_.free()) {
            if (constraint_.exclude) {
              d[constraint_.axis] = 0.0;
            } else {
              const double keep = d[constraint_.axis];
              d.setZero();
              d[constraint_.axis] = keep;
            }
          }
        }
        distance_ = d;
      } else if (!constraint_.free() && !constraint_.exclude) {
        const Eigen::Vector3d a = Eigen::Vector3d::Unit(constraint_.axis);
        const auto s0 = widgets::closestLineParameter(start_, pivot_, a);
        const auto s = widgets::closestLineParameter(ray, pivot_, a);
        if (s0 && s) distance_ = (*s - *s0) * a;
      } else {
        const auto h0 = moveHit(start_);
        const auto h = moveHit(ray);
        if (h0 && h) distance_ = *h - *h0;
      }
      if (snap && !typed)
        for (int a = 0; a < 3; ++a) distance_[a] = roundTo(distance_[a], steps_.distance);
      Eigen::Affine3d m = Eigen::Affine3d::Identity();
      m.translation() = distance_;
      return m;
    }
    case TransformMode::Rotate: {
      double angle = angle_;
      if (typed) {
        angle = (*typed)[0] * std::numbers::pi / 180.0;
        angle_ = angle;
        const Eigen::Vector3d axis =
            constraint_.free() ? Eigen::Vector3d(-view_) : Eigen::Vector3d::Unit(constraint_.axis);
        return about(Eigen::AngleAxisd(angle, axis).toRotationMatrix());
      }
      // The pointer's turn about the pivot as seen in the view (unwrapped: several turns add up).
      const auto t0 = widgets::intersectPlane(start_, pivot_, view_);
      const auto t = widgets::intersectPlane(ray, pivot_, view_);
      if (t0 && t) {
        const Eigen::Vector3d s = start_.at(*t0) - pivot_, c = ray.at(*t) - pivot_;
        if (s.norm() > 1e-12 && c.norm() > 1e-12) {
          const double raw = std::atan2((-view_).dot(s.cross(c)), s.dot(c));
          angle_ += wrapAngle(raw - lastRaw_);
          lastRaw_ = raw;
        }
      }
      angle = snap ? roundTo(angle_, steps_.degrees * std::numbers::pi / 180.0) : angle_;
      return about(Eigen::AngleAxisd(angle, rotationAxis()).toRotationMatrix());
    }
    case TransformMode::Scale: {
      if (typed) {
        factor_ = (*typed)[0];
      } else {
        const auto t0 = widgets::intersectPlane(start_, pivot_, view_);
        const auto t = widgets::intersectPlane(ray, pivot_, view_);
        if (t0 && t) {
          const double d0 = (start_.at(*t0) - pivot_).norm();
          if (d0 > 1e-12) factor_ = (ray.at(*t) - pivot_).norm() / d0;
        }
        if (snap) factor_ = std::max(steps_.factor, roundTo(factor_, steps_.factor));
      }
      const double f = factor_;
      Eigen::Matrix3d linear = f * Eigen::Matrix3d::Identity();
      if (!constraint_.free()) {
        const Eigen::Vector3d a = Eigen::Vector3d::Unit(constraint_.axis);
        linear = constraint_.exclude ? Eigen::Matrix3d(f * Eigen::Matrix3d::Identity() + (1.0 - f) * a * a.transpose())
                                     : Eigen::Matrix3d(Eigen::Matrix3d::Identity() + (f - 1.0) * a * a.transpose());
      }
      return about(linear);
    }
  }
  return Eigen::Affine3d::Identity();
}

std::string ModalTransform::describe() const {
  char text[160];
  const std::string where = constraint_.describe();
  const std::string suffix = (where.empty() ? "" : " " + where) + (typed_.empty() ? "" : " [" + typed_.text() + "]");
  switch (mode_) {
    case TransformMode::Move:
      std::snprintf(text, sizeof text, "move (%.3f, %.3f, %.3f)", distance_.x(), distance_.y(), distance_.z());
      break;
    case TransformMode::Rotate: std::snprintf(text, sizeof text, "turn %.2f°", angle_ * 180.0 / std::numbers::pi); break;
    case TransformMode::Scale: std::snprintf(text, sizeof text, "scale x%.3f", factor_); break;
  }
  return text + suffix;
}

}  // namespace ffdkit::app
