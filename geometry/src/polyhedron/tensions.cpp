#include "ffdkit/geometry/polyhedron/tensions.h"

#include <cmath>
#include <string>

#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {
namespace {

void requireTension(double value, const std::string& where) {
  if (!std::isfinite(value) || value < 0.0) {
    throw PolyhedronError(where + ": expected a finite tension >= 0, got " + std::to_string(value));
  }
}

}  // namespace

ResolvedTensions resolveTensions(const Tensions& tensions, const MeshTopology& topology) {
  requireTension(tensions.defaultAlpha, "default vertex tension alpha");
  requireTension(tensions.defaultBeta, "default edge tension beta");
  ResolvedTensions out;
  out.alpha = Eigen::VectorXd::Constant(topology.vertexCount(), tensions.defaultAlpha);
  out.beta = Eigen::VectorXd::Constant(topology.edgeCount(), tensions.defaultBeta);
  for (const auto& [v, value] : tensions.vertexAlpha) {
    const std::string where = "tension alpha of vertex " + std::to_string(v);
    if (v < 0 || v >= topology.vertexCount()) {
      throw PolyhedronError(where + ": no such vertex (mesh has " + std::to_string(topology.vertexCount()) + ")");
    }
    requireTension(value, where);
    out.alpha[v] = value;
  }
  std::vector<bool> seen(topology.edgeCount(), false);
  for (const auto& [ends, value] : tensions.edgeBeta) {
    const std::string where =
        "tension beta of edge (" + std::to_string(ends.first) + ", " + std::to_string(ends.second) + ")";
    const int he = topology.findHalfEdge(ends.first, ends.second);
    if (he < 0) throw PolyhedronError(where + ": the mesh has no such edge");
    requireTension(value, where);
    const int e = topology.edge(he);
    if (seen[e]) throw PolyhedronError(where + ": given twice (as (a, b) and (b, a))");
    seen[e] = true;
    out.beta[e] = value;
  }
  if (!tensions.endBeta.empty()) {
    Eigen::VectorXd start = out.beta, end = out.beta;  // the ends at from(edgeHalfEdge) and to(...)
    for (const auto& [ends, value] : tensions.endBeta) {
      const std::string where =
          "end tension beta of edge (" + std::to_string(ends.first) + ", " + std::to_string(ends.second) + ") at vertex " +
          std::to_string(ends.first);
      const int he = topology.findHalfEdge(ends.first, ends.second);
      if (he < 0) throw PolyhedronError(where + ": the mesh has no such edge");
      requireTension(value, where);
      const int e = topology.edge(he);
      (topology.edgeHalfEdge(e) == he ? start : end)[e] = value;
    }
    out.beta = 0.5 * (start + end);
  }
  for (int v = 0; v < topology.vertexCount(); ++v) {
    if (out.alpha[v] > 0.0) continue;
    bool anyBeta = false;
    for (int he : topology.ringHalfEdges(v)) anyBeta = anyBeta || out.beta[topology.edge(he)] > 0.0;
    if (!anyBeta) {
      throw PolyhedronError("vertex " + std::to_string(v) +
                            ": alpha = 0 and beta = 0 on all its edges leave its frame undetermined; "
                            "expected alpha > 0 or some beta > 0");
    }
  }
  return out;
}

}  // namespace ffdkit::geometry::polyhedron
