#include "ffdkit/geometry/g3/bohm_conversion.h"

#include <gtest/gtest.h>

#include "g3_test_data.h"

namespace ffdkit::geometry::g3 {
namespace {

TEST(BohmConversion, SingleSpanUsesTheInnerDeBoorOrdinatesAsBezierOrdinates) {
  Eigen::VectorXd ds(1);
  ds << 2.5;
  Eigen::VectorXd d(4);
  d << 0.1, 0.4, -0.2, 0.7;
  const Eigen::VectorXd b = bezierOrdinatesFromDeBoor(ds, d);
  ASSERT_EQ(b.size(), 4);
  EXPECT_EQ(b[0], 0.1);
  EXPECT_EQ(b[1], 0.4);
  EXPECT_EQ(b[2], -0.2);
  EXPECT_EQ(b[3], 0.7);
}

TEST(BohmConversion, BezierOrdinatesOfAGlobalCubicAreItsBlossomValues) {
  const Eigen::VectorXd knots = testdata::s1Knots();
  const Eigen::Vector4d c(0.3, -0.25, 0.03, -0.001);
  const Eigen::VectorXd d = testdata::cubicDeBoor(c, knots);
  const int n = static_cast<int>(knots.size()) - 1;
  const Eigen::VectorXd ds = knots.tail(n) - knots.head(n);
  const Eigen::VectorXd b = bezierOrdinatesFromDeBoor(ds, d);
  auto blossom = [&](double u1, double u2, double u3) {
    return c[0] + c[1] * (u1 + u2 + u3) / 3.0 + c[2] * (u1 * u2 + u1 * u3 + u2 * u3) / 3.0 + c[3] * u1 * u2 * u3;
  };
  for (int i = 0; i < n; ++i) {
    const double a = knots[i], e = knots[i + 1];
    EXPECT_NEAR(b[3 * i], blossom(a, a, a), 1e-14) << i;
    EXPECT_NEAR(b[3 * i + 1], blossom(a, a, e), 1e-14) << i;
    EXPECT_NEAR(b[3 * i + 2], blossom(a, e, e), 1e-14) << i;
  }
  EXPECT_NEAR(b[3 * n], blossom(10, 10, 10), 1e-14);
}

TEST(BohmConversion, AnalyticJacobianMatchesCentralDifferences) {
  for (int n : {1, 2, 3, 6}) {
    Eigen::VectorXd ds(n), d(n + 3);
    for (int i = 0; i < n; ++i) ds[i] = 1.0 + 0.37 * i + 0.1 * (i % 2);
    for (int j = 0; j < n + 3; ++j) d[j] = 0.3 * std::sin(1.7 * j) - 0.2 * j;
    const Eigen::MatrixXd jac = bezierOrdinateJacobian(ds, d);
    ASSERT_EQ(jac.rows(), 3 * n + 1);
    ASSERT_EQ(jac.cols(), 2 * n + 3);
    Eigen::VectorXd v(2 * n + 3);
    v << ds, d;
    for (int j = 0; j < 2 * n + 3; ++j) {
      const double h = 1e-6 * (1.0 + std::abs(v[j]));
      Eigen::VectorXd vp = v, vm = v;
      vp[j] += h;
      vm[j] -= h;
      const Eigen::VectorXd fd = (bezierOrdinatesFromDeBoor(vp.head(n), vp.tail(n + 3)) -
                                  bezierOrdinatesFromDeBoor(vm.head(n), vm.tail(n + 3))) /
                                 (2.0 * h);
      EXPECT_LE((fd - jac.col(j)).cwiseAbs().maxCoeff(), 1e-8) << "n " << n << " column " << j;
    }
  }
}

}  // namespace
}  // namespace ffdkit::geometry::g3
