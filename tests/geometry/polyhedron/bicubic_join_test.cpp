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

// Residual |lambda X + Y + Z| and tangent-plane angle along the shared edge (spec §6 property 15).
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
