#include "ffdkit/geometry/quaternion/qi_spline.h"

#include <algorithm>

#include "ffdkit/geometry/quaternion/quaternion_error.h"

namespace ffdkit::geometry::quaternion {

QiSpline::QiSpline(std::vector<BezierQiSegment> segments, SegmentPlacement placement)
    : segments_(std::move(segments)), placement_(placement) {
  if (segments_.empty()) {
    throw QuaternionCurveError("QiSpline: expected at least one segment, got 0");
  }
  arcStarts_.push_back(0.0);
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    if (placement_ == SegmentPlacement::Chained && i > 0) {
      starts_.push_back(starts_.back() + segments_[i - 1].length() * segments_[i - 1].chordIntegral());
    } else {
      starts_.push_back(segments_[i].start());
    }
    arcStarts_.push_back(arcStarts_.back() + segments_[i].length());
  }
}

std::pair<int, double> QiSpline::locate(double s) const {
  const double sc = std::clamp(s, 0.0, length());
  const auto it = std::upper_bound(arcStarts_.begin(), arcStarts_.end(), sc);
  int i = static_cast<int>(it - arcStarts_.begin()) - 1;
  i = std::clamp(i, 0, static_cast<int>(segments_.size()) - 1);
  return {i, std::clamp((sc - arcStarts_[i]) / segments_[i].length(), 0.0, 1.0)};
}

double QiSpline::arcLengthAtGlobal(double u) const {
  const int n = static_cast<int>(segments_.size());
  const double uc = std::clamp(u, 0.0, static_cast<double>(n));
  const int i = std::min(static_cast<int>(uc), n - 1);
  return arcStarts_[i] + (uc - i) * segments_[i].length();
}

Eigen::Vector3d QiSpline::position(double s) const {
  const auto [i, t] = locate(s);
  const BezierQiSegment& seg = segments_[i];
  return starts_[i] + (seg.point(t) - seg.start());
}

Eigen::Vector3d QiSpline::tangent(double s) const {
  const auto [i, t] = locate(s);
  return segments_[i].tangent(t);
}

double QiSpline::curvature(double s) const {
  const auto [i, t] = locate(s);
  return segments_[i].curvature(t);
}

double QiSpline::torsion(double s) const {
  const auto [i, t] = locate(s);
  return segments_[i].torsion(t);
}

Eigen::Vector3d QiSpline::curvatureVector(double s) const {
  const auto [i, t] = locate(s);
  return segments_[i].curvatureVector(t);
}

}  // namespace ffdkit::geometry::quaternion
