#include "ffdkit/geometry/cardinal/s_spline_basis.h"

#include <cmath>

#include <gtest/gtest.h>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

namespace ffdkit::geometry::cardinal {
namespace {

TEST(SSplineCoefficients, ReproduceTable3_1) {
  // Kuriyama 1996, Table 3-1 (sec. 3.2.3), printed to 6 decimals.
  const double beta2[4] = {0.0, 5.0, 25.0, 100.0};
  const double table[4][5] = {
      {1.732051, -0.464102, 0.124356, -0.033321, 0.008928},
      {1.374369, -0.216698, 0.034167, -0.005387, 0.000849},
      {1.129541, -0.068710, 0.004180, -0.000254, 0.000015},
      {1.037749, -0.019224, 0.000356, -0.000007, 0.000000},
  };
  for (int r = 0; r < 4; ++r) {
    const Eigen::VectorXd c = sSplineCoefficients(beta2[r], 4);
    ASSERT_EQ(c.size(), 5);
    for (int i = 0; i < 5; ++i) {
      EXPECT_NEAR(c[i], table[r][i], 5e-7) << "beta2 = " << beta2[r] << ", c_" << i;
    }
  }
}

TEST(SSplineCoefficients, CubicClosedForm) {
  const Eigen::VectorXd c = sSplineCoefficients(0.0, 6);
  for (int i = 0; i <= 6; ++i) {
    EXPECT_NEAR(c[i], std::sqrt(3.0) * std::pow(-2.0 + std::sqrt(3.0), i), 1e-14);
  }
}

TEST(SSplineCoefficients, RejectsNegativeTensionAndZeroWidth) {
  EXPECT_THROW(sSplineCoefficients(-1.0, 4), CardinalSplineError);
  EXPECT_THROW(sSplineCoefficients(0.0, 0), CardinalSplineError);
}

TEST(Beta2SplineBasis, ValuesSymmetryAndPartitionOfUnity) {
  for (double b : {0.0, 5.0, 25.0, 100.0}) {
    const double v = b + 12.0;
    EXPECT_NEAR(beta2SplineBasis(0.0, b), (b + 8.0) / v, 1e-15);
    EXPECT_NEAR(beta2SplineBasis(1.0, b), 2.0 / v, 1e-15);
    EXPECT_NEAR(beta2SplineBasis(1.0, b, 1), -6.0 / v, 1e-14);
    for (double x = -2.0; x <= 2.0; x += 0.125) {
      EXPECT_NEAR(beta2SplineBasis(x, b), beta2SplineBasis(-x, b), 1e-14);
    }
    for (double x = 0.0; x < 1.0; x += 0.1) {
      double sum = 0.0;
      for (int k = -2; k <= 2; ++k) sum += beta2SplineBasis(x - k, b);
      EXPECT_NEAR(sum, 1.0, 1e-14);
    }
  }
  // beta2 = 0 is the uniform cubic B-spline: B(0.5) = 23/48.
  EXPECT_NEAR(beta2SplineBasis(0.5, 0.0), 23.0 / 48.0, 1e-15);
}

TEST(Beta2SplineBasis, SecondDerivativeJumpsByBeta2TimesSlope) {
  // eq. (3.10): B''(k+) = B''(k-) + beta2 B'(k-) at every integer knot.
  const double b = 7.0;
  for (int k = -2; k <= 2; ++k) {
    const double left2 = beta2SplineBasis(k, b, 2, Limit::FromLeft);
    const double right2 = beta2SplineBasis(k, b, 2, Limit::FromRight);
    const double left1 = beta2SplineBasis(k, b, 1, Limit::FromLeft);
    const double right1 = beta2SplineBasis(k, b, 1, Limit::FromRight);
    EXPECT_NEAR(left1, right1, 1e-14) << "knot " << k;
    EXPECT_NEAR(right2, left2 + b * left1, 1e-13) << "knot " << k;
  }
}

TEST(SSplineBasis, CardinalAtKnotsAndFigureValues) {
  // Case T3 (Fig. 3-1/3-2, beta2 = 0, w = 4).
  const SSplineBasis s(0.0, 4);
  const double x[10] = {0, .25, .5, .75, 1, 1.5, 2, 2.5, 3, 3.5};
  const double expected[10] = {1, 0.881430, 0.600481, 0.269291, 0,
                               -0.127405, 0, 0.034138, 0, -0.009097};
  for (int k = 0; k < 10; ++k) EXPECT_NEAR(s.evaluate(x[k]), expected[k], 5e-7) << x[k];
  for (int j = -6; j <= 6; ++j) EXPECT_NEAR(s.evaluate(j), j == 0 ? 1.0 : 0.0, 1e-14) << j;
  // Case T4 (beta2 = 5, w = 4).
  const SSplineBasis s5(5.0, 4);
  const double x5[6] = {0, .5, 1, 1.5, 2, 2.5};
  const double e5[6] = {1, 0.559127, 0, -0.068449, 0, 0.010792};
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(s5.evaluate(x5[k]), e5[k], 5e-7) << x5[k];
}

TEST(SSplineBasis, TruncationJumpsMatchSpecTable) {
  // Prototype table, columns A (value just inside the cut) and B (slope there), 2 significant digits.
  struct Row { double beta2; int w; double a, b; };
  const Row rows[] = {{0, 4, 3.99e-4, 1.67e-2}, {5, 4, 1.6e-5, 1.9e-3},
                      {25, 3, -8.4e-7, -6.8e-4}, {100, 2, 1.2e-7, 1.0e-3}, {0, 3, -1.5e-3, -6.2e-2}};
  for (const Row& r : rows) {
    const SSplineBasis s(r.beta2, r.w);
    const double a = s.evaluate(r.w, 0, Limit::FromLeft);
    const double b = s.evaluate(r.w, 1, Limit::FromLeft);
    EXPECT_NEAR(a, r.a, 0.05 * std::abs(r.a)) << "beta2 " << r.beta2 << " w " << r.w;
    EXPECT_NEAR(b, r.b, 0.05 * std::abs(r.b)) << "beta2 " << r.beta2 << " w " << r.w;
    EXPECT_EQ(s.evaluate(r.w), 0.0);  // open support: exactly zero at the cut
    EXPECT_NEAR(s.evaluate(-r.w, 0, Limit::FromRight), a, 1e-15);  // symmetry
  }
}

TEST(SSplineCoefficientsOddDegree, CubicAgreesWithClosedForm) {
  const Eigen::VectorXd a = sSplineCoefficientsOddDegree(3, 6);
  const Eigen::VectorXd b = sSplineCoefficients(0.0, 6);
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(SSplineCoefficientsOddDegree, QuinticMatchesSpec) {
  // Prototype values (eqs. (3.4)-(3.9) of Kuriyama 1996, sec. 3.2.2): c_0..c_4 = 2.842171, -1.321729, 0.573326, -0.247042, 0.106378.
  const Eigen::VectorXd c = sSplineCoefficientsOddDegree(5, 4);
  const double expected[5] = {2.842171, -1.321729, 0.573326, -0.247042, 0.106378};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(c[i], expected[i], 5e-7) << i;
  // Knot values of the quintic B-spline: (1, 26, 66, 26, 1) / 120.
  const double v[5] = {1, 26, 66, 26, 1};
  for (int j = 1; j <= 5; ++j) EXPECT_NEAR(centredBSpline(j - 3.0, 5), v[j - 1] / 120.0, 1e-15);
}

TEST(SSplineBasis, QuinticIsCardinalAndSmoothInside) {
  const SSplineBasis s(0.0, 8, 5);
  for (int j = -10; j <= 10; ++j) EXPECT_NEAR(s.evaluate(j), j == 0 ? 1.0 : 0.0, 1e-13) << j;
  // Inside the support the quintic basis is C4: left and right second/third derivatives agree.
  for (int j = -6; j <= 6; ++j) {
    EXPECT_NEAR(s.evaluate(j, 3, Limit::FromLeft), s.evaluate(j, 3, Limit::FromRight), 1e-12) << j;
  }
  EXPECT_THROW(SSplineBasis(1.0, 4, 5), CardinalSplineError);
  EXPECT_THROW(SSplineBasis(0.0, 4, 4), CardinalSplineError);
}

TEST(SSplineBasis, CoefficientSumsAndUnclippedInterpolationErrorMatchSpecTable) {
  // Prototype table, columns D (sum of c_i over |i| <= w) and F (worst knot-interpolation error of
  // the unclipped variant).
  struct Row { double beta2; int w; double d, f; };
  const Row rows[] = {{0, 4, 1.003774, 1.5e-3}, {5, 4, 1.000231, 1.0e-4}, {25, 3, 0.999971, 1.4e-5},
                      {100, 2, 1.000013, 6.4e-6}, {0, 3, 0.985917, 5.6e-3}};
  for (const Row& r : rows) {
    const Eigen::VectorXd c = sSplineCoefficients(r.beta2, r.w);
    const double d = c[0] + 2.0 * c.tail(r.w).sum();
    EXPECT_NEAR(d, r.d, 5e-7) << r.beta2;
    const SSplineBasis unclipped(r.beta2, r.w, 3, false);
    double f = 0.0;
    for (int j = -r.w - 3; j <= r.w + 3; ++j) f = std::max(f, std::abs(unclipped.evaluate(j) - (j == 0)));
    EXPECT_NEAR(f, r.f, 0.05 * r.f) << r.beta2;
    // Unclipped: exactly C1 and G2-beta (no jumps at the former cut).
    EXPECT_NEAR(unclipped.evaluate(r.w, 1, Limit::FromLeft), unclipped.evaluate(r.w, 1, Limit::FromRight), 1e-15);
  }
}

TEST(SSplineBasis, IsEven) {
  const SSplineBasis s(25.0, 3);
  for (double x = 0.0; x < 3.0; x += 0.0625) EXPECT_NEAR(s.evaluate(x), s.evaluate(-x), 1e-14);
}

TEST(SSplineBasis, TangentFactorMatchesSpec) {
  // Kuriyama 1996, sec. 3.2.4, computed by the prototype: lambda_w = 0.646171, 0.410191, 0.171390, 0.055575.
  EXPECT_NEAR(SSplineBasis(0.0, 4).tangentFactor(), 0.646171, 5e-7);
  EXPECT_NEAR(SSplineBasis(5.0, 4).tangentFactor(), 0.410191, 5e-7);
  EXPECT_NEAR(SSplineBasis(25.0, 3).tangentFactor(), 0.171390, 5e-7);
  EXPECT_NEAR(SSplineBasis(100.0, 2).tangentFactor(), 0.055575, 5e-7);
}

}  // namespace
}  // namespace ffdkit::geometry::cardinal
