#include "ffdkit/geometry/cardinal/surface_tessellation.h"

#include <cmath>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "ffdkit/geometry/cardinal/cardinal_error.h"
#include "ffdkit/geometry/cardinal/shape_points.h"

namespace ffdkit::geometry::cardinal {
namespace {

// A torus-like grid, closed in both directions (radius 2 around z, tube radius 0.5).
PointGrid torusGrid(int nu, int nv) {
  PointGrid g(nu, nv);
  for (int i = 0; i < nu; ++i) {
    const double a = 2 * M_PI * i / nu;
    for (int j = 0; j < nv; ++j) {
      const double b = 2 * M_PI * j / nv;
      const double r = 2.0 + 0.5 * std::cos(b);
      g(i, j) = Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 0.5 * std::sin(b));
    }
  }
  return g;
}

void expectConsistentMesh(const SurfaceTessellation& t, int expectedVertices, int expectedTriangles) {
  ASSERT_EQ(t.mesh.vertices.rows(), expectedVertices);
  ASSERT_EQ(t.mesh.triangles.rows(), expectedTriangles);
  ASSERT_EQ(t.normals.rows(), expectedVertices);
  EXPECT_GE(t.mesh.triangles.minCoeff(), 0);
  EXPECT_LT(t.mesh.triangles.maxCoeff(), expectedVertices);
  for (Eigen::Index v = 0; v < t.normals.rows(); ++v) EXPECT_NEAR(t.normals.row(v).norm(), 1.0, 1e-12);
  // Triangles wind counter-clockwise around the vertex normals.
  for (Eigen::Index f = 0; f < t.mesh.triangles.rows(); ++f) {
    const Eigen::Vector3d a = t.mesh.vertices.row(t.mesh.triangles(f, 0));
    const Eigen::Vector3d b = t.mesh.vertices.row(t.mesh.triangles(f, 1));
    const Eigen::Vector3d c = t.mesh.vertices.row(t.mesh.triangles(f, 2));
    const Eigen::Vector3d face = (b - a).cross(c - a);
    EXPECT_GT(face.dot(t.normals.row(t.mesh.triangles(f, 0)).transpose()), 0.0) << f;
  }
}

TEST(SurfaceTessellation, SigmaTorusIsWeldedAndOrientedOutward) {
  const SigmaSurface s = interpolateSigmaSurface(SigmaKnots::uniform(8, true),
                                                 SigmaKnots::uniform(6, true), torusGrid(8, 6))
                             .surface;
  const SurfaceTessellation t = tessellate(s, {4, 3});
  expectConsistentMesh(t, 32 * 18, 2 * 32 * 18);
  // Outward: the normal points away from the tube centre line.
  for (Eigen::Index v = 0; v < t.mesh.vertices.rows(); ++v) {
    const Eigen::Vector3d p = t.mesh.vertices.row(v);
    const Eigen::Vector3d centre = 2.0 * Eigen::Vector3d(p.x(), p.y(), 0).normalized();
    EXPECT_GT(t.normals.row(v).dot(p - centre), 0.0);
  }
  // Vertices lie on the surface, normals are the analytic ones.
  for (Eigen::Index v = 0; v < t.mesh.vertices.rows(); v += 7) {
    const double u = t.parameters(v, 0), w = t.parameters(v, 1);
    EXPECT_LT((t.mesh.vertices.row(v).transpose() - s.evaluate(u, w)).norm(), 1e-12);
    const Eigen::Vector3d n = s.evaluate(u, w, 1, 0).cross(s.evaluate(u, w, 0, 1)).normalized();
    EXPECT_LT((t.normals.row(v).transpose() - n).norm(), 1e-9);
  }
}

TEST(SurfaceTessellation, OpenSigmaPatchHasBoundaryRowsAndInterpolates) {
  PointGrid g(4, 3);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) g(i, j) = Eigen::Vector3d(i, j, 0.1 * i * j);
  const SigmaSurface s = interpolateSigmaSurface(SigmaKnots::uniform(3), SigmaKnots::uniform(2), g).surface;
  const SurfaceTessellation t = tessellate(s, {2, 2});
  expectConsistentMesh(t, 7 * 5, 2 * 6 * 4);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_LT((t.mesh.vertices.row((2 * i) * 5 + 2 * j).transpose() - g(i, j)).norm(), 1e-12);
}

TEST(SurfaceTessellation, SSplineTorusIsWeldedAndOriented) {
  SSplineSurfaceOptions o;
  o.closedU = o.closedV = true;
  o.beta2U = 5.0;
  const SSplineSurface s(torusGrid(8, 6), o);
  const SurfaceTessellation t = tessellate(s, {3, 3});
  expectConsistentMesh(t, 24 * 18, 2 * 24 * 18);
  // The shared-basis grid sampling equals pointwise evaluation.
  for (Eigen::Index v = 0; v < t.mesh.vertices.rows(); ++v) {
    const double u = t.parameters(v, 0), w = t.parameters(v, 1);
    EXPECT_LT((t.mesh.vertices.row(v).transpose() - s.evaluate(u, w)).norm(), 1e-13);
    const Eigen::Vector3d n = s.evaluate(u, w, 1, 0).cross(s.evaluate(u, w, 0, 1)).normalized();
    EXPECT_LT((t.normals.row(v).transpose() - n).norm(), 1e-12);
  }
}

TEST(SurfaceTessellation, RejectsZeroSampling) {
  const SSplineSurface s(torusGrid(3, 3));
  EXPECT_THROW(tessellate(s, {0, 2}), CardinalSplineError);
}

}  // namespace
}  // namespace ffdkit::geometry::cardinal
