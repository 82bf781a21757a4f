#include "ffdkit/geometry/polyhedron/patch_surface.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "ffdkit/geometry/polyhedron/builtin_meshes.h"
#include "ffdkit/geometry/polyhedron/polyhedron_error.h"
#include "ffdkit/geometry/polyhedron/surface_diagnostics.h"
#include "test_support.h"

namespace ffdkit::geometry::polyhedron {
namespace {

struct NamedMesh {
  std::string name;
  PolygonMesh mesh;
  Tensions tensions;
};

Tensions topHexagonTensions(double alpha, double beta) {
  Tensions t;
  for (int k = 0; k < 6; ++k) {
    t.vertexAlpha[6 + k] = alpha;
    t.edgeBeta[{6 + k, 6 + (k + 1) % 6}] = beta;
  }
  return t;
}

std::vector<NamedMesh> referenceMeshes() {
  return {{"tetrahedron", tetrahedronMesh(), {}},
          {"cube", cubeMesh(), {}},
          {"octahedron", octahedronMesh(), {}},
          {"hexagonal prism", hexagonalPrismMesh(), {}},
          {"open hexagonal prism", openHexagonalPrismMesh(), {}},
          {"L prism", lShapedPrismMesh(), {}},
          {"L prism convex", lShapedPrismConvexMesh(), {}},
          {"hex prism beta 10 (Fig 4-13)", hexagonalPrismMesh(), topHexagonTensions(0.0, 10.0)},
          {"hex prism alpha 10 (Fig 4-14)", hexagonalPrismMesh(), topHexagonTensions(10.0, 1.0)},
          {"sphere 8x4", sphereMesh(8, 4), {}},
          {"torus 12x6", torusMesh(12, 6), {}}};
}

TEST(PatchSurface, IsG1AcrossEveryInteriorCurveOfEveryReferenceMesh) {
  for (const auto& m : referenceMeshes()) {
    const PatchSurface s = PatchSurface::build(m.mesh, m.tensions);
    const NormalJumpReport jump = maxNormalJump(s, 20);
    EXPECT_LE(jump.maxAngle, 1e-9) << m.name;
    EXPECT_GT(jump.minCosine, 0.0) << m.name;
    EXPECT_GT(jump.curvesChecked, 0) << m.name;
    std::cout << m.name << " max jump " << jump.maxAngle << "\n";
  }
}

TEST(PatchSurface, InterpolatesVerticesAndSharesNetworkCurvesExactly) {
  for (const auto& m : referenceMeshes()) {
    const PatchSurface s = PatchSurface::build(m.mesh, m.tensions);
    const double diagonal = boundingBoxDiagonal(m.mesh.vertices);
    EXPECT_LE(maxBoundaryDeviation(s, 20), 1e-12 * diagonal) << m.name;
    for (const auto& patch : s.patches()) {
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector3d uvw = Eigen::Vector3d::Zero();
        uvw[k] = 1.0;
        const Eigen::Vector3d corner = patch.evaluate(uvw[0], uvw[1], uvw[2]);
        EXPECT_LE((corner - s.triangulated().points.row(patch.corners[k]).transpose()).norm(), 1e-12 * diagonal);
      }
    }
  }
}

TEST(PatchSurface, CornerNormalsFollowTheVertexTangentPlanes) {
  for (const auto& m : referenceMeshes()) {
    EXPECT_LE(maxCornerNormalDeviation(PatchSurface::build(m.mesh, m.tensions)), 1e-9) << m.name;
  }
}

}  // namespace
}  // namespace ffdkit::geometry::polyhedron
