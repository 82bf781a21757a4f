#include "ffdkit/geometry/g3/quadratic_curvature_spline.h"

#include <cmath>

#include <gtest/gtest.h>

#include "ffdkit/geometry/g3/g3_error.h"
#include "g3_test_data.h"

namespace ffdkit::geometry::g3 {
namespace {

QuadraticCurvatureSpline s1Curve() {
  const Eigen::VectorXd knots = testdata::s1Knots();
  const int n = static_cast<int>(knots.size()) - 1;
  const Eigen::VectorXd d = testdata::cubicDeBoor({0.3, -0.25, 0.03, -0.001}, knots);
  return QuadraticCurvatureSpline::fromStartPoint({1.0, 2.0}, knots.tail(n) - knots.head(n), d);
}

TEST(QuadraticCurvatureSpline, ReproducesAKnownCubicTangentAngleExactly) {
  const QuadraticCurvatureSpline curve = s1Curve();
  const Eigen::MatrixX2d expected = testdata::s1Points();
  EXPECT_NEAR(curve.length(), 10.0, 1e-15);
  for (int i = 0; i < expected.rows(); ++i) {
    const double s = testdata::s1Knots()[i];
    EXPECT_LE((curve.position(s) - expected.row(i).transpose()).norm(), 1e-11) << i;
  }
  for (double s = 0.0; s <= 10.0; s += 0.37) {
    EXPECT_NEAR(curve.tangentAngle(s), testdata::s1Angle(s), 1e-13) << s;
    EXPECT_NEAR(curve.curvature(s), testdata::s1Curvature(s), 1e-13) << s;
    EXPECT_NEAR(curve.curvatureDerivative(s), testdata::s1CurvatureDerivative(s), 1e-13) << s;
    EXPECT_NEAR(curve.curvatureSecondDerivative(s), -0.006, 1e-13) << s;
  }
}

TEST(QuadraticCurvatureSpline, ReproducesACircleWhenTheAngleIsLinear) {
  const double radius = 5.0;
  Eigen::VectorXd knots(5);
  knots << 0, 2, 5.5, 7.5, 11.5;
  const Eigen::VectorXd d = testdata::cubicDeBoor({0.0, 1.0 / radius, 0.0, 0.0}, knots);
  const QuadraticCurvatureSpline curve =
      QuadraticCurvatureSpline::fromStartPoint({0.0, 0.0}, knots.tail(4) - knots.head(4), d);
  for (double s = 0.0; s <= curve.length(); s += 0.25) {
    const double a = s / radius;
    EXPECT_LE((curve.position(s) - Eigen::Vector2d(radius * std::sin(a), radius * (1.0 - std::cos(a)))).norm(), 1e-13);
    EXPECT_NEAR(curve.curvature(s), 0.2, 1e-14);
    EXPECT_NEAR(curve.curvatureDerivative(s), 0.0, 1e-14);
  }
}

TEST(QuadraticCurvatureSpline, ReproducesAStraightLineWhenAllOrdinatesAreEqual) {
  Eigen::VectorXd ds(3);
  ds << 1.0, 2.5, 0.5;
  const double angle = 0.7;
  const Eigen::VectorXd d = Eigen::VectorXd::Constant(6, angle);
  const QuadraticCurvatureSpline curve = QuadraticCurvatureSpline::fromStartPoint({-1.0, 3.0}, ds, d);
  for (double s = 0.0; s <= 4.0; s += 0.3) {
    const Eigen::Vector2d expected = Eigen::Vector2d(-1.0, 3.0) + s * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    EXPECT_LE((curve.position(s) - expected).norm(), 1e-14);
    EXPECT_NEAR(curve.curvature(s), 0.0, 1e-14);
  }
}

// Spec sec. 7 properties 2-5 hold by construction for any ordinates and span lengths.
TEST(QuadraticCurvatureSpline, IsG3ContinuousAtEveryKnotForArbitraryOrdinates) {
  Eigen::VectorXd ds(6), d(9);
  ds << 1.2, 3.1, 0.4, 2.2, 5.0, 1.7;
  d << 0.2, -0.5, 1.3, 2.9, -1.1, 0.4, 3.3, -6.0, 1.0;
  const QuadraticCurvatureSpline curve = QuadraticCurvatureSpline::fromStartPoint({0.0, 0.0}, ds, d);
  double kappaMax = 0.0, dkappaMax = 0.0;
  for (int i = 0; i < 6; ++i) {
    for (int k = 0; k <= 10; ++k) {
      const double s = curve.knots()[i] + 0.1 * k * ds[i];
      kappaMax = std::max(kappaMax, std::abs(curve.curvature(s)));
      dkappaMax = std::max(dkappaMax, std::abs(curve.curvatureDerivative(s)));
    }
  }
  const Eigen::VectorXd& b = curve.bezierOrdinates();
  for (int i = 1; i < 6; ++i) {
    const Eigen::Vector3d left = curve.curvatureQuadratic(i - 1);
    const Eigen::Vector3d right = curve.curvatureQuadratic(i);
    const double dl = ds[i - 1];
    // Tangent: span i-1 ends at its last Bezier ordinate, which span i starts from.
    const double psiLeft = b[3 * i];
    EXPECT_LE(std::abs(psiLeft - curve.tangentAngle(curve.knots()[i])), 1e-14 * (1.0 + std::abs(psiLeft)));
    const double kappaLeft = left[0] + dl * (left[1] + dl * left[2]);
    EXPECT_LE(std::abs(kappaLeft - right[0]), 1e-12 * (1.0 + kappaMax)) << i;
    const double dkappaLeft = left[1] + 2.0 * dl * left[2];
    EXPECT_LE(std::abs(dkappaLeft - right[1]), 1e-10 * (1.0 + dkappaMax)) << i;
  }
  // Quadratic per span: third differences of kappa at 6 equidistant samples vanish.
  for (int i = 0; i < 6; ++i) {
    double values[6];
    for (int k = 0; k < 6; ++k) values[k] = curve.curvature(curve.knots()[i] + ds[i] * k / 5.0);
    for (int k = 0; k + 3 < 6; ++k) {
      const double third = values[k + 3] - 3 * values[k + 2] + 3 * values[k + 1] - values[k];
      EXPECT_LE(std::abs(third), 1e-10 * (1.0 + kappaMax)) << i;
    }
  }
}

TEST(QuadraticCurvatureSpline, SamplesAgreeWithPointwiseEvaluation) {
  const QuadraticCurvatureSpline curve = s1Curve();
  const CurveSamples samples = curve.sample(8);
  ASSERT_EQ(samples.arcLength.size(), 6 * 8 + 1);
  for (Eigen::Index k = 0; k < samples.arcLength.size(); ++k) {
    const double s = samples.arcLength[k];
    EXPECT_LE((samples.points.row(k).transpose() - curve.position(s)).norm(), 1e-12) << k;
    EXPECT_NEAR(samples.tangentAngle[k], testdata::s1Angle(s), 1e-13);
    EXPECT_NEAR(samples.curvature[k], testdata::s1Curvature(s), 1e-13);
    EXPECT_NEAR(samples.curvatureDerivative[k], testdata::s1CurvatureDerivative(s), 1e-13);
  }
  EXPECT_EQ(samples.arcLength[samples.arcLength.size() - 1], curve.length());
}

TEST(QuadraticCurvatureSpline, RejectsMismatchedSizesAndNonPositiveSpans) {
  Eigen::VectorXd ds(2), d(4);
  ds << 1.0, 2.0;
  d.setZero();
  EXPECT_THROW(QuadraticCurvatureSpline::fromStartPoint({0, 0}, ds, d), G3InputError);
  Eigen::VectorXd d5 = Eigen::VectorXd::Zero(5);
  ds[1] = 0.0;
  EXPECT_THROW(QuadraticCurvatureSpline::fromStartPoint({0, 0}, ds, d5), G3InputError);
  ds[1] = 2.0;
  const QuadraticCurvatureSpline curve = QuadraticCurvatureSpline::fromStartPoint({0, 0}, ds, d5);
  EXPECT_THROW(curve.position(3.5), G3InputError);
  EXPECT_THROW(curve.sample(0), G3InputError);
  EXPECT_THROW(QuadraticCurvatureSpline::fromSpanStarts(Eigen::MatrixX2d::Zero(2, 2), ds, d5), G3InputError);
}

}  // namespace
}  // namespace ffdkit::geometry::g3
