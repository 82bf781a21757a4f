#include "ffdkit/geometry/polyhedron/rational_quartic_triangle.h"

#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

namespace ffdkit::geometry::polyhedron {
namespace {

RationalQuarticTriangle randomPatch(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  auto point = [&] { return Eigen::Vector3d(uniform(random), uniform(random), uniform(random)); };
  RationalQuarticTriangle p;
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; i + j <= 4; ++j) {
      if (i > 0 && j > 0 && i + j < 4) continue;
      p.d[RationalQuarticTriangle::index(i, j)] = point();
    }
  }
  p.dw211 = point();
  p.dv211 = point();
  p.dw121 = point();
  p.du121 = point();
  p.dv112 = point();
  p.du112 = point();
  return p;
}

TEST(RationalQuarticTriangle, IndexCoversFifteenSlots) {
  std::vector<int> seen(15, 0);
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; i + j <= 4; ++j) ++seen[RationalQuarticTriangle::index(i, j)];
  }
  for (int count : seen) EXPECT_EQ(count, 1);
}

TEST(RationalQuarticTriangle, EqualSubPointsGiveThePolynomialQuartic) {
  RationalQuarticTriangle p = randomPatch(1);
  p.dv211 = p.dw211;
  p.du121 = p.dw121;
  p.du112 = p.dv112;
  const double u = 0.2, v = 0.5, w = 0.3;
  Eigen::Vector3d expected = Eigen::Vector3d::Zero();
  const double factorial[5] = {1, 1, 2, 6, 24};
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; i + j <= 4; ++j) {
      const int k = 4 - i - j;
      Eigen::Vector3d d = p.d[RationalQuarticTriangle::index(i, j)];
      if (i == 2 && j == 1) d = p.dw211;
      if (i == 1 && j == 2) d = p.dw121;
      if (i == 1 && j == 1) d = p.dv112;
      expected += 24.0 / (factorial[i] * factorial[j] * factorial[k]) * std::pow(u, i) * std::pow(v, j) * std::pow(w, k) * d;
    }
  }
  EXPECT_LE((p.evaluate(u, v, w) - expected).norm(), 1e-14);
}

TEST(RationalQuarticTriangle, PartialsMatchCentralDifferences) {
  const RationalQuarticTriangle p = randomPatch(2);
  const double h = 1e-6;
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.2, 0.5, 0.3), Eigen::Vector3d(0.7, 0.1, 0.2), Eigen::Vector3d(0.05, 0.05, 0.9)}) {
    const PatchDerivatives d = p.evaluateWithPartials(x[0], x[1], x[2]);
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::Vector3d plus = x, minus = x;
      plus[axis] += h;
      minus[axis] -= h;
      const Eigen::Vector3d numeric = (p.evaluate(plus[0], plus[1], plus[2]) - p.evaluate(minus[0], minus[1], minus[2])) / (2 * h);
      const Eigen::Vector3d analytic = axis == 0 ? d.du : axis == 1 ? d.dv : d.dw;
      EXPECT_LE((numeric - analytic).norm(), 1e-7) << "axis " << axis;
    }
  }
}

TEST(RationalQuarticTriangle, EdgeDependsOnlyOnItsBoundaryPointsAndCornersAreFinite) {
  RationalQuarticTriangle p = randomPatch(3);
  const Eigen::Vector3d before = p.evaluate(0.4, 0.6, 0.0);
  p.dv211 += Eigen::Vector3d(1, 2, 3);  // belongs to edge v = 0, enters the w = 0 edge not at all
  p.dw211 += Eigen::Vector3d(1, 2, 3);
  EXPECT_LE((p.evaluate(0.4, 0.6, 0.0) - before).norm(), 1e-15);
  for (const Eigen::Vector3d& c : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1)}) {
    EXPECT_TRUE(p.evaluateWithPartials(c[0], c[1], c[2]).du.allFinite());
    EXPECT_NEAR(p.normal(c[0], c[1], c[2]).norm(), 1.0, 1e-12);
  }
}

TEST(RationalQuarticTriangle, CrossDerivativeAlongAnEdgeSeesOnlyThatEdgesSubPoints) {
  RationalQuarticTriangle p = randomPatch(4);
  auto cross = [&](const RationalQuarticTriangle& q) {
    const PatchDerivatives d = q.evaluateWithPartials(0.3, 0.7, 0.0);
    return Eigen::Vector3d(d.dw - d.dv);
  };
  const Eigen::Vector3d before = cross(p);
  p.dv211 += Eigen::Vector3d(1, 1, 1);
  p.du121 += Eigen::Vector3d(1, -1, 1);
  p.dv112 += Eigen::Vector3d(2, 1, 0);
  p.du112 += Eigen::Vector3d(0, 1, 2);
  EXPECT_LE((cross(p) - before).norm(), 1e-13);
  p.dw211 += Eigen::Vector3d(1, 0, 0);
  EXPECT_GT((cross(p) - before).norm(), 1e-3);
}

TEST(RationalQuarticTriangle, SubPointSlotsFollowEquation418) {
  RationalQuarticTriangle p;
  EXPECT_EQ(&p.subPoint(0, 1), &p.dw211);
  EXPECT_EQ(&p.subPoint(0, 2), &p.dv211);
  EXPECT_EQ(&p.subPoint(1, 0), &p.dw121);
  EXPECT_EQ(&p.subPoint(1, 2), &p.du121);
  EXPECT_EQ(&p.subPoint(2, 0), &p.dv112);
  EXPECT_EQ(&p.subPoint(2, 1), &p.du112);
  EXPECT_THROW(p.subPoint(1, 1), std::invalid_argument);
}

TEST(RationalQuarticTriangle, ElevatesCubicsExactly) {
  const std::array<Eigen::Vector3d, 4> cubic = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 0),
                                                Eigen::Vector3d(3, 2, 1), Eigen::Vector3d(4, 0, 0)};
  const auto quartic = elevateCubic(cubic);
  for (double s : {0.0, 0.3, 0.8, 1.0}) {
    const double r = 1 - s;
    const Eigen::Vector3d c = r * r * r * cubic[0] + 3 * r * r * s * cubic[1] + 3 * r * s * s * cubic[2] + s * s * s * cubic[3];
    Eigen::Vector3d q = Eigen::Vector3d::Zero();
    const double binomial[5] = {1, 4, 6, 4, 1};
    for (int i = 0; i <= 4; ++i) q += binomial[i] * std::pow(r, 4 - i) * std::pow(s, i) * quartic[i];
    EXPECT_LE((c - q).norm(), 1e-14);
  }
}

}  // namespace
}  // namespace ffdkit::geometry::polyhedron
