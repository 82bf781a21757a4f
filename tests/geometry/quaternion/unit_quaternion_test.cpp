#include "ffdkit/geometry/quaternion/unit_quaternion.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "ffdkit/geometry/quaternion/bernstein.h"
#include "ffdkit/geometry/quaternion/quaternion_error.h"
#include "ffdkit/geometry/quaternion/tangent_integration.h"

namespace ffdkit::geometry::quaternion {
namespace {

TEST(UnitQuaternion, LogInvertsExpBelowHalfPi) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    Eigen::Vector3d v(dist(gen), dist(gen), dist(gen));
    v *= (M_PI / 2 - 1e-6) * std::abs(dist(gen)) / v.norm();
    EXPECT_LE((quaternionLog(quaternionExp(v)) - v).norm(), 1e-13);
  }
}

TEST(UnitQuaternion, ExpRotatesByTwiceTheVectorNorm) {
  const Eigen::Vector3d v(0.3, -0.2, 0.5);
  const Eigen::Quaterniond q = quaternionExp(v);
  const Eigen::Matrix3d expected = Eigen::AngleAxisd(2.0 * v.norm(), v.normalized()).toRotationMatrix();
  EXPECT_LE((q.toRotationMatrix() - expected).norm(), 1e-14);
  EXPECT_NEAR(q.norm(), 1.0, 1e-15);
  const Eigen::Vector3d p(0.4, 1.1, -0.7);
  EXPECT_LE((rotateFixedVector(q, p) - expected * p).norm(), 1e-14);
}

TEST(UnitQuaternion, ExpAndLogAreSmoothAtZero) {
  EXPECT_LE((quaternionExp(Eigen::Vector3d::Zero()).coeffs() - Eigen::Quaterniond::Identity().coeffs()).norm(), 0.0);
  const Eigen::Vector3d tiny(1e-10, -2e-10, 3e-10);
  EXPECT_LE((quaternionLog(quaternionExp(tiny)) - tiny).norm(), 1e-24);
}

TEST(UnitQuaternion, LogKeepsTheSignOfW) {
  // -q is the opposite tangent for pure controls (Sphere-tangent report, sec. 3.2): no hemisphere flip.
  const Eigen::Quaterniond q(-0.6, 0.8, 0.0, 0.0);
  EXPECT_NEAR(quaternionLog(q).x(), std::atan2(0.8, -0.6), 1e-15);
  EXPECT_THROW(quaternionLog(Eigen::Quaterniond(-1.0, 0.0, 0.0, 0.0)), QuaternionCurveError);
}

TEST(UnitQuaternion, SlerpSphereMidpointAvoidsEigenNegation) {
  // Case R9: Eigen's slerp would give (0.894, -0.447, 0).
  const Eigen::Vector3d m = slerpSphere(Eigen::Vector3d::UnitX(), Eigen::Vector3d(-0.6, 0.8, 0.0), 0.5);
  EXPECT_LE((m - Eigen::Vector3d(0.4472135955, 0.8944271910, 0.0)).norm(), 1e-10);
  EXPECT_THROW(slerpSphere(Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(), 0.5), QuaternionCurveError);
}

TEST(UnitQuaternion, MinimalRotationMapsFromToTo) {
  const Eigen::Vector3d from = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d to = Eigen::Vector3d(0.2, -0.5, 0.8).normalized();
  EXPECT_LE((rotateFixedVector(minimalRotation(from, to), from) - to).norm(), 1e-15);
  EXPECT_LE((rotateFixedVector(minimalRotation(from, -from), from) + from).norm(), 1e-15);
}

TEST(Bernstein, CumulativeBasisHasUnitEndValuesAndDerivative) {
  for (int n = 1; n <= 5; ++n) {
    EXPECT_DOUBLE_EQ(cumulativeBernstein(n, 0, 0.3), 1.0);
    for (int i = 1; i <= n; ++i) {
      EXPECT_NEAR(cumulativeBernstein(n, i, 0.0), 0.0, 1e-15);
      EXPECT_NEAR(cumulativeBernstein(n, i, 1.0), 1.0, 1e-15);
      const double h = 1e-6, t = 0.37;
      const double fd = (cumulativeBernstein(n, i, t + h) - cumulativeBernstein(n, i, t - h)) / (2 * h);
      EXPECT_NEAR(cumulativeBernsteinDerivative(n, i, t), fd, 1e-8);
    }
  }
}

TEST(TangentIntegration, SimpsonRejectsOddIntervalsAndIntegratesCubicsExactly) {
  const auto f = [](double t) { return Eigen::Vector3d(t * t * t, 1.0, t); };
  EXPECT_LE((integrateSimpson(f, 0.0, 1.0, 2) - Eigen::Vector3d(0.25, 1.0, 0.5)).norm(), 1e-15);
  EXPECT_THROW(integrateSimpson(f, 0.0, 1.0, 3), QuaternionCurveError);
}

TEST(TangentIntegration, CumulativeGaussLegendreMatchesClosedForm) {
  const auto f = [](double t) { return Eigen::Vector3d(std::cos(3 * t), std::sin(3 * t), 1.0); };
  Eigen::VectorXd params(4);
  params << 0.0, 0.21, 0.5, 1.0;
  const Eigen::MatrixX3d c = cumulativeGaussLegendre(f, params, 8, 8);
  for (int k = 0; k < 4; ++k) {
    const double t = params[k];
    EXPECT_NEAR(c(k, 0), std::sin(3 * t) / 3, 1e-15);
    EXPECT_NEAR(c(k, 1), (1 - std::cos(3 * t)) / 3, 1e-15);
    EXPECT_NEAR(c(k, 2), t, 1e-15);
  }
}

}  // namespace
}  // namespace ffdkit::geometry::quaternion
