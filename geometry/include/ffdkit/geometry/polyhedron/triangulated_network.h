#pragma once

#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/polyhedron/curve_network.h"
#include "ffdkit/geometry/polyhedron/mesh_topology.h"
#include "ffdkit/geometry/polyhedron/polygon_mesh.h"

namespace ffdkit::geometry::polyhedron {

/// How the leg t_{c->O} from a face corner to the face's split point is chosen (
/// Kuriyama 1996, secs. 4.2.2, 4.3.1).
enum class SplitLegRule {
  /// Kuriyama 1996, sec. 4.2.2: s_f = 1 / (2 (1 - cos(2 pi / m))), m = sides of the face. Default.
  ThesisFaceBased,
  /// Kuriyama 1996, sec. 4.3.1 alternative: s_v = 1 / (2 cos(Delta_v / 2)), which makes every star
  /// of the triangulated network regular so that the thesis G1 constants are exact (surfaces
  /// bulge).
  RegularVertexBased,
};

/// The curve network after face splitting (Kuriyama 1996, sec. 4.2.2): vertices
/// 0..V-1 are the polyhedron vertices, V + f is the split point O_f of face f; every face
/// (c_0..c_{m-1}) becomes the triangles (O_f, c_k, c_{k+1}).
struct TriangulatedNetwork {
  int originalVertexCount = 0;  ///< V, the polyhedron's vertex count
  Eigen::MatrixX3d points;          ///< (V + F) x 3
  Eigen::MatrixX3i triangles;       ///< sum_f m_f rows (O_f, c_k, c_{k+1}), counter-clockwise
  std::vector<int> triangleFace;    ///< originating polyhedron face of each triangle
  MeshTopology topology;            ///< half-edges of `triangles`
  Eigen::MatrixX3d legs;            ///< per half-edge of `topology`: t_{from -> to}
  std::vector<bool> splitPointInside;  ///< per face: O_f projects inside its polygon (sec. 4.3.4)
};

/// Splits every face, triangles included (Kuriyama 1996, sec. 4.2.2), with split legs from `rule`
/// and the split point and its frame from the closed form (S3) of eq. (4.8)-(4.10).
/// @see Kuriyama 1996, sec. 4.2.2
TriangulatedNetwork splitFaces(const PolygonMesh& mesh, const MeshTopology& topology,
                               const CurveNetworkResult& network, SplitLegRule rule = SplitLegRule::ThesisFaceBased);

}  // namespace ffdkit::geometry::polyhedron
