#include "ffdkit/geometry/quaternion/bezier_qi_segment.h"

#include <cmath>

#include <gtest/gtest.h>

#include "ffdkit/geometry/quaternion/unit_quaternion.h"

namespace ffdkit::geometry::quaternion {
namespace {

// A twisted, non-planar segment: every derivative in the formulas is non-zero.
BezierQiSegment twistedSegment() {
  return BezierQiSegment(Eigen::Vector3d(0.5, -1.0, 2.0), 1.7, {0.3, 1.1, 0.4}, {0.5, 0.2, 0.9});
}

TEST(BezierQiSegment, TangentIsUnitAndEqualsRotatedXAxis) {
  const BezierQiSegment seg = twistedSegment();
  for (int k = 0; k <= 100; ++k) {
    const double t = k / 100.0;
    const Eigen::Quaterniond q = seg.quaternion(t);
    EXPECT_NEAR(seg.tangent(t).norm(), 1.0, 1e-14);
    EXPECT_LE((seg.tangent(t) - rotateFixedVector(q, Eigen::Vector3d::UnitX())).norm(), 1e-14);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
    EXPECT_NEAR(q.x(), 0.0, 1e-15);  // q(t) lies on the great 2-sphere x = 0 (Miura 1998, sec. 3.3)
  }
}

TEST(BezierQiSegment, OmegaEqualsConjugateTimesDerivative) {
  // Property 3: the corrected eq. (68) equals q^-1 q' from central differences.
  const BezierQiSegment seg = twistedSegment();
  const double h = 1e-5;
  for (double t : {0.05, 0.3, 0.62, 0.95}) {
    const Eigen::Vector4d dq = (seg.quaternion(t + h).coeffs() - seg.quaternion(t - h).coeffs()) / (2 * h);
    const Eigen::Quaterniond qdot(dq[3], dq[0], dq[1], dq[2]);
    const Eigen::Quaterniond w = seg.quaternion(t).conjugate() * qdot;
    EXPECT_NEAR(w.w(), 0.0, 1e-7);
    EXPECT_LE((w.vec() - seg.omega(t)).norm(), 1e-7) << "t " << t;
  }
}

TEST(BezierQiSegment, CurvatureMatchesBracketFormAndFiniteDifferences) {
  const BezierQiSegment seg = twistedSegment();
  const double l = seg.length();
  const double h = 1e-5;
  for (double t : {0.05, 0.3, 0.62, 0.95}) {
    const double kappa = seg.curvature(t);
    // kappa = 2 |[omega_s, e_x]| with omega_s = omega / l (eq. 28).
    EXPECT_NEAR(kappa, 2.0 * seg.omega(t).cross(Eigen::Vector3d::UnitX()).norm() / l, 1e-12 * kappa);
    const Eigen::Vector3d dTds = (seg.tangent(t + h) - seg.tangent(t - h)) / (2 * h * l);
    EXPECT_NEAR(kappa, dTds.norm(), 1e-6 * kappa);
    EXPECT_LE((seg.curvatureVector(t) - dTds).norm(), 1e-6 * kappa);
    // d kappa / ds
    const double mu = (seg.curvature(t + h) - seg.curvature(t - h)) / (2 * h * l);
    EXPECT_NEAR(seg.curvatureDerivative(t), mu, 1e-6 * std::max(1.0, std::abs(mu)));
    // torsion = det(T, T', T'') / |T'|^2 with T' = curvatureVector, T'' by central differences.
    const Eigen::Vector3d k1 = seg.curvatureVector(t);
    const Eigen::Vector3d k2 = (seg.curvatureVector(t + h) - seg.curvatureVector(t - h)) / (2 * h * l);
    const double tau = seg.tangent(t).dot(k1.cross(k2)) / k1.squaredNorm();
    EXPECT_NEAR(seg.torsion(t), tau, 1e-6 * std::max(1.0, std::abs(tau))) << "t " << t;
  }
}

TEST(BezierQiSegment, AnglesFromTangentInvertTheClosedForm) {
  for (double a : {-2.0, 0.3, 1.4, 3.0}) {
    for (double b : {0.1, 0.7, 1.3}) {
      const Eigen::Vector3d t = qiTangentFromAngles(a, b);
      const QiAngles back = qiAnglesFromTangent(t);
      EXPECT_LE((qiTangentFromAngles(back.alpha, back.beta) - t).norm(), 1e-14);
      const QiAngles near = nearestEquivalentAngles(back, {a + 0.01, b - 0.01});
      EXPECT_NEAR(near.alpha, a, 1e-12);
      EXPECT_NEAR(near.beta, b, 1e-12);
    }
  }
}

TEST(BezierQiSegment, ConstantBetaAndLinearAlphaGiveAHelix) {
  // Miura 1998, sec. 3.3, special case: kappa = |a'| sin 2b / l, tau = a' cos 2b / l.
  const double gamma = 1.0, k = 0.8;
  const BezierQiSegment seg(Eigen::Vector3d::Zero(), 1.0, {0.0, k / 2, k}, {gamma / 2, gamma / 2, gamma / 2});
  for (double t : {0.0, 0.4, 1.0}) {
    EXPECT_NEAR(seg.curvature(t), k * std::sin(gamma), 1e-14);
    EXPECT_NEAR(seg.torsion(t), k * std::cos(gamma), 1e-14);
  }
}

TEST(BezierQiSegment, RejectsNonPositiveLength) {
  EXPECT_THROW(BezierQiSegment(Eigen::Vector3d::Zero(), 0.0, {0, 0, 0}, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(BezierQiSegment(Eigen::Vector3d::Zero(), 1.0, {0, 0, 0}, {0, 0, 0}, 7), std::invalid_argument);
}

}  // namespace
}  // namespace ffdkit::geometry::quaternion
