#pragma once

#include <Eigen/Core>

#include "ffdkit/geometry/cardinal/s_spline_surface.h"
#include "ffdkit/geometry/cardinal/sigma_surface.h"
#include "ffdkit/geometry/tessellation.h"

namespace ffdkit::geometry::cardinal {

/// How densely a surface is sampled.
struct SurfaceSampling {
  int samplesPerSpanU = 8;  ///< sub-intervals per knot interval along u (>= 1)
  int samplesPerSpanV = 8;  ///< sub-intervals per knot interval along v (>= 1)
};

/// A tessellation with what a zebra / reflection-line display needs: unit normals
/// Q_u x Q_v / |Q_u x Q_v| at every vertex (analytic, not averaged from triangles).
struct SurfaceTessellation {
  TriangleMesh mesh;          ///< closed directions are welded (no duplicate seam vertices)
  Eigen::MatrixX3d normals;   ///< #V x 3, unit; triangles are counter-clockwise around them
  Eigen::MatrixX2d parameters;  ///< #V x 2, the (u, v) of each vertex
  int verticesU = 0;  ///< vertex grid size along u (vertex index = iu * verticesV + iv)
  int verticesV = 0;  ///< vertex grid size along v
};

/// @throws CardinalSplineError if a sampling count is < 1.
SurfaceTessellation tessellate(const SigmaSurface& surface, const SurfaceSampling& sampling = {});
SurfaceTessellation tessellate(const SSplineSurface& surface, const SurfaceSampling& sampling = {});

}  // namespace ffdkit::geometry::cardinal
