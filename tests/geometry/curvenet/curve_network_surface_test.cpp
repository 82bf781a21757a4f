#include "ffdkit/geometry/curvenet/curve_network_surface.h"

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
