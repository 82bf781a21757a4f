#include "ffdkit/geometry/curvenet/network_tessellation.h"

#include <cmath>
#include <numbers>
#include <functional>
#include <map>
#include <utility>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "ffdkit/geometry/curvenet/example_networks.h"

namespace ffdkit::geometry::curvenet {
namespace {

// Directed edge -> count; a crack-free, consistently oriented mesh uses every interior edge
// once in each direction.
std::map<std::pair<int, int>, int> directedEdges(const TriangleMesh& m) {
  std::map<std::pair<int, int>, int> edges;
  for (int t = 0; t < m.triangles.rows(); ++t) {
    for (int e = 0; e < 3; ++e) ++edges[{m.triangles(t, e), m.triangles(t, (e + 1) % 3)}];
  }
  return edges;
}

TEST(NetworkTessellation, LatticeHasSpecCountsAndCoversTheNGonCounterClockwise) {  // P13
  for (int n = 3; n <= 6; ++n) {
    const NGonDomain d(n);
    const double polygonArea = 0.5 * n * std::sin(2 * std::numbers::pi / n);
    for (int pitch = 1; pitch <= 5; ++pitch) {
      const NGonLattice l = ngonLattice(d, pitch);
      EXPECT_EQ(l.points.rows(), 1 + n * pitch * (pitch + 1) / 2);
      EXPECT_EQ(l.triangles.rows(), n * pitch * pitch);
      double area = 0.0;
      for (int t = 0; t < l.triangles.rows(); ++t) {
        const Eigen::Vector2d a = l.points.row(l.triangles(t, 0)), b = l.points.row(l.triangles(t, 1)),
                              c = l.points.row(l.triangles(t, 2));
        const double signedArea = 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
        EXPECT_GT(signedArea, 0.0);
        area += signedArea;
      }
      EXPECT_NEAR(area, polygonArea, 1e-12);
    }
  }
  EXPECT_THROW(ngonLattice(NGonDomain(3), 0), std::invalid_argument);
}

TEST(NetworkTessellation, SphereOctantsGiveAWeldedClosedMeshWithExactCounts) {  // F3, P13, F14
  const CurveNetwork net = buildCurveNetwork(sphereOctantNetwork());
  for (int pitch : {1, 3, 6}) {
    const NetworkMesh m = tessellateNetwork(net, pitch);
    const int interior = 1 + 3 * pitch * (pitch - 1) / 2;
    EXPECT_EQ(m.mesh.vertices.rows(), 6 + 12 * (pitch - 1) + 8 * interior);
    EXPECT_EQ(m.mesh.triangles.rows(), 8 * 3 * pitch * pitch);
    const auto edges = directedEdges(m.mesh);
    for (const auto& [e, count] : edges) {
      EXPECT_EQ(count, 1);
      EXPECT_EQ(edges.count({e.second, e.first}), 1u) << "crack or flipped triangle at edge " << e.first << "-" << e.second;
    }
    for (int v = 0; v < m.mesh.vertices.rows(); ++v) {
      EXPECT_GT(m.normals.row(v).dot(m.mesh.vertices.row(v)), 0.9) << "outward unit normals";
      EXPECT_NEAR(m.normals.row(v).norm(), 1.0, 1e-12);
    }
    for (int t = 0; t < m.mesh.triangles.rows(); ++t) {
      const Eigen::Vector3d a = m.mesh.vertices.row(m.mesh.triangles(t, 0)), b = m.mesh.vertices.row(m.mesh.triangles(t, 1)),
                            c = m.mesh.vertices.row(m.mesh.triangles(t, 2));
      EXPECT_GT((b - a).cross(c - a).dot(a + b + c), 0.0) << "CCW seen from outside";
    }
  }
}

// No cracks: every edge used by one triangle lies on the outer boundary of the sheet.
void expectCrackFree(const NetworkMesh& m, const std::function<bool(const Eigen::Vector3d&)>& onOuterBoundary) {
  const auto edges = directedEdges(m.mesh);
  int boundary = 0;
  for (const auto& [e, count] : edges) {
    EXPECT_EQ(count, 1);
    if (edges.count({e.second, e.first})) continue;
    ++boundary;
    EXPECT_TRUE(onOuterBoundary(m.mesh.vertices.row(e.first)) && onOuterBoundary(m.mesh.vertices.row(e.second)))
        << "crack at " << m.mesh.vertices.row(e.first) << " - " << m.mesh.vertices.row(e.second);
  }
  EXPECT_GT(boundary, 0);
}

TEST(NetworkTessellation, TJunctionMeshIsStitchedWithoutCracks) {  // F8, Kuriyama 1996, sec. 5.3.4, zipper
  const CurveNetwork net = buildCurveNetwork(tJunctionNetwork());
  const NetworkMesh m = tessellateNetwork(net, 5);
  expectCrackFree(m, [](const Eigen::Vector3d& p) {
    return std::abs(p.x()) < 1e-9 || std::abs(p.x() - 2) < 1e-9 || std::abs(std::abs(p.y()) - 2) < 1e-9;
  });
}

TEST(NetworkTessellation, HeightGridCountsAndWelding) {  // P13 on an open sheet
  const CurveNetwork net = buildCurveNetwork(heightGridNetwork(4));
  const int pitch = 4;
  const NetworkMesh m = tessellateNetwork(net, pitch);
  // 3 x 3 quads: 16 corners, 24 edges with pitch - 1 inner samples, 9 interiors.
  EXPECT_EQ(m.mesh.vertices.rows(), 16 + 24 * (pitch - 1) + 9 * (1 + 4 * pitch * (pitch - 1) / 2));
  EXPECT_EQ(m.mesh.triangles.rows(), 9 * 4 * pitch * pitch);
  expectCrackFree(m, [](const Eigen::Vector3d& p) {
    return std::abs(p.x()) < 1e-9 || std::abs(p.x() - 2) < 1e-9 || std::abs(p.y()) < 1e-9 || std::abs(p.y() - 2) < 1e-9;
  });
  // Welding leaves no duplicate positions.
  for (int a = 0; a < m.mesh.vertices.rows(); ++a) {
    for (int b = a + 1; b < m.mesh.vertices.rows(); ++b) {
      EXPECT_GT((m.mesh.vertices.row(a) - m.mesh.vertices.row(b)).norm(), 1e-9);
    }
  }
}

TEST(NetworkTessellation, FilledOpenRegionsExtendTheSheetWithoutCracks) {  // rule (c)
  CurveNetworkOptions fill;
  fill.fillOpenRegions = true;
  const CurveNetwork net = buildCurveNetwork(heightGridNetwork(4), fill);
  int open = 0;
  for (const Face& f : net.faces) open += f.openRegion ? 1 : 0;
  EXPECT_EQ(open, 16) << "4 corner regions, 12 regions along the sides";
  EXPECT_TRUE(net.openChains.empty());
  const NetworkMesh m = tessellateNetwork(net, 4);
  EXPECT_TRUE(m.mesh.vertices.allFinite());
  EXPECT_TRUE(m.normals.allFinite());
  const auto edges = directedEdges(m.mesh);
  for (const auto& [e, count] : edges) EXPECT_EQ(count, 1);
  // The sheet's border is now made of the virtual sides only: its vertices lie outside the
  // square [0, 2]^2 spanned by the curves' crossings.
  for (const auto& [e, count] : edges) {
    if (edges.count({e.second, e.first})) continue;
    const Eigen::Vector3d p = m.mesh.vertices.row(e.first);
    EXPECT_TRUE(p.x() < -1e-2 || p.x() > 2.01 || p.y() < -1e-2 || p.y() > 2.01) << p.transpose();
  }
}

TEST(NetworkTessellation, LensMeshIsStitchedWithoutCracks) {  // F11
  const CurveNetwork net = buildCurveNetwork(lensNetwork());
  const NetworkMesh m = tessellateNetwork(net, 4);
  const CurveNetwork& n = net;
  // Outer boundary: the lower parabola, x = +-0.5 and y = 1.5 (in the xy projection).
  expectCrackFree(m, [&](const Eigen::Vector3d& p) {
    (void)n;
    return std::abs(p.y() - (p.x() * p.x() - 1)) < 1e-2 || std::abs(std::abs(p.x()) - 0.5) < 1e-9 ||
           std::abs(p.y() - 1.5) < 1e-9 || std::abs(p.y() - (1 - p.x() * p.x())) < 1e-2;
  });
}

}  // namespace
}  // namespace ffdkit::geometry::curvenet
