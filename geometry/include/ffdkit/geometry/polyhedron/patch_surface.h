#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/polyhedron/curve_network.h"
#include "ffdkit/geometry/polyhedron/polygon_mesh.h"
#include "ffdkit/geometry/polyhedron/rational_quartic_triangle.h"
#include "ffdkit/geometry/polyhedron/tensions.h"
#include "ffdkit/geometry/polyhedron/triangulated_network.h"

namespace ffdkit::geometry::polyhedron {

/// Where the G1 weight omega and end scalars kappa of each curve come from (Kuriyama 1996,
/// sec. 4.3.1).
enum class G1Scalars {
  /// Per half-edge from the actual legs: omega t_{i+1} + (1 - omega) t_{i-1} = (4/3) kappa t_i
  /// (least squares, exact since the legs are coplanar). G1 with any split-leg rule. Default.
  PerEdge,
  /// The thesis constants omega = 1/2, kappa = (3/4) cos(2 pi / N) (sec. 4.3.1). G1 only with
  /// SplitLegRule::RegularVertexBased; with the face-based rule the normals jump (measured by
  /// tests/geometry/polyhedron).
  ThesisConstants,
};

/// Options of PatchSurface::build.
struct PatchSurfaceOptions {
  SplitLegRule splitRule = SplitLegRule::ThesisFaceBased;  ///< the thesis rule (sec. 4.2.2)
  G1Scalars g1Scalars = G1Scalars::PerEdge;               ///< default
  CurveNetworkOptions network;                            ///< frame overrides, solver tolerances
  /// Largest accepted least-squares residual of the per-edge omega/kappa fit, relative to |t_i|.
  double legFitTolerance = 1e-9;
};

/// G1 scalars of one half-edge P -> P' of the triangulated network (Kuriyama 1996, sec. 4.3.1).
struct EdgeG1Scalars {
  double omega = 0.5;  ///< weight of the patch face(he) in (4.13)-(4.16); the twin has 1 - omega
  double kappa = 0.0;  ///< end scalar kappa_{P,e} (thesis 1 - beta at P, gamma at P')
};

/// Polyhedron -> G1 surface of rational quartic triangular patches (Kuriyama 1996, ch. 4,
/// secs. 4, 4.4): curve network (sec. 4.2.1), face splitting (sec. 4.2.2), boundary control points
/// and per-edge G1 scalars (sec. 4.3.1) and the ring solves of the sub-points (secs. 4.3.1-4.3.2).
/// One patch per triangle of triangulated().triangles, in the same order.
class PatchSurface {
 public:
  /// Builds the surface. Polyhedron: #V x 3 vertices, faces counter-clockwise from outside.
  /// @throws PolyhedronError for invalid meshes (validatePolygonMesh), invalid tensions
  ///   (resolveTensions), an unsolvable network or collapsed frame, or a G1 fit that fails its
  ///   checks; never returns a surface with NaN.
  static PatchSurface build(const PolygonMesh& mesh, const Tensions& tensions = {},
                            const PatchSurfaceOptions& options = {});

  /// The polyhedron the surface was built from.
  const PolygonMesh& mesh() const { return mesh_; }
  /// Its half-edge topology.
  const MeshTopology& topology() const { return topology_; }
  /// The tensions, resolved per edge.
  const ResolvedTensions& tensions() const { return tensions_; }
  /// The solved curve network.
  const CurveNetworkResult& network() const { return network_; }
  /// The network after face splitting.
  const TriangulatedNetwork& triangulated() const { return triangulated_; }
  /// The triangular patches, one per triangle of triangulated().
  const std::vector<RationalQuarticTriangle>& patches() const { return patches_; }
  /// Per half-edge of triangulated().topology.
  const std::vector<EdgeG1Scalars>& g1Scalars() const { return g1_; }
  /// Cubic Bezier control points V0..V3 of the network curve from vertex a to vertex b
  /// (triangulated-network ids). @throws PolyhedronError if a, b are not joined.
  std::array<Eigen::Vector3d, 4> curve(int a, int b) const;
  /// Human-readable notes, e.g. split points outside a concave face (sec. 4.3.4).
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  PolygonMesh mesh_;
  MeshTopology topology_;
  ResolvedTensions tensions_;
  CurveNetworkResult network_;
  TriangulatedNetwork triangulated_;
  std::vector<RationalQuarticTriangle> patches_;
  std::vector<EdgeG1Scalars> g1_;
  std::vector<std::string> warnings_;
};

}  // namespace ffdkit::geometry::polyhedron
