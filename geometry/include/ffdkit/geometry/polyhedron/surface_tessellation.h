#pragma once

#include <Eigen/Core>

#include "ffdkit/geometry/polyhedron/patch_surface.h"
#include "ffdkit/geometry/tessellation.h"

namespace ffdkit::geometry::polyhedron {

/// A welded triangle mesh of a patch surface with per-vertex normals (for shading and the
/// zebra display).
struct TessellatedSurface {
  TriangleMesh mesh;           ///< crack-free: vertices on shared curves exist once
  Eigen::MatrixX3d normals;    ///< #V x 3 unit normals (mean of the adjacent patches' analytic normals)
  Eigen::VectorXi trianglePatch;  ///< #triangles: index of the patch each triangle samples
};

/// Samples every patch on the barycentric grid (i, j, k) / n, i + j + k = n, and welds the
/// samples shared by patches: network vertices by id, curve samples by (curve, step). Each
/// patch gives n^2 triangles, counter-clockwise like the patch. Normals: mean of the unit
/// analytic normals of the patches sharing the vertex; where those vanish (a cusp from a huge
/// vertex tension), the area-weighted normal of the tessellation instead; never NaN.
/// @param samplesPerPatchSide  n >= 1
/// @throws PolyhedronError if n < 1.
TessellatedSurface tessellate(const PatchSurface& surface, int samplesPerPatchSide);

}  // namespace ffdkit::geometry::polyhedron
