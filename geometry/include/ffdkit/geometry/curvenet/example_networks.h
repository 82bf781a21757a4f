#pragma once

#include <string>
#include <vector>

#include "ffdkit/geometry/curvenet/curve_network.h"

namespace ffdkit::geometry::curvenet {

/// The height field of an independent prototype used for cross-checks, used to lift planar fixtures
/// into 3D: H = 0.3x^2 - 0.2xy + 0.25y^2 + 0.1x^3 + 0.05y^3 + 0.2x^2y - 0.15xy^2 + 0.1 sin 2x cos
/// 1.5y.
double prototypeHeight(double x, double y);

/// F3 (Fig. 5-4): 3 closed cubic splines through 8 points at 45 deg on the unit circles in the
/// planes z = 0, x = 0, y = 0. 6 vertices, 12 edges, 8 triangular faces.
CurveNetworkDescription sphereOctantNetwork();

/// F9 (Fig. 5-10/11): meridian circles at 0, 60, 120 deg (12 points each) and the equator
/// (12 points). Multiple points (lambda = 2) at the poles, 12 triangular faces.
CurveNetworkDescription meridianNetwork();

/// A '#'-grid of `curvesPerDirection` lines x = const and as many y = const over [0, 2]^2,
/// extended by 0.25 beyond the outer lines and lifted onto prototypeHeight; each curve
/// interpolates `pointsPerCurve` points. (n - 1)^2 quadrilateral faces.
/// @throws std::invalid_argument if curvesPerDirection < 2 or pointsPerCurve < 4.
CurveNetworkDescription heightGridNetwork(int curvesPerDirection, int pointsPerCurve = 0);

/// F11 (Fig. 5-13): the lens between y = 1 - x^2 and y = x^2 - 1 (a two-curve region) and the
/// region above it bounded by x = -0.5, x = 0.5 (T-junctions on the upper parabola) and y = 1.5,
/// lifted onto prototypeHeight.
CurveNetworkDescription lensNetwork();

/// F8 (Fig. 5-9): the quads [0, 2] x [-2, 0] and [0, 2] x [0, 2] with the stem x = 0.7 ending on
/// y = 0 from above (a T-junction), lifted onto prototypeHeight.
CurveNetworkDescription tJunctionNetwork();

/// P9: a translational network Q(u, v) = A(u) + B(v) with A(u) = (u, 0, 0.3u^2 - 0.1u^3) and
/// B(v) = (0, v, 0.2 sin 1.5v): the curves A + B(0), A + B(1.5), B + A(0), B + A(2).
CurveNetworkDescription translationalNetwork();

/// Names of the example networks above ("sphere-octants", "meridians", "height-grid",
/// "lens", "t-junction", "translational") and the network for a name.
/// @throws std::invalid_argument for an unknown name (listing the known ones).
std::vector<std::string> exampleNetworkNames();
CurveNetworkDescription exampleNetwork(const std::string& name);

}  // namespace ffdkit::geometry::curvenet
