#include "ffdkit/geometry/polyhedron/surface_tessellation.h"

#include <map>
#include <set>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "ffdkit/geometry/polyhedron/builtin_meshes.h"
#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {
namespace {

std::map<std::pair<int, int>, int> edgeUses(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> uses;
  for (int f = 0; f < mesh.triangles.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles(f, k), b = mesh.triangles(f, (k + 1) % 3);
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  return uses;
}

TEST(SurfaceTessellation, ClosedSurfaceIsWatertightWithWeldedVertices) {
  for (const PolygonMesh& mesh : {cubeMesh(), tetrahedronMesh(), hexagonalPrismMesh()}) {
    for (int n : {1, 2, 5}) {
      const TessellatedSurface t = tessellate(PatchSurface::build(mesh), n);
      const auto uses = edgeUses(t.mesh);
      for (const auto& [edge, count] : uses) EXPECT_EQ(count, 2);
      const long v = t.mesh.vertices.rows(), e = static_cast<long>(uses.size()), f = t.mesh.triangles.rows();
      EXPECT_EQ(v - e + f, 2);  // genus-0 sphere
      // No two vertices at the same place: the weld is complete.
      std::set<std::tuple<long, long, long>> keys;
      for (int i = 0; i < v; ++i) {
        keys.insert({std::lround(t.mesh.vertices(i, 0) * 1e9), std::lround(t.mesh.vertices(i, 1) * 1e9),
                     std::lround(t.mesh.vertices(i, 2) * 1e9)});
      }
      EXPECT_EQ(static_cast<long>(keys.size()), v);
    }
  }
}

TEST(SurfaceTessellation, OpenSurfaceHasOneBoundaryLoopOfRimSamples) {
  const int n = 4;
  const TessellatedSurface t = tessellate(PatchSurface::build(openHexagonalPrismMesh()), n);
  int boundary = 0;
  for (const auto& [edge, count] : edgeUses(t.mesh)) {
    EXPECT_LE(count, 2);
    boundary += count == 1;
  }
  EXPECT_EQ(boundary, 6 * n);
}

TEST(SurfaceTessellation, TrianglesFaceOutwardAndNormalsAreUnitAndAgree) {
  const TessellatedSurface t = tessellate(PatchSurface::build(cubeMesh()), 6);
  for (int f = 0; f < t.mesh.triangles.rows(); ++f) {
    const Eigen::Vector3d a = t.mesh.vertices.row(t.mesh.triangles(f, 0)).transpose();
    const Eigen::Vector3d b = t.mesh.vertices.row(t.mesh.triangles(f, 1)).transpose();
    const Eigen::Vector3d c = t.mesh.vertices.row(t.mesh.triangles(f, 2)).transpose();
    const Eigen::Vector3d faceNormal = (b - a).cross(c - a);
    EXPECT_GT(faceNormal.dot(a), 0.0);  // the cube surface is star-shaped about the origin
    EXPECT_GT(faceNormal.normalized().dot(t.normals.row(t.mesh.triangles(f, 0)).transpose()), 0.9);
  }
  for (int v = 0; v < t.normals.rows(); ++v) EXPECT_NEAR(t.normals.row(v).norm(), 1.0, 1e-12);
}

TEST(SurfaceTessellation, CuspFromHugeVertexTensionStillGivesFiniteNormals) {
  Tensions t;
  t.vertexAlpha[0] = 1e12;
  const TessellatedSurface s = tessellate(PatchSurface::build(cubeMesh(), t), 4);
  EXPECT_TRUE(s.mesh.vertices.allFinite());
  EXPECT_TRUE(s.normals.allFinite());
}

TEST(SurfaceTessellation, RejectsZeroSamples) { EXPECT_THROW(tessellate(PatchSurface::build(cubeMesh()), 0), PolyhedronError); }

}  // namespace
}  // namespace ffdkit::geometry::polyhedron
