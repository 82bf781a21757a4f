#pragma once

#include "ffdkit/geometry/curvenet/curve_network.h"
#include "ffdkit/geometry/curvenet/multisided_patch.h"
#include "ffdkit/geometry/curvenet/network_tessellation.h"
#include "ffdkit/geometry/curvenet/run_fairing.h"
#include "ffdkit/geometry/tessellation.h"

namespace ffdkit::geometry::curvenet {

/// Parameters of the scenes generator `curve-network-surface` (plain data).
struct CurveNetworkSurfaceParams {
  CurveNetworkDescription network;   ///< the curves (>= 2)
  CurveNetworkOptions networkOptions;  ///< tolerance tau (0: 1% of the diagonal), angles, hint
  PatchOptions patch;                ///< blending exponent m (default 3)
  bool fairing = false;              ///< affine-matrix sweeps with thin-plate fairing (Kuriyama 1996, sec. 5.2.1)

  /// @throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Builds the network and tessellates it with `pitch` (sampling density: each side gets pitch
/// segments). Deterministic: the same params and pitch give the same mesh.
/// @throws std::invalid_argument (params, pitch < 1), CurveInputError, CurveNetworkError.
TriangleMesh generateCurveNetworkSurface(const CurveNetworkSurfaceParams& params, int pitch);

/// The same with per-vertex normals (zebra / shading) and the face of each triangle.
NetworkMesh generateCurveNetworkSurfaceWithNormals(const CurveNetworkSurfaceParams& params,
                                                   int pitch);

}  // namespace ffdkit::geometry::curvenet
