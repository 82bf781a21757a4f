#include "ffdkit/geometry/polyhedron/polygon_mesh.h"

#include <string>

#include <Eigen/Geometry>

#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {

double boundingBoxDiagonal(const Eigen::MatrixX3d& points) {
  if (points.rows() == 0) return 0.0;
  return (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
}

MeshTopology validatePolygonMesh(const PolygonMesh& mesh, double relativeTolerance) {
  const int n = static_cast<int>(mesh.vertices.rows());
  for (int v = 0; v < n; ++v) {
    if (!mesh.vertices.row(v).allFinite()) {
      throw PolyhedronError("vertex " + std::to_string(v) + ": expected finite coordinates");
    }
  }
  MeshTopology topology = MeshTopology::build(mesh.faces, n);
  const double diagonal = boundingBoxDiagonal(mesh.vertices);
  if (!(diagonal > 0.0)) throw PolyhedronError("polyhedron: all vertices coincide (bounding-box diagonal 0)");
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& c = mesh.faces[f];
    Eigen::Vector3d area = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < c.size(); ++k) {
      const Eigen::Vector3d a = mesh.vertices.row(c[k]);
      const Eigen::Vector3d b = mesh.vertices.row(c[(k + 1) % c.size()]);
      if ((b - a).norm() <= relativeTolerance * diagonal) {
        throw PolyhedronError("degenerate face " + std::to_string(f) + ": vertices " + std::to_string(c[k]) + " and " +
                              std::to_string(c[(k + 1) % c.size()]) + " coincide");
      }
      area += a.cross(b);
    }
    if (0.5 * area.norm() <= relativeTolerance * diagonal * diagonal) {
      throw PolyhedronError("degenerate face " + std::to_string(f) + ": expected a non-zero vector area, got " +
                            std::to_string(0.5 * area.norm()) + " (collinear corners?)");
    }
  }
  for (int v = 0; v < n; ++v) {
    if (topology.valence(v) < 3) {
      throw PolyhedronError("vertex " + std::to_string(v) + " has valence " + std::to_string(topology.valence(v)) +
                            (topology.isBoundaryVertex(v) ? " on the boundary" : "") +
                            "; expected >= 3 (a valence-2 vertex leaves its tangent frame undetermined: "
                            "remove it or merge it into its edge)");
    }
  }
  return topology;
}

}  // namespace ffdkit::geometry::polyhedron
