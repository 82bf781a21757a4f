#include "ffdkit/geometry/polyhedron/polyhedron_surface_generator.h"

#include <gtest/gtest.h>

#include "ffdkit/geometry/polyhedron/builtin_meshes.h"
#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {
namespace {

TEST(PolyhedronSurfaceGenerator, DefaultIsTheCubeAtEightSamplesPerSide) {
  const TriangleMesh mesh = generatePolyhedronSurface({});
  EXPECT_EQ(mesh.triangles.rows(), 24 * 64);
  EXPECT_TRUE(mesh.vertices.allFinite());
}

TEST(PolyhedronSurfaceGenerator, IsDeterministicAndRegeneratesAtAnotherDensity) {
  PolyhedronSurfaceParams params;
  params.builtinMesh = "hexagonal-prism";
  params.tensions.vertexAlpha[6] = 2.0;
  const TriangleMesh a = generatePolyhedronSurface(params, {4});
  const TriangleMesh b = generatePolyhedronSurface(params, {4});
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.triangles, b.triangles);
  const TriangleMesh fine = generatePolyhedronSurface(params, {8});
  EXPECT_EQ(fine.triangles.rows(), 4 * a.triangles.rows());
  // Polyhedron vertices keep their ids and positions at every density.
  for (int v = 0; v < 12; ++v) {
    EXPECT_LE((a.vertices.row(v) - fine.vertices.row(v)).norm(), 1e-15);
    EXPECT_LE((a.vertices.row(v) - hexagonalPrismMesh().vertices.row(v)).norm(), 1e-12);
  }
}

TEST(PolyhedronSurfaceGenerator, ExplicitMeshOverridesTheBuiltinName) {
  PolyhedronSurfaceParams params;
  params.builtinMesh = "no-such-mesh";
  params.mesh = octahedronMesh();
  EXPECT_EQ(generatePolyhedronSurface(params, {2}).triangles.rows(), 24 * 4);
}

TEST(PolyhedronSurfaceGenerator, ReportsBadParametersClearly) {
  PolyhedronSurfaceParams unknown;
  unknown.builtinMesh = "no-such-mesh";
  EXPECT_THROW(generatePolyhedronSurface(unknown), PolyhedronError);
  EXPECT_THROW(generatePolyhedronSurface({}, {0}), PolyhedronError);
  PolyhedronSurfaceParams badEdge;
  badEdge.tensions.edgeBeta[{0, 7}] = 2.0;  // not an edge of the cube
  try {
    generatePolyhedronSurface(badEdge);
    FAIL();
  } catch (const PolyhedronError& e) {
    EXPECT_NE(std::string(e.what()).find("edge (0, 7)"), std::string::npos) << e.what();
  }
}

TEST(PolyhedronSurfaceGenerator, EveryBuiltinMeshGivesAFiniteSurfaceWithNormals) {
  for (const auto& name : builtinMeshNames()) {
    PolyhedronSurfaceParams params;
    params.builtinMesh = name;
    const TessellatedSurface s = generatePolyhedronSurfaceWithNormals(params, {3});
    EXPECT_TRUE(s.mesh.vertices.allFinite()) << name;
    EXPECT_TRUE(s.normals.allFinite()) << name;
    EXPECT_EQ(s.normals.rows(), s.mesh.vertices.rows());
  }
}

}  // namespace
}  // namespace ffdkit::geometry::polyhedron
