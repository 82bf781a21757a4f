#pragma once

#include <map>
#include <utility>

#include <Eigen/Core>

#include "ffdkit/geometry/polyhedron/mesh_topology.h"

namespace ffdkit::geometry::polyhedron {

/// Shape tensions of the curve network, in the thesis scaling of functional S1 (
/// Kuriyama 1996 eq. (4.3)-(4.4), sec. 4.2.1; Kuriyama 1996, sec. 4.2.1): a vertex tension alpha_v >= 0 shortens
/// every tangent leg at v (the surface tightens and becomes pointed there, sec. 4.3.4); an edge
/// tension beta_e >= 0 straightens the cubic along e. alpha = 0, beta = 1 everywhere is Nielson's
/// minimum-norm network (sec. 4.2.1).
struct Tensions {
  double defaultAlpha = 0.0;                      ///< alpha_v of vertices not in vertexAlpha
  double defaultBeta = 1.0;                       ///< beta_e of edges not in edgeBeta
  std::map<int, double> vertexAlpha;              ///< vertex index -> alpha_v
  std::map<std::pair<int, int>, double> edgeBeta;  ///< (a, b) in either order -> beta_e
  /// Thesis per-end tensions beta^v_i (sec. 4.2.1): (v, w) -> the tension of edge {v, w} at v's
  /// end. The edge gets the mean of its two ends, the exact minimiser of (4.3) (Kuriyama 1996,
  /// sec. 4.2.1); an end not listed keeps the edge's value from edgeBeta / defaultBeta.
  std::map<std::pair<int, int>, double> endBeta;
};

/// Tensions resolved to one value per vertex and per undirected edge of a topology.
struct ResolvedTensions {
  Eigen::VectorXd alpha;  ///< #V, alpha_v
  Eigen::VectorXd beta;   ///< #E, beta_e indexed by MeshTopology::edge()
};

/// Resolves defaults and overrides.
/// @throws PolyhedronError for a negative or non-finite tension, an override naming a vertex
///   or an edge the mesh does not have, an edge given twice in edgeBeta (as (a,b) and (b,a)), or a vertex
///   where alpha_v = 0 and every beta of its edges is 0 (the network system would be singular).
ResolvedTensions resolveTensions(const Tensions& tensions, const MeshTopology& topology);

}  // namespace ffdkit::geometry::polyhedron
