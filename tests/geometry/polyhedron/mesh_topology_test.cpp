#include "ffdkit/geometry/polyhedron/mesh_topology.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "ffdkit/geometry/polyhedron/builtin_meshes.h"
#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {
namespace {

std::string buildError(const std::vector<std::vector<int>>& faces, int vertices) {
  try {
    MeshTopology::build(faces, vertices);
  } catch (const PolyhedronError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshTopology, ClosedCubeHasTwinnedHalfEdgesAndCounterClockwiseRings) {
  const PolygonMesh cube = cubeMesh();
  const MeshTopology t = MeshTopology::build(cube.faces, 8);
  EXPECT_EQ(t.halfEdgeCount(), 24);
  EXPECT_EQ(t.edgeCount(), 12);
  for (int he = 0; he < t.halfEdgeCount(); ++he) {
    EXPECT_EQ(t.twin(t.twin(he)), he);
    EXPECT_GE(t.face(he), 0);
    EXPECT_EQ(t.from(t.twin(he)), t.to(he));
  }
  for (int v = 0; v < 8; ++v) {
    EXPECT_FALSE(t.isBoundaryVertex(v));
    ASSERT_EQ(t.valence(v), 3);
    const auto& ring = t.ringHalfEdges(v);
    const Eigen::Vector3d p = cube.vertices.row(v).transpose();
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(t.ringIndex(ring[i]), i);
      // Counter-clockwise seen from outside: consecutive legs turn about the outward normal p.
      const Eigen::Vector3d a = cube.vertices.row(t.to(ring[i])).transpose() - p;
      const Eigen::Vector3d b = cube.vertices.row(t.to(ring[(i + 1) % 3])).transpose() - p;
      EXPECT_GT(a.cross(b).dot(p), 0.0);
      // Face Q_i lies between e_i and e_{i+1}: it contains both neighbours.
      const auto& face = t.faceVertices(t.face(ring[i]));
      EXPECT_NE(std::find(face.begin(), face.end(), t.to(ring[(i + 1) % 3])), face.end());
    }
  }
}

TEST(MeshTopology, OpenMeshRingsStartAndEndAtBoundaryEdges) {
  const PolygonMesh open = openHexagonalPrismMesh();
  const MeshTopology t = MeshTopology::build(open.faces, 12);
  for (int v = 6; v < 12; ++v) {
    ASSERT_TRUE(t.isBoundaryVertex(v));
    const auto& ring = t.ringHalfEdges(v);
    ASSERT_EQ(ring.size(), 3u);
    EXPECT_GE(t.face(ring.front()), 0);
    EXPECT_LT(t.face(t.twin(ring.front())), 0);
    EXPECT_LT(t.face(ring.back()), 0);
    EXPECT_TRUE(t.isBoundaryEdge(t.edge(ring.front())));
  }
  for (int v = 0; v < 6; ++v) EXPECT_FALSE(t.isBoundaryVertex(v));
  EXPECT_EQ(t.findHalfEdge(0, 11), -1);
}

TEST(MeshTopology, RejectsNonManifoldEdge) {
  const std::string message = buildError({{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}, 5);
  EXPECT_NE(message.find("non-manifold edge (0, 1)"), std::string::npos) << message;
}

TEST(MeshTopology, RejectsInconsistentOrientation) {
  const std::string message = buildError({{0, 1, 2}, {0, 1, 3}}, 4);
  EXPECT_NE(message.find("inconsistent orientation"), std::string::npos) << message;
}

TEST(MeshTopology, RejectsBowTieVertex) {
  const std::string message = buildError({{0, 1, 2}, {0, 3, 4}}, 5);
  EXPECT_NE(message.find("non-manifold vertex 0"), std::string::npos) << message;
}

TEST(MeshTopology, RejectsBadIndicesShortFacesRepeatedCornersAndIsolatedVertices) {
  EXPECT_NE(buildError({{0, 1, 5}}, 3).find("outside [0, 3)"), std::string::npos);
  EXPECT_NE(buildError({{0, 1}}, 2).find(">= 3 corners"), std::string::npos);
  EXPECT_NE(buildError({{0, 1, 1}}, 2).find("appears twice"), std::string::npos);
  EXPECT_NE(buildError({{0, 1, 2}}, 4).find("vertex 3 is used by no face"), std::string::npos);
}

}  // namespace
}  // namespace ffdkit::geometry::polyhedron
