#pragma once
// Internal to the curve network: where the curves of a network meet (Kuriyama 1996, sec. 5.3.3,
// steps 1-2): the closest points of every pair of curves within the tolerance, T-junctions
// snapped to open ends, near misses noted, crossings too shallow refused.

#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/curvenet/curve_network.h"

namespace ffdkit::geometry::curvenet::detail {

/// "(x, y, z)" with 6 significant digits, for messages.
inline std::string formatPoint(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s.precision(6);
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

/// Where curves a < b meet: their parameters, the distance of their closest points and the midpoint.
struct PairHit {
  int a = -1, b = -1;
  double ta = 0.0, tb = 0.0, distance = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

/// The samples of a network's curves the search starts from.
struct CurveSamples {
  const std::vector<Eigen::MatrixX3d>& points;  ///< per curve, samplesPerSegment per segment
  const std::vector<Eigen::VectorXd>& params;   ///< their parameters
  int samplesPerSegment = 8;                    ///< samples per curve segment
};

/// Every meeting of two curves of `network` (its curves and names), closer than `tolerance`.
/// A pair that passes within 3 x tolerance without meeting adds a line to network.notes.
/// @throws CurveNetworkError for two curves meeting at less than `minimumCrossingAngleDegrees`.
std::vector<PairHit> findCurveIntersections(CurveNetwork& network, const CurveSamples& samples, double tolerance,
                                            double minimumCrossingAngleDegrees);

}  // namespace ffdkit::geometry::curvenet::detail
