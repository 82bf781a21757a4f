#pragma once

#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/curvenet/curve_network.h"
#include "ffdkit/geometry/curvenet/multisided_patch.h"
#include "ffdkit/geometry/curvenet/ngon_domain.h"
#include "ffdkit/geometry/tessellation.h"

namespace ffdkit::geometry::curvenet {

/// The concentric-ring lattice of a regular N-gon (Kuriyama 1996, sec. 5.3.4): 1 + N P (P + 1) / 2
/// points and N P^2 CCW triangles. Point (r, k, j), r = 1..P, j = 0..r-1, is row 1 + N r (r - 1) /
/// 2 + k r + j at (r / P) [(1 - j / r) p_k + (j / r) p_{k+1}]; row 0 is the centre; ring P is the
/// boundary.
struct NGonLattice {
  Eigen::MatrixX2d points;  ///< #points x 2 in the domain
  Eigen::MatrixX3i triangles;  ///< #triangles x 3 point indices, counter-clockwise
};
/// @throws std::invalid_argument if pitch < 1.
NGonLattice ngonLattice(const NGonDomain& domain, int pitch);

/// A tessellated network with per-vertex unit normals (for shading and zebra display).
struct NetworkMesh {
  TriangleMesh mesh;  ///< points and triangles
  Eigen::MatrixX3d normals;        ///< #V x 3, unit, outward
  std::vector<int> triangleFace;   ///< face of each triangle
};

/// Tessellates every face with its lattice of the given pitch and welds the whole network:
/// network vertices are shared by key, boundary samples by (run, sample index), so faces with
/// equal pitch share their boundary vertices bitwise (Kuriyama 1996, sec. 5.3.4, P13). Where faces
/// sample one run differently (the stem side of a T-junction, two-curve regions), the triangles of
/// the coarser side are split at the other side's boundary vertices, so the mesh has no T-vertices.
/// Boundary vertices are evaluated on the curve itself; their normals come from the patch,
/// corner normals from the network vertex (A6; at free ends and two-curve midpoints from the
/// patch just inside). The virtual side of an open region is a free boundary of its face.
/// @see Kuriyama 1996, sec. 5.3.4 (b.1-b.5).
/// @throws std::invalid_argument if pitch < 1.
NetworkMesh tessellateNetwork(const CurveNetwork& network, int pitch,
                              const PatchOptions& options = {});

}  // namespace ffdkit::geometry::curvenet
