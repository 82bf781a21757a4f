#include "ffdkit/geometry/polyhedron/builtin_meshes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {
namespace {

// Signed volume by the divergence theorem: positive iff faces are counter-clockwise from outside.
double signedVolume(const PolygonMesh& mesh) {
  double volume = 0.0;
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d a = mesh.vertices.row(f[0]).transpose();
    for (std::size_t k = 1; k + 1 < f.size(); ++k) {
      const Eigen::Vector3d b = mesh.vertices.row(f[k]).transpose(), c = mesh.vertices.row(f[k + 1]).transpose();
      volume += a.dot(b.cross(c)) / 6.0;
    }
  }
  return volume;
}

TEST(BuiltinMeshes, ClosedMeshesAreOrientedOutwardWithExpectedVolumes) {
  EXPECT_NEAR(signedVolume(tetrahedronMesh()), 8.0 / 3.0, 1e-12);
  EXPECT_NEAR(signedVolume(cubeMesh()), 8.0, 1e-12);
  EXPECT_NEAR(signedVolume(octahedronMesh()), 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(signedVolume(hexagonalPrismMesh()), 1.5 * std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(signedVolume(lShapedPrismMesh()), 2.5, 1e-12);
  EXPECT_NEAR(signedVolume(lShapedPrismConvexMesh()), 2.5, 1e-12);
  EXPECT_GT(signedVolume(sphereMesh(8, 4)), 0.0);
  EXPECT_GT(signedVolume(torusMesh(12, 6)), 0.0);
}

TEST(BuiltinMeshes, HaveTheDocumentedFaceCounts) {
  EXPECT_EQ(tetrahedronMesh().faces.size(), 4u);
  EXPECT_EQ(cubeMesh().faces.size(), 6u);
  EXPECT_EQ(octahedronMesh().faces.size(), 8u);
  EXPECT_EQ(hexagonalPrismMesh().faces.size(), 8u);
  EXPECT_EQ(hexagonalPrismMesh().faces.back().size(), 6u);
  EXPECT_EQ(openHexagonalPrismMesh().faces.size(), 7u);
  EXPECT_EQ(lShapedPrismMesh().faces.size(), 8u);
  EXPECT_EQ(lShapedPrismConvexMesh().faces.size(), 10u);
  EXPECT_EQ(sphereMesh(8, 4).faces.size(), 32u);
  EXPECT_EQ(torusMesh(40, 25).faces.size(), 1000u);
}

TEST(BuiltinMeshes, LooksUpByNameAndListsKnownNamesOnError) {
  for (const auto& name : builtinMeshNames()) EXPECT_NO_THROW(builtinMesh(name));
  try {
    builtinMesh("dodecahedron");
    FAIL();
  } catch (const PolyhedronError& e) {
    EXPECT_NE(std::string(e.what()).find("known: tetrahedron, cube"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sphereMesh(2, 4), PolyhedronError);
  EXPECT_THROW(torusMesh(8, 4, 1.0, 2.0), PolyhedronError);
}

}  // namespace
}  // namespace ffdkit::geometry::polyhedron
