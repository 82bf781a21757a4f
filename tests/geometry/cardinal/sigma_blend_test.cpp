#include "ffdkit/geometry/cardinal/sigma_blend.h"

#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "ffdkit/geometry/cardinal/cardinal_error.h"
#include "ffdkit/geometry/cardinal/shape_points.h"

namespace ffdkit::geometry::cardinal {
namespace {

// A closed-in-u, open-in-v surface of two horizontal sections (case T16): points of the
// section at radius r(angle index) for heights z0, z1; u knots from the interval widths.
SigmaSurface sectionSurface(const std::vector<double>& widths,
                            const std::function<double(int)>& radius, double z0, double z1) {
  const int count = static_cast<int>(widths.size());
  Eigen::VectorXd tu(count + 1);
  tu[0] = 0.0;
  for (int i = 0; i < count; ++i) tu[i + 1] = tu[i] + widths[static_cast<std::size_t>(i)];
  SigmaKnotsOptions closed;
  closed.closed = true;
  const SigmaKnots ku(tu, {}, closed);
  Eigen::VectorXd tv(2);
  tv << 0.0, 10.0;
  const SigmaKnots kv(tv);
  PointGrid g(count, 2);
  for (int i = 0; i < count; ++i) {
    const double angle = 2.0 * M_PI * tu[i] / 40.0;
    for (int j = 0; j < 2; ++j) {
      const double scale = j == 0 ? 1.0 : 1.2;
      g(i, j) = Eigen::Vector3d(scale * radius(i) * std::cos(angle),
                                scale * radius(i) * std::sin(angle), j == 0 ? z0 : z1);
    }
  }
  return interpolateSigmaSurface(ku, kv, g).surface;
}

SigmaSurface circle(double z0, double z1) {
  return sectionSurface({10, 10, 10, 10}, [](int) { return 1.0; }, z0, z1);
}
SigmaSurface star(double z0, double z1) {
  return sectionSurface(std::vector<double>(10, 4.0), [](int i) { return i % 2 ? 0.5 : 1.0; }, z0, z1);
}
SigmaSurface vase(double z0, double z1) {
  return sectionSurface({4, 2, 2, 4, 2, 2, 4, 4, 4, 4, 4, 4},
                        [](int i) { return 0.8 + 0.2 * std::cos(1.7 * i); }, z0, z1);
}

// d2Q/dv2 at (u, knot v_j) from the left (interval j-1) and the right (interval j).
std::pair<Eigen::Vector3d, Eigen::Vector3d> secondDerivativeAcross(const SigmaSurface& s, double u,
                                                                   int j) {
  double su = 0.0;
  const int i = s.knotsU.locate(u, su);
  const double dl = s.knotsV.delta(j - 1), dr = s.knotsV.delta(j);
  return {evaluateQuarticPatch(s.patch(i, j - 1), su, 1.0, 0, 2) / (dl * dl),
          evaluateQuarticPatch(s.patch(i, j), su, 0.0, 0, 2) / (dr * dr)};
}

void expectBlendProperties(const SigmaSurface& a, const SigmaSurface& b, int expectedUKnots) {
  const BlendResult r = blendSurfaces(a, b);
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_EQ(r.composite.knotsU.last(), expectedUKnots);
  const int n = a.knotsV.last();
  // Reproduction of both originals (P13).
  double worst = 0.0;
  for (int k = 0; k <= 80; ++k) {
    const double u = k * 0.5;
    for (int m = 0; m <= 20; ++m) {
      const double v = m * 0.5;
      worst = std::max(worst, (r.composite.evaluate(u, v) - a.evaluate(u, v)).norm());
      worst = std::max(worst, (r.composite.evaluate(u, v + r.surface2VOffset) - b.evaluate(u, v)).norm());
    }
  }
  EXPECT_LT(worst, 1e-12);
  // C2 across v_n and v_{n+2} (all beta2 = 0), and the blend alone equals the composite there.
  double jump = 0.0, slice = 0.0;
  for (int k = 0; k < 80; ++k) {
    const double u = k * 0.5;
    for (int j : {n, n + 2}) {
      const auto [left, right] = secondDerivativeAcross(r.composite, u, j);
      jump = std::max(jump, (left - right).norm());
    }
    for (int m = 0; m <= 10; ++m) {
      const double v = r.blend.knotsV.start() + m * (r.blend.knotsV.end() - r.blend.knotsV.start()) / 10;
      slice = std::max(slice, (r.blend.evaluate(u, v) - r.composite.evaluate(u, v)).norm());
    }
  }
  EXPECT_LT(jump, 1e-12);
  EXPECT_LT(slice, 1e-12);
}

TEST(SigmaBlend, CircleToStarReproducesBothAndIsC2) {
  expectBlendProperties(circle(0, 1), star(3, 4), 12);
}

TEST(SigmaBlend, StarToVaseUsesTheVaseKnots) {
  expectBlendProperties(star(0, 1), vase(3, 4), 12);
}

TEST(SigmaBlend, CircleToVaseHasFourteenKnots) {
  const BlendResult r = blendSurfaces(circle(0, 1), vase(3, 4));
  Eigen::VectorXd expected(15);
  expected << 0, 4, 6, 8, 10, 12, 14, 16, 20, 24, 28, 30, 32, 36, 40;
  EXPECT_LT((r.composite.knotsU.knots() - expected).cwiseAbs().maxCoeff(), 1e-12);
  expectBlendProperties(circle(0, 1), vase(3, 4), 14);
}

TEST(SigmaBlend, UniformMiddleWeightsMatchSpec) {
  // All four v-intervals around the blend are 10 wide: the blending weights of Kuriyama 1996, sec. 3.3.7.
  const BlendResult r = blendSurfaces(circle(0, 1), star(3, 4));
  const double expected[6] = {1.0 / 8, 1.0 / 8, -3.0 / 32, 15.0 / 32, 15.0 / 32, -3.0 / 32};
  double sum = 0.0;
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(r.middleWeights[static_cast<std::size_t>(k)], expected[k], 1e-14) << k;
    sum += r.middleWeights[static_cast<std::size_t>(k)];
  }
  EXPECT_NEAR(sum, 1.0, 1e-14);
}

TEST(SigmaBlend, NonUniformGapsStillReproduceAndAreC2) {
  BlendOptions o;
  o.gapBefore = 3.0;
  o.gapAfter = 17.0;
  const SigmaSurface a = circle(0, 1), b = star(3, 4);
  const BlendResult r = blendSurfaces(a, b, o);
  double sum = 0.0;
  for (double w : r.middleWeights) sum += w;
  EXPECT_NEAR(sum, 1.0, 1e-13);
  for (int k = 0; k < 40; ++k) {
    const auto [left, right] = secondDerivativeAcross(r.composite, k, a.knotsV.last() + 2);
    EXPECT_LT((left - right).norm(), 1e-12);
    EXPECT_LT((r.composite.evaluate(k, 5.0) - a.evaluate(k, 5.0)).norm(), 1e-12);
  }
}

TEST(SigmaBlend, JunctionTensionKeepsOriginalsAndGivesG2Beta) {
  // With beta2 != 0 at v_n and v_{n+2} the composite still reproduces both originals and obeys
  // Q_vv(v+) = Q_vv(v-) + beta2 Q_v(v-) there (G2, not C2).
  BlendOptions o;
  o.junctionBeta2 = {2.0, 0.5, 3.0};
  const SigmaSurface a = circle(0, 1), b = star(3, 4);
  const BlendResult r = blendSurfaces(a, b, o);
  const int n = a.knotsV.last();
  for (int k = 0; k < 40; ++k) {
    EXPECT_LT((r.composite.evaluate(k, 4.0) - a.evaluate(k, 4.0)).norm(), 1e-12);
    EXPECT_LT((r.composite.evaluate(k, 6.0 + r.surface2VOffset) - b.evaluate(k, 6.0)).norm(), 1e-12);
    for (int m = 0; m < 2; ++m) {
      const int j = n + 2 * m;
      const double beta2 = o.junctionBeta2[static_cast<std::size_t>(2 * m)];
      const auto [left, right] = secondDerivativeAcross(r.composite, k, j);
      double su = 0.0;
      const int i = r.composite.knotsU.locate(k, su);
      const Eigen::Vector3d slope =
          evaluateQuarticPatch(r.composite.patch(i, j - 1), su, 1.0, 0, 1) / r.composite.knotsV.delta(j - 1);
      EXPECT_LT((right - left - beta2 * slope).norm(), 1e-10);
    }
  }
}

TEST(SigmaBlend, WarnsWhenTensionsDifferAtASharedUKnot) {
  // Kuriyama 1996, sec. 3.3.7 claims only G1 here: surface 2 has tension at a u-knot that surface 1 lacks.
  const SigmaSurface a = circle(0, 1);
  SigmaSurface b = star(3, 4);
  Eigen::VectorXd beta2 = Eigen::VectorXd::Zero(10);
  beta2[1] = 5.0;
  b.knotsU = SigmaKnots(b.knotsU.knots(), beta2, b.knotsU.options());
  const BlendResult r = blendSurfaces(a, b);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("u = 4"), std::string::npos) << r.warnings[0];
  // Surface 1 is still reproduced exactly.
  for (int k = 0; k < 40; ++k) EXPECT_LT((r.composite.evaluate(k, 3.0) - a.evaluate(k, 3.0)).norm(), 1e-12);
}

TEST(SigmaBlend, RejectsMismatchedSurfaces) {
  const SigmaSurface a = circle(0, 1);
  // u range [0, 20] vs [0, 40].
  EXPECT_THROW(blendSurfaces(a, sectionSurface({5, 5, 5, 5}, [](int) { return 1.0; }, 0, 1)),
               CardinalSplineError);
  // A surface closed in v cannot be blended along v.
  const SigmaKnots kv = SigmaKnots::uniform(3, true);
  PointGrid g(4, 3);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) g(i, j) = Eigen::Vector3d(i, j, i * j);
  SigmaKnots ku(Eigen::Vector4d(0, 1, 2, 3));
  const SigmaSurface closedV = interpolateSigmaSurface(ku, kv, g).surface;
  EXPECT_THROW(blendSurfaces(closedV, closedV), CardinalSplineError);
}

}  // namespace
}  // namespace ffdkit::geometry::cardinal
