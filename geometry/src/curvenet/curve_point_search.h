#pragma once
// Private to curvenet: closest points on and between network curves, projections, end tests
// (the numerics of buildCurveNetwork's intersection, vertex and normal stages, Kuriyama 1996,
// secs. 5.3.3-5.3.4).

#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/curvenet/network_curve.h"

namespace ffdkit::geometry::curvenet::detail {

// t itself on a closed curve, else clamped to the curve's domain.
double clampParameter(const NetworkCurve& c, double t);

// Newton on f(s, t) = 1/2 |A(s) - B(t)|^2 from a sampled start; open curves are clamped to
// their domain so that a free end near a curve is found as a T candidate (Kuriyama 1996,
// sec. 5.3.3).
void refineClosestPoints(const NetworkCurve& ca, const NetworkCurve& cb, double& s, double& t);

// Moves t to an end of an open curve whose point lies within tau of c(t); true if it did.
bool snapToEnd(const NetworkCurve& c, double& t, double tau);

// Closest point of curve c to the fixed point x, by Newton from t.
void refineOnOneCurve(const Eigen::Vector3d& x, const NetworkCurve& c, double& t);

// The point nearest to x on all the given planes (least squares, minimum-norm correction).
Eigen::Vector3d projectOntoPlanes(const Eigen::Vector3d& x, const std::vector<Plane>& planes);

// True when t is an end of an open curve (within 1e-9 of its period).
bool endsAt(const NetworkCurve& c, double t);

// t with its component along the unit normal n removed, normalised (zero stays zero).
Eigen::Vector3d projectedUnit(const Eigen::Vector3d& t, const Eigen::Vector3d& n);

}  // namespace ffdkit::geometry::curvenet::detail
