#include "ffdkit/geometry/polyhedron/tensions.h"

#include <gtest/gtest.h>

#include "ffdkit/geometry/polyhedron/builtin_meshes.h"
#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {
namespace {

TEST(Tensions, DefaultsAndOverridesResolvePerVertexAndEdge) {
  const MeshTopology topology = validatePolygonMesh(cubeMesh());
  Tensions t;
  t.defaultAlpha = 0.25;
  t.vertexAlpha[3] = 2.0;
  t.edgeBeta[{1, 0}] = 5.0;
  const ResolvedTensions r = resolveTensions(t, topology);
  EXPECT_EQ(r.alpha[0], 0.25);
  EXPECT_EQ(r.alpha[3], 2.0);
  EXPECT_EQ(r.beta[topology.edge(topology.findHalfEdge(0, 1))], 5.0);
  EXPECT_EQ(r.beta[topology.edge(topology.findHalfEdge(0, 2))], 1.0);
}

TEST(Tensions, PerEndTensionsAverageOverTheEdge) {
  const MeshTopology topology = validatePolygonMesh(cubeMesh());
  Tensions t;
  t.endBeta[{0, 1}] = 3.0;
  t.endBeta[{1, 0}] = 5.0;
  t.endBeta[{0, 2}] = 7.0;  // other end keeps the default 1
  const ResolvedTensions r = resolveTensions(t, topology);
  EXPECT_EQ(r.beta[topology.edge(topology.findHalfEdge(0, 1))], 4.0);
  EXPECT_EQ(r.beta[topology.edge(topology.findHalfEdge(0, 2))], 4.0);
}

TEST(Tensions, RejectsNegativeUnknownDuplicateAndUnderdeterminedTensions) {
  const MeshTopology topology = validatePolygonMesh(cubeMesh());
  Tensions negative;
  negative.vertexAlpha[0] = -1.0;
  EXPECT_THROW(resolveTensions(negative, topology), PolyhedronError);
  Tensions unknownVertex;
  unknownVertex.vertexAlpha[8] = 1.0;
  EXPECT_THROW(resolveTensions(unknownVertex, topology), PolyhedronError);
  Tensions duplicate;
  duplicate.edgeBeta[{0, 1}] = 1.0;
  duplicate.edgeBeta[{1, 0}] = 2.0;
  EXPECT_THROW(resolveTensions(duplicate, topology), PolyhedronError);
  Tensions unknownEnd;
  unknownEnd.endBeta[{0, 7}] = 1.0;
  EXPECT_THROW(resolveTensions(unknownEnd, topology), PolyhedronError);
  Tensions free;
  free.defaultBeta = 0.0;
  try {
    resolveTensions(free, topology);
    FAIL();
  } catch (const PolyhedronError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ffdkit::geometry::polyhedron
