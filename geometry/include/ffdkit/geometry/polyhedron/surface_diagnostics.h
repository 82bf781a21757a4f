#pragma once

#include "ffdkit/geometry/polyhedron/patch_surface.h"

namespace ffdkit::geometry::polyhedron {

/// Largest normal jump across the interior curves of a surface (G1 holds across them by
/// Kuriyama 1996, sec. 4.3.1).
struct NormalJumpReport {
  double maxAngle = 0.0;    ///< radians, atan2(|n1 x n2|, n1 . n2) with analytic normals
  double minCosine = 1.0;   ///< smallest n1 . n2 (> 0: no folds)
  int worstHalfEdge = -1;   ///< half-edge of triangulated().topology where maxAngle occurs
  int curvesChecked = 0;    ///< interior curves sampled
};

/// Samples every interior curve at s = k / (samples + 1), k = 1..samples, evaluates both
/// adjacent patches there and compares their unit normals. A zero normal counts as pi.
NormalJumpReport maxNormalJump(const PatchSurface& surface, int samplesPerCurve = 20);

/// Largest distance between a patch boundary and its network cubic, over every patch edge
/// sampled at `samples + 1` points, and between patch corners and network vertices
/// (properties 1 and 2). Same length unit as the mesh.
double maxBoundaryDeviation(const PatchSurface& surface, int samples = 20);

/// Largest angle (radians) between a patch's corner normal and the normal of the vertex's
/// leg plane, t_1 x t_2 of its ring (property 6).
double maxCornerNormalDeviation(const PatchSurface& surface);

/// Position on patch `patch` of the network curve from corner a to corner b at s in [0, 1].
Eigen::Vector3d evaluateOnPatchEdge(const RationalQuarticTriangle& patch, int a, int b, double s);

/// Barycentric coordinates (u, v, w) of the point at s on the patch edge from corner a to b.
Eigen::Vector3d edgeBarycentric(const RationalQuarticTriangle& patch, int a, int b, double s);

}  // namespace ffdkit::geometry::polyhedron
