#include "ffdkit/geometry/polyhedron/triangulated_network.h"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "ffdkit/geometry/polyhedron/builtin_meshes.h"

namespace ffdkit::geometry::polyhedron {
namespace {

TriangulatedNetwork split(const PolygonMesh& mesh, SplitLegRule rule = SplitLegRule::ThesisFaceBased) {
  const MeshTopology topology = validatePolygonMesh(mesh);
  const ResolvedTensions tensions = resolveTensions({}, topology);
  return splitFaces(mesh, topology, solveCurveNetwork(mesh, topology, tensions), rule);
}

TEST(TriangulatedNetwork, TetrahedronSplitPointsAndLegsMatchReference) {
  const PolygonMesh mesh = tetrahedronMesh();
  const TriangulatedNetwork net = split(mesh);
  ASSERT_EQ(net.points.rows(), 8);
  EXPECT_EQ(net.triangles.rows(), 12);
  for (int f = 0; f < 4; ++f) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int c : mesh.faces[f]) centroid += mesh.vertices.row(c).transpose() / 3.0;
    EXPECT_LE((net.points.row(4 + f).transpose() - 1.8 * centroid).norm(), 1e-12);
  }
  bool foundReference = false;
  for (int f = 4; f < 8; ++f) foundReference = foundReference || (net.points.row(f).transpose() - Eigen::Vector3d(0.6, 0.6, -0.6)).norm() < 1e-12;
  EXPECT_TRUE(foundReference);
  for (int he = 0; he < net.topology.halfEdgeCount(); ++he) {
    const bool toSplit = net.topology.to(he) >= 4, fromSplit = net.topology.from(he) >= 4;
    if (toSplit) {
      EXPECT_NEAR(net.legs.row(he).norm(), 0.326599, 1e-6);
    }
    if (fromSplit) {
      EXPECT_NEAR(net.legs.row(he).norm(), 0.762063, 1e-6);
    }
  }
}

TEST(TriangulatedNetwork, CubeSplitPointAndLegsMatchReference) {
  const TriangulatedNetwork net = split(cubeMesh());
  bool bottom = false;
  for (int f = 8; f < 14; ++f) bottom = bottom || (net.points.row(f).transpose() - Eigen::Vector3d(0, 0, -10.0 / 7.0)).norm() < 1e-12;
  EXPECT_TRUE(bottom);
  for (int he = 0; he < net.topology.halfEdgeCount(); ++he) {
    if (net.topology.to(he) >= 8) {
      EXPECT_NEAR(net.legs.row(he).norm(), 0.349927, 1e-6);
    }
    if (net.topology.from(he) >= 8) {
      EXPECT_NEAR(net.legs.row(he).norm(), 0.606092, 1e-6);
    }
  }
}

TEST(TriangulatedNetwork, OctahedronSplitPointsScaleTheCentroids) {
  const TriangulatedNetwork net = split(octahedronMesh());
  for (int f = 6; f < 14; ++f) EXPECT_NEAR(net.points.row(f).norm(), 1.5 * std::sqrt(1.0 / 3.0), 1e-12);
}

TEST(TriangulatedNetwork, ValencesAlternateOriginalAndSplitEdges) {
  const TriangulatedNetwork closed = split(hexagonalPrismMesh());
  for (int v = 0; v < 12; ++v) EXPECT_EQ(closed.topology.valence(v), 6);
  EXPECT_EQ(closed.topology.valence(12 + 7), 6);  // top hexagon split point
  const TriangulatedNetwork open = split(openHexagonalPrismMesh());
  for (int v = 6; v < 12; ++v) {
    EXPECT_EQ(open.topology.valence(v), 5);
    const auto& ring = open.topology.ringHalfEdges(v);
    for (std::size_t i = 0; i < ring.size(); ++i) EXPECT_EQ(open.topology.to(ring[i]) >= 12, i % 2 == 1);
  }
}

TEST(TriangulatedNetwork, LegsAtEveryNetworkVertexAreCoplanar) {
  for (SplitLegRule rule : {SplitLegRule::ThesisFaceBased, SplitLegRule::RegularVertexBased}) {
    const TriangulatedNetwork net = split(torusMesh(8, 5), rule);
    for (int v = 0; v < net.topology.vertexCount(); ++v) {
      const auto& ring = net.topology.ringHalfEdges(v);
      const Eigen::Vector3d n = net.legs.row(ring[0]).cross(net.legs.row(ring[1])).normalized().transpose();
      for (int he : ring) EXPECT_LE(std::abs(n.dot(net.legs.row(he).transpose())), 1e-12 * net.legs.row(he).norm());
    }
  }
}

}  // namespace
}  // namespace ffdkit::geometry::polyhedron
