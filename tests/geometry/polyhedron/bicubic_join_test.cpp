#include "ffdkit/geometry/polyhedron/bicubic_join.h"

#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace ffdkit::geometry::polyhedron {
namespace {

struct Fixture {
  BicubicNet net;
  RationalQuarticTriangle triangle;
  double l1 = 0.0, l2 = 0.0;
};

Fixture randomFixture(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0), multiplier(-2.0, 2.0);
  auto point = [&] { return Eigen::Vector3d(uniform(random), uniform(random), uniform(random)); };
  Fixture f;
  for (auto& row : f.net) {
    for (auto& p : row) p = point();
  }
  // Other triangle points random, on the side w > 0 of the shared edge.
  for (auto& d : f.triangle.d) d = point() + Eigen::Vector3d(0, 0, 2);
  f.triangle.dv211 = point();
  f.triangle.du121 = point();
  f.triangle.dv112 = point();
  f.triangle.du112 = point();
  f.l1 = multiplier(random);
  f.l2 = multiplier(random);
  return f;
}

// Residual |lambda X + Y + Z| and tangent-plane angle along the shared edge (property 15).
std::pair<double, double> joinDefect(const Fixture& f) {
  double residual = 0.0, angle = 0.0;
  for (int k = 0; k <= 20; ++k) {
    const double u = k / 20.0;
    const BicubicPoint s = evaluateBicubic(f.net, u, 0.0);
    const PatchDerivatives q = f.triangle.evaluateWithPartials(u, 1.0 - u, 0.0);
    EXPECT_LE((s.point - q.point).norm(), 1e-13);
    const Eigen::Vector3d z = q.dw - q.dv;
    const double lambda = f.l1 * (1.0 - u) + f.l2 * u;
    residual = std::max(residual, (lambda * s.du + s.dw + z).norm());
    const Eigen::Vector3d n1 = s.du.cross(s.dw), n2 = (q.du - q.dv).cross(z);
    if (k > 0 && k < 20) angle = std::max(angle, std::asin(std::min(1.0, n1.normalized().cross(n2.normalized()).norm())));
  }
  return {residual, angle};
}

TEST(BicubicJoin, TriangleRowFromBicubicIsG1ForRandomData) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    Fixture f = randomFixture(seed);
    joinTriangleToBicubic(f.triangle, f.net, f.l1, f.l2);
    const auto [residual, angle] = joinDefect(f);
    EXPECT_LE(residual, 1e-10) << seed;
    EXPECT_LE(angle, 1e-9) << seed;
  }
}

TEST(BicubicJoin, BicubicSecondRowFromTriangleIsG1ForRandomData) {
  for (unsigned seed = 11; seed <= 20; ++seed) {
    Fixture f = randomFixture(seed);
    joinTriangleToBicubic(f.triangle, f.net, 0.0, 0.0);  // only to share the boundary row
    f.triangle.d[RationalQuarticTriangle::index(0, 3)] += Eigen::Vector3d(0.1, 0.2, 0.3);
    f.triangle.dw121 += Eigen::Vector3d(-0.3, 0.1, 0.2);
    f.triangle.dw211 += Eigen::Vector3d(0.2, 0.2, -0.1);
    const std::array<Eigen::Vector3d, 4> row0 = {f.net[0][0], f.net[1][0], f.net[2][0], f.net[3][0]};
    const auto row1 = bicubicSecondRowFromTriangle(f.triangle, row0, f.l1, f.l2);
    for (int i = 0; i < 4; ++i) f.net[i][1] = row1[i];
    const auto [residual, angle] = joinDefect(f);
    EXPECT_LE(residual, 1e-10) << seed;
    EXPECT_LE(angle, 1e-9) << seed;
  }
}

TEST(BicubicJoin, TwoDirectionsAreInverse) {
  Fixture f = randomFixture(42);
  const TriangleJoinRow row = triangleRowFromBicubic(f.net, f.l1, f.l2);
  joinTriangleToBicubic(f.triangle, f.net, f.l1, f.l2);
  EXPECT_EQ(f.triangle.dw121, row.dw121);
  const std::array<Eigen::Vector3d, 4> row0 = {f.net[0][0], f.net[1][0], f.net[2][0], f.net[3][0]};
  const auto row1 = bicubicSecondRowFromTriangle(f.triangle, row0, f.l1, f.l2);
  for (int i = 0; i < 4; ++i) EXPECT_LE((row1[i] - f.net[i][1]).norm(), 1e-13);
}

}  // namespace
}  // namespace ffdkit::geometry::polyhedron

#include "ffdkit/geometry/polyhedron/builtin_meshes.h"
#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {
namespace {

TEST(BicubicJoin, RelabellingKeepsTheSurface) {
  const PatchSurface s = PatchSurface::build(cubeMesh());
  const RationalQuarticTriangle& p = s.patches()[5];
  const RationalQuarticTriangle q = relabelled(p, {2, 0, 1});
  EXPECT_EQ(q.corners[0], p.corners[2]);
  // Slot s of q is slot order[s] of p, so q(x0, x1, x2) = p(x1, x2, x0).
  EXPECT_LE((q.evaluate(0.2, 0.3, 0.5) - p.evaluate(0.3, 0.5, 0.2)).norm(), 1e-14);
  EXPECT_THROW(relabelled(p, {0, 0, 1}), std::invalid_argument);
}

TEST(BicubicJoin, BicubicAcrossAnOpenBoundaryIsG1) {
  const PatchSurface s = PatchSurface::build(openHexagonalPrismMesh());
  std::mt19937 random(5);
  std::uniform_real_distribution<double> uniform(-0.1, 0.1);
  for (int k = 0; k < 6; ++k) {
    const int a = 6 + (k + 1) % 6, b = 6 + k;  // rim curve, boundary on the open top
    const auto row0 = s.curve(a, b);
    std::array<Eigen::Vector3d, 4> row2, row3;
    for (int i = 0; i < 4; ++i) {
      row2[i] = row0[i] + Eigen::Vector3d(uniform(random), uniform(random), 0.6);
      row3[i] = row0[i] + Eigen::Vector3d(uniform(random), uniform(random), 1.0);
    }
    for (const auto& [l1, l2] : {std::pair{0.0, 0.0}, std::pair{0.7, -1.3}}) {
      Fixture f;
      f.net = bicubicAcrossBoundary(s, a, b, row2, row3, l1, l2);
      f.triangle = boundaryPatchForJoin(s, a, b);
      f.l1 = l1;
      f.l2 = l2;
      const auto [residual, angle] = joinDefect(f);
      EXPECT_LE(residual, 1e-10) << k;
      EXPECT_LE(angle, 1e-9) << k;
    }
  }
  EXPECT_THROW(bicubicAcrossBoundary(s, 0, 1, {}, {}), PolyhedronError);  // bottom rim is interior
}

}  // namespace
}  // namespace ffdkit::geometry::polyhedron
