#pragma once

#include <vector>

#include <Eigen/Core>

namespace ffdkit::app {

/// A curvature comb of a polyline: at each sample a tooth from the curve point along the
/// principal normal (toward the centre of curvature), of length scale * curvature, and the
/// polyline joining the tooth tips.
struct CurvatureComb {
  Eigen::MatrixX3d bases;    ///< the curve points with a tooth
  Eigen::MatrixX3d tips;     ///< bases + scale * curvature * normal, row for row
  Eigen::VectorXd curvature; ///< discrete curvature at each base (>= 0)
};

/// Discrete curvature comb of the polyline `points` (#P x 3, in order; `closed` joins the last
/// point to the first): the curvature at a point is that of the circle through it and its two
/// neighbours (Menger curvature 4 * area / product of the three side lengths), the normal points
/// toward that circle's centre; it tends to the curve's curvature and principal normal as the
/// samples get denser. Open polylines get no tooth at their two end points; a straight run (or
/// repeated points) gets zero-length teeth. `scale`: tooth length per unit curvature (world
/// length squared).
CurvatureComb curvatureComb(const Eigen::MatrixX3d& points, bool closed, double scale);

/// Splits line segments (pairs of point indices) into chains of point indices in curve order;
/// a chain whose last point equals its first is closed (the first index is then repeated).
std::vector<std::vector<int>> segmentChains(const Eigen::MatrixX2i& segments, Eigen::Index pointCount);

}  // namespace ffdkit::app
