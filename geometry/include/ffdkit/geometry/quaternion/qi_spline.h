#pragma once

#include <vector>

#include "ffdkit/geometry/quaternion/arc_length_curve.h"
#include "ffdkit/geometry/quaternion/bezier_qi_segment.h"

namespace ffdkit::geometry::quaternion {

/// How a chain of Miura 1998 segments places each segment (sec. 5.3).
enum class SegmentPlacement {
  Anchored,  ///< segment i starts at its own data point P_i (Miura 1998, eq. (60))
  Chained,   ///< segment i starts at the computed end of segment i-1 (Miura 1998, Fig. 4, sec. 5.3)
};

/// A G2 chain of BezierQiSegment, evaluated by arc length s in [0, sum l_i] or by the global
/// parameter u = i + t in [0, n] that the paper plots against (Miura 1998, sec. 5.3).
class QiSpline : public ArcLengthCurve {
 public:
  /// @throws QuaternionCurveError if segments is empty.
  explicit QiSpline(std::vector<BezierQiSegment> segments, SegmentPlacement placement = SegmentPlacement::Anchored);

  /// The segments, in order.
  const std::vector<BezierQiSegment>& segments() const { return segments_; }
  /// Where segments start: anchored at the data points or chained end to end.
  SegmentPlacement placement() const { return placement_; }
  /// Start point of segment i under the placement.
  const Eigen::Vector3d& segmentStart(int i) const { return starts_[i]; }
  /// Arc length at the start of segment i (i = n gives the total length).
  double segmentArcStart(int i) const { return arcStarts_[i]; }

  /// (segment index, local t) of an arc length s (clamped).
  std::pair<int, double> locate(double s) const;
  /// Arc length of the global parameter u in [0, n].
  double arcLengthAtGlobal(double u) const;

  double length() const override { return arcStarts_.back(); }
  Eigen::Vector3d position(double s) const override;
  Eigen::Vector3d tangent(double s) const override;
  double curvature(double s) const override;
  double torsion(double s) const override;
  Eigen::Vector3d curvatureVector(double s) const override;

 private:
  std::vector<BezierQiSegment> segments_;
  SegmentPlacement placement_;
  std::vector<Eigen::Vector3d> starts_;
  std::vector<double> arcStarts_;
};

}  // namespace ffdkit::geometry::quaternion
