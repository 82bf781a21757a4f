#pragma once

#include "ffdkit/geometry/tessellation.h"

namespace ffdkit::geometry::quaternion {

/// A closed-ring tube of `sides` vertices per polyline point around an open polyline, with frames
/// carried by parallel transport (no twist from a fixed up-vector), and no end caps.
/// @return #points * sides vertices and 2 (#points - 1) sides triangles, ring k = vertices
///   [k sides, (k+1) sides), counter-clockwise seen from outside.
/// @throws QuaternionCurveError if radius <= 0, sides < 3 or fewer than 2 points.
TriangleMesh tubeMesh(const Polyline& line, double radius, int sides = 12);

}  // namespace ffdkit::geometry::quaternion
