#include "ffdkit/geometry/curvenet/curve_network_surface.h"

#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "ffdkit/geometry/curvenet/example_networks.h"

namespace ffdkit::geometry::curvenet {
namespace {

TEST(CurveNetworkSurface, EveryExampleNetworkGeneratesAMesh) {
  for (const std::string& name : exampleNetworkNames()) {
    CurveNetworkSurfaceParams params;
    params.network = exampleNetwork(name);
    const NetworkMesh m = generateCurveNetworkSurfaceWithNormals(params, 3);
    EXPECT_GT(m.mesh.triangles.rows(), 0) << name;
    EXPECT_EQ(m.normals.rows(), m.mesh.vertices.rows()) << name;
    EXPECT_TRUE(m.mesh.vertices.allFinite()) << name;
    EXPECT_TRUE(m.normals.allFinite()) << name;
  }
  EXPECT_THROW(exampleNetwork("nope"), std::invalid_argument);
}

TEST(CurveNetworkSurface, IsDeterministicAndRegeneratesAtAnotherDensity) {
  CurveNetworkSurfaceParams params;
  params.network = tJunctionNetwork();
  const TriangleMesh a = generateCurveNetworkSurface(params, 4);
  const TriangleMesh b = generateCurveNetworkSurface(params, 4);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_GT(generateCurveNetworkSurface(params, 8).triangles.rows(), a.triangles.rows());
}

TEST(CurveNetworkSurface, FairingKeepsTheBoundaryAndChangesTheInterior) {
  CurveNetworkSurfaceParams params;
  params.network = heightGridNetwork(3);
  const NetworkMesh plain = generateCurveNetworkSurfaceWithNormals(params, 4);
  params.fairing = true;
  const NetworkMesh faired = generateCurveNetworkSurfaceWithNormals(params, 4);
  ASSERT_EQ(plain.mesh.vertices.rows(), faired.mesh.vertices.rows());
  EXPECT_EQ(plain.mesh.triangles, faired.mesh.triangles);
  EXPECT_GT((plain.mesh.vertices - faired.mesh.vertices).norm(), 1e-6);
}

// Largest distance from a vertex of `a` to the nearest vertex of `b` (both ways), and for each
// matched pair the normal agreement n_a . n_b (min over pairs).
struct MeshMatch {
  double distance = 0.0;
  double minNormalDot = 1.0;
  double maxNormalDot = -1.0;
};

MeshMatch matchMeshes(const NetworkMesh& a, const NetworkMesh& b) {
  MeshMatch m;
  for (int pass = 0; pass < 2; ++pass) {
    const NetworkMesh& from = pass ? b : a;
    const NetworkMesh& to = pass ? a : b;
    for (Eigen::Index r = 0; r < from.mesh.vertices.rows(); ++r) {
      Eigen::Index best = 0;
      const double d = std::sqrt((to.mesh.vertices.rowwise() - from.mesh.vertices.row(r)).rowwise().squaredNorm().minCoeff(&best));
      m.distance = std::max(m.distance, d);
      const double dot = from.normals.row(r).dot(to.normals.row(best));
      m.minNormalDot = std::min(m.minNormalDot, dot);
      m.maxNormalDot = std::max(m.maxNormalDot, dot);
    }
  }
  return m;
}

double diagonal(const TriangleMesh& m) { return (m.vertices.colwise().maxCoeff() - m.vertices.colwise().minCoeff()).norm(); }

TEST(CurveNetworkSurface, ReversingTheCurvesGivesTheSameSurface) {
  // Spec P10: the surface does not depend on how the loops or curves are oriented. Every curve
  // traversed backwards turns every side of every face loop around (forward <-> backward): the
  // same points must come out (the tessellation samples the same domain points, mirrored).
  for (const std::string& name : exampleNetworkNames()) {
    CurveNetworkSurfaceParams params;
    params.network = exampleNetwork(name);
    const NetworkMesh base = generateCurveNetworkSurfaceWithNormals(params, 4);
    for (CurveDescription& c : params.network.curves) {
      if (c.kind != CurveDescription::Kind::Polyline) continue;
      c.points = c.points.colwise().reverse().eval();
    }
    const NetworkMesh reversed = generateCurveNetworkSurfaceWithNormals(params, 4);
    const MeshMatch m = matchMeshes(base, reversed);
    EXPECT_EQ(reversed.mesh.vertices.rows(), base.mesh.vertices.rows()) << name;
    EXPECT_LE(m.distance, 1e-9 * diagonal(base.mesh)) << name;
    EXPECT_GE(m.minNormalDot, 1.0 - 1e-9) << name;  // the outward normals are decided by the network, not the curves
  }
}

// A flat sheet of straight curves, 3 along x and 3 along y (4 quads in z = 0): no vertex rule
// decides its normal, so the orientation hint does.
CurveNetworkDescription straightSheet() {
  CurveNetworkDescription d;
  for (int k = 0; k < 3; ++k) {
    for (int axis = 0; axis < 2; ++axis) {
      CurveDescription c;
      c.name = (axis ? "y = " : "x = ") + std::to_string(k);
      c.points.resize(4, 3);
      for (int r = 0; r < 4; ++r) {
        const double along = -0.2 + 1.4 * r / 3.0, across = 0.5 * k;
        c.points.row(r) << (axis ? along : across), (axis ? across : along), 0.0;
      }
      d.curves.push_back(c);
    }
  }
  return d;
}

TEST(CurveNetworkSurface, FlippingTheOrientationHintReversesTheLoopsNotTheSurface) {
  // Spec P10: reversing a loop's orientation mirrors the domain and flips the normal, and gives
  // the same surface. Flipping the hint traces every loop of the sheet the other way round.
  CurveNetworkSurfaceParams params;
  params.network = straightSheet();
  params.networkOptions.orientationHint = Eigen::Vector3d::UnitZ();
  const NetworkMesh up = generateCurveNetworkSurfaceWithNormals(params, 4);
  params.networkOptions.orientationHint = -Eigen::Vector3d::UnitZ();
  const NetworkMesh down = generateCurveNetworkSurfaceWithNormals(params, 4);
  ASSERT_GT(up.mesh.triangles.rows(), 0);
  for (Eigen::Index r = 0; r < up.normals.rows(); ++r) EXPECT_NEAR(up.normals(r, 2), 1.0, 1e-12) << r;
  const MeshMatch m = matchMeshes(up, down);
  EXPECT_EQ(down.mesh.vertices.rows(), up.mesh.vertices.rows());
  EXPECT_LE(m.distance, 1e-12);
  EXPECT_LE(m.maxNormalDot, -1.0 + 1e-12);  // every normal flipped
  // Triangles keep facing along their normals: the winding turned with the loops.
  for (Eigen::Index t = 0; t < down.mesh.triangles.rows(); ++t) {
    const Eigen::RowVector3i tri = down.mesh.triangles.row(t);
    const Eigen::Vector3d a = down.mesh.vertices.row(tri[0]), b = down.mesh.vertices.row(tri[1]), c = down.mesh.vertices.row(tri[2]);
    EXPECT_LT((b - a).cross(c - a).z(), 0.0) << t;
  }
}

TEST(CurveNetworkSurface, ValidatesParameters) {
  CurveNetworkSurfaceParams params;
  EXPECT_THROW(params.validate(), std::invalid_argument);
  params.network = sphereOctantNetwork();
  params.patch.blendingExponent = 0;
  EXPECT_THROW(params.validate(), std::invalid_argument);
  params.patch.blendingExponent = 3;
  EXPECT_NO_THROW(params.validate());
  EXPECT_THROW(generateCurveNetworkSurface(params, 0), std::invalid_argument);
}

}  // namespace
}  // namespace ffdkit::geometry::curvenet
