#pragma once

#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "ffdkit/geometry/polyhedron/mesh_topology.h"
#include "ffdkit/geometry/polyhedron/polygon_mesh.h"
#include "ffdkit/geometry/polyhedron/tensions.h"

namespace ffdkit::geometry::polyhedron {

/// Tangent-plane frame (T^s_v, T^c_v) of a vertex: its legs are
/// t_{v->w_i} = T^s sin(theta_i) + T^c cos(theta_i) (Kuriyama 1996, sec. 4.2.1, eq. (4.2)).
struct Frame {
  Eigen::Vector3d ts = Eigen::Vector3d::Zero();  ///< T^s_v
  Eigen::Vector3d tc = Eigen::Vector3d::Zero();  ///< T^c_v
};

/// Ring angle theta of outgoing half-edge `he` at its vertex: 2 pi i / n at closed vertices,
/// pi i / (n - 1) at boundary vertices (0-based ring index i, valence n; sec. 4.2.1).
double ringAngle(const MeshTopology& topology, int he);

/// The sparse symmetric normal equations K X = F of functional S1 (eq. (4.7), sec. 4.2.1;
/// written here in matrix form). Row 2v holds T^s_v, row 2v+1 holds T^c_v; F has one column per
/// coordinate (x, y, z).
struct NetworkSystem {
  Eigen::SparseMatrix<double> stiffness;  ///< K, 2V x 2V, symmetric positive (semi)definite
  Eigen::MatrixX3d load;                  ///< F, 2V x 3
};

/// Assembles K and F. @see Kuriyama 1996, sec. 4.2.1, eq. (4.5)-(4.7)
NetworkSystem assembleNetworkSystem(const PolygonMesh& mesh, const MeshTopology& topology,
                                    const ResolvedTensions& tensions);

/// Options of the curve-network solve.
struct CurveNetworkOptions {
  /// Vertices whose frame is fixed by the designer instead of solved (Kuriyama 1996, sec. 4.3.2):
  /// with all frames fixed, moving a vertex only changes nearby patches.
  std::map<int, Frame> frameOverrides;
  /// A frame counts as collapsed when |T^s x T^c| <= this * |T^s| |T^c|.
  double degenerateFrameTolerance = 1e-10;
  /// Largest accepted relative residual ||K X - F|| / ||F||.
  double residualTolerance = 1e-10;
};

/// The tension-controlled cubic curve network along the polyhedron edges (Kuriyama 1996,
/// sec. 4.2.1).
struct CurveNetworkResult {
  bool converged = false;        ///< false: `message` says why (singular system, collapsed frame)
  double relativeResidual = 0.0;  ///< ||K X - F|| / max(||F||, tiny)
  int iterations = 0;            ///< 1: the solve is direct (Eigen::SimplicialLDLT)
  std::string message;  ///< why it failed, empty on success
  std::vector<Frame> frames;     ///< #V
  Eigen::MatrixX3d legs;         ///< #halfEdges x 3: t_{from -> to} per half-edge (Bezier offset)
};

/// Solves the network: minimises S1 over all frames with one sparse LDL^T factorisation and
/// three right-hand sides. Unsolvable inputs come back with converged = false, never as NaN.
/// @see Kuriyama 1996, sec. 4.2.1, eq. (4.1)-(4.7)
CurveNetworkResult solveCurveNetwork(const PolygonMesh& mesh, const MeshTopology& topology,
                                     const ResolvedTensions& tensions, const CurveNetworkOptions& options = {});

/// Legs t_{v->w} of every half-edge from the frames (eq. (4.2)).
Eigen::MatrixX3d legsFromFrames(const MeshTopology& topology, const std::vector<Frame>& frames);

/// Value of functional S1 (thesis scaling, Kuriyama 1996, sec. 4.2.1): sum over edges of
/// beta_e (|A|^2 + A.B + |B|^2) / 3 plus sum over half-edges of alpha_v |t_{v->w}|^2.
double pseudoNorm(const PolygonMesh& mesh, const MeshTopology& topology, const ResolvedTensions& tensions,
                  const Eigen::MatrixX3d& legs);

/// The edge term (|A|^2 + A.B + |B|^2) / 3 of S1 for undirected edge `edge` (Kuriyama 1996,
/// sec. 4.2.1).
double edgePseudoNorm(const PolygonMesh& mesh, const MeshTopology& topology, const Eigen::MatrixX3d& legs, int edge);

}  // namespace ffdkit::geometry::polyhedron
