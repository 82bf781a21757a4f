#include "ffdkit/geometry/gauss_legendre.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

namespace ffdkit::geometry {
namespace {

TEST(GaussLegendre, IntegratesPolynomialsOfDegreeUpTo2nMinus1Exactly) {
  for (int n = 1; n <= 12; ++n) {
    const GaussLegendreRule rule = gaussLegendreRule(n);
    EXPECT_NEAR(rule.weights.sum(), 2.0, 1e-14);
    for (int k = 0; k <= 2 * n - 1; ++k) {
      // Integral of x^k over [0, 2] is 2^(k+1) / (k+1).
      const double got = integrateGaussLegendre(rule, 0.0, 2.0, [k](double x) { return std::pow(x, k); });
      const double expected = std::pow(2.0, k + 1) / (k + 1);
      EXPECT_NEAR(got, expected, 1e-13 * expected) << "n " << n << " k " << k;
    }
  }
}

TEST(GaussLegendre, NodesAreSymmetricAndAscending) {
  const GaussLegendreRule rule = gaussLegendreRule(7);
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(rule.nodes[i], -rule.nodes[6 - i], 1e-15);
    if (i > 0) {
      EXPECT_LT(rule.nodes[i - 1], rule.nodes[i]);
    }
  }
  EXPECT_NEAR(rule.nodes[3], 0.0, 1e-15);
}

TEST(GaussLegendre, IntegratesVectorValuedFunctions) {
  const GaussLegendreRule rule = gaussLegendreRule(20);
  const Eigen::Vector2d got = integrateGaussLegendre(rule, 0.0, std::numbers::pi, [](double t) {
    return Eigen::Vector2d(std::cos(t), std::sin(t));
  });
  EXPECT_NEAR(got.x(), 0.0, 1e-14);
  EXPECT_NEAR(got.y(), 2.0, 1e-14);
}

TEST(GaussLegendre, RejectsZeroPoints) { EXPECT_THROW(gaussLegendreRule(0), std::invalid_argument); }

}  // namespace
}  // namespace ffdkit::geometry
