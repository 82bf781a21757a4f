#include "ffdkit/geometry/polyhedron/triangulated_network.h"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {
namespace {

// Winding test of `point` against the polygon projected on its Newell plane.
bool projectsInside(const std::vector<Eigen::Vector3d>& polygon, const Eigen::Vector3d& point) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < polygon.size(); ++k) normal += polygon[k].cross(polygon[(k + 1) % polygon.size()]);
  const Eigen::Vector3d unit = normal.normalized();
  auto inPlane = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d { return x - x.dot(unit) * unit; };
  double angle = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector3d a = inPlane(polygon[k] - point), b = inPlane(polygon[(k + 1) % polygon.size()] - point);
    angle += std::atan2(a.cross(b).dot(unit), a.dot(b));
  }
  return std::abs(angle) > std::numbers::pi;
}

}  // namespace

TriangulatedNetwork splitFaces(const PolygonMesh& mesh, const MeshTopology& topology,
                               const CurveNetworkResult& network, SplitLegRule rule) {
  if (!network.converged) throw PolyhedronError("face splitting: the curve network did not converge: " + network.message);
  const int v0 = topology.vertexCount();
  const int faces = topology.faceCount();
  TriangulatedNetwork out;
  out.originalVertexCount = v0;
  out.points.resize(v0 + faces, 3);
  out.points.topRows(v0) = mesh.vertices;
  out.splitPointInside.assign(faces, true);

  int triangleCount = 0;
  for (int f = 0; f < faces; ++f) triangleCount += static_cast<int>(topology.faceVertices(f).size());
  out.triangles.resize(triangleCount, 3);
  out.triangleFace.resize(triangleCount);
  std::vector<std::vector<int>> triangleLists;
  triangleLists.reserve(triangleCount);
  // Legs of split edges, keyed by (corner, split point) in both directions.
  std::vector<Eigen::Vector3d> cornerToSplit(triangleCount), splitToCorner(triangleCount);
  int t = 0;
  for (int f = 0; f < faces; ++f) {
    const auto& c = topology.faceVertices(f);
    const int m = static_cast<int>(c.size());
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), legSum = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> toSplit(m), polygon(m);
    for (int k = 0; k < m; ++k) {
      const int next = c[(k + 1) % m], prev = c[(k + m - 1) % m];
      const int heNext = topology.findHalfEdge(c[k], next), hePrev = topology.findHalfEdge(c[k], prev);
      double s = 0.0;
      if (rule == SplitLegRule::ThesisFaceBased) {
        s = 1.0 / (2.0 * (1.0 - std::cos(2.0 * std::numbers::pi / m)));  // sec. 4.2.2, n = sides (Kuriyama 1996, sec. 4.2.2)
      } else {
        const int n = topology.valence(c[k]);
        const double delta = topology.isBoundaryVertex(c[k]) ? std::numbers::pi / (n - 1) : 2.0 * std::numbers::pi / n;
        s = 1.0 / (2.0 * std::cos(0.5 * delta));
      }
      toSplit[k] = s * (network.legs.row(heNext) + network.legs.row(hePrev)).transpose();
      polygon[k] = mesh.vertices.row(c[k]).transpose();
      centroid += polygon[k];
      legSum += toSplit[k];
    }
    // Closed form (S3) of eq. (4.8)-(4.10): the 3x3 system is diagonal for m >= 3.
    const Eigen::Vector3d o = centroid / m + 1.5 / m * legSum;
    Eigen::Vector3d ys = Eigen::Vector3d::Zero(), yc = Eigen::Vector3d::Zero();
    for (int k = 0; k < m; ++k) {
      const double phi = 2.0 * std::numbers::pi * k / m;
      const Eigen::Vector3d q = polygon[k] + toSplit[k];
      ys += std::sin(phi) * q / m;
      yc += std::cos(phi) * q / m;
    }
    out.points.row(v0 + f) = o.transpose();
    out.splitPointInside[f] = projectsInside(polygon, o);
    for (int k = 0; k < m; ++k) {
      const double phi = 2.0 * std::numbers::pi * k / m;
      out.triangles.row(t) << v0 + f, c[k], c[(k + 1) % m];
      triangleLists.push_back({v0 + f, c[k], c[(k + 1) % m]});
      out.triangleFace[t] = f;
      cornerToSplit[t] = toSplit[k];
      splitToCorner[t] = ys * std::sin(phi) + yc * std::cos(phi);
      ++t;
    }
  }
  out.topology = MeshTopology::build(triangleLists, v0 + faces);
  out.legs.resize(out.topology.halfEdgeCount(), 3);
  for (int he = 0; he < out.topology.halfEdgeCount(); ++he) {
    const int a = out.topology.from(he), b = out.topology.to(he);
    if (a < v0 && b < v0) out.legs.row(he) = network.legs.row(topology.findHalfEdge(a, b));
  }
  for (int tri = 0; tri < triangleCount; ++tri) {
    const int o = out.triangles(tri, 0), c = out.triangles(tri, 1);
    out.legs.row(out.topology.findHalfEdge(c, o)) = cornerToSplit[tri].transpose();
    out.legs.row(out.topology.findHalfEdge(o, c)) = splitToCorner[tri].transpose();
  }
  return out;
}

}  // namespace ffdkit::geometry::polyhedron
