#include "ffdkit/geometry/quaternion/qi_chain.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "ffdkit/geometry/quaternion/unit_quaternion.h"
#include "qi_fit_datasets.h"

namespace ffdkit::geometry::quaternion {
namespace {

QiChainSegment twisted(QiQuadrature quad = {}) {
  return QiChainSegment(Eigen::Vector3d(1, 2, 3), quaternionExp(Eigen::Vector3d(0.1, -0.2, 0.3)),
                        {{0.9, -0.4, 1.1}, {-0.7, 1.2, 0.5}}, 7.0, ProductForm::Global, Eigen::Vector3d::UnitX(), quad);
}

TEST(CumulativeBezierQuaternion, StaysUnitForLargeOmegas) {
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<Eigen::Vector3d> w;
    for (int j = 0; j < 3; ++j) {
      Eigen::Vector3d v(d(gen), d(gen), d(gen));
      w.push_back(v.normalized() * 10.0 * std::abs(d(gen)));
    }
    for (ProductForm form : {ProductForm::Global, ProductForm::Local}) {
      const CumulativeBezierQuaternion q(quaternionExp(Eigen::Vector3d(0.2, 0.1, -0.4)), w, form);
      for (int k = 0; k < 100; ++k) {
        EXPECT_NEAR(q.value(std::abs(d(gen))).norm(), 1.0, 1e-12);
      }
    }
  }
}

TEST(CumulativeBezierQuaternion, EndpointsAreFirstAndLastControl) {
  const Eigen::Quaterniond q0 = quaternionExp(Eigen::Vector3d(0.3, 0.0, 0.1));
  const std::vector<Eigen::Vector3d> w = {{0.2, 0.5, -0.1}, {-0.3, 0.1, 0.4}};
  const CumulativeBezierQuaternion a(q0, w, ProductForm::Global);
  EXPECT_LE((a.value(0.0).coeffs() - q0.coeffs()).norm(), 1e-15);
  const Eigen::Quaterniond endA = quaternionExp(w[1]) * quaternionExp(w[0]) * q0;
  EXPECT_LE((a.value(1.0).coeffs() - endA.coeffs()).norm(), 1e-14);
  const CumulativeBezierQuaternion b(q0, w, ProductForm::Local);
  const Eigen::Quaterniond endB = q0 * quaternionExp(w[0]) * quaternionExp(w[1]);
  EXPECT_LE((b.value(1.0).coeffs() - endB.coeffs()).norm(), 1e-14);
}

TEST(CumulativeBezierQuaternion, AnalyticDerivativeMatchesCentralDifference) {
  const std::vector<Eigen::Vector3d> w = {{0.2, 0.5, -0.1}, {-0.3, 0.1, 0.4}, {0.6, -0.2, 0.3}};
  for (ProductForm form : {ProductForm::Global, ProductForm::Local}) {
    const CumulativeBezierQuaternion q(quaternionExp(Eigen::Vector3d(0.3, 0.0, 0.1)), w, form);
    const double h = 1e-6;
    for (double t : {0.0 + 2e-6, 0.3, 0.77, 1.0 - 2e-6}) {
      const Eigen::Vector4d fd = (q.value(t + h).coeffs() - q.value(t - h).coeffs()) / (2 * h);
      EXPECT_LE((q.derivative(t).coeffs() - fd).norm(), 1e-8);
    }
  }
}

TEST(QiChainSegment, ClosedFormsOfLineCircleAndHelix) {
  const double l = 5.0;
  // omega = 0: straight segment.
  const QiChainSegment line(Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(), {{0, 0, 0}, {0, 0, 0}}, l);
  EXPECT_LE((line.point(0.6) - Eigen::Vector3d(0.6 * l, 0, 0)).norm(), 1e-12 * l);
  // k = 1, phi: circle of radius l / (2 phi); k = 2 with phi1 = phi2: radius l / (4 phi).
  const double phi = 0.4;
  const QiChainSegment arc1(Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(), {{0, 0, phi}}, l);
  const QiChainSegment arc2(Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(), {{0, 0, phi}, {0, 0, phi}}, l);
  for (const auto& [seg, radius] : {std::pair{&arc1, l / (2 * phi)}, std::pair{&arc2, l / (4 * phi)}}) {
    const double turn = l / radius;
    const Eigen::Vector3d expected(radius * std::sin(turn), radius * (1 - std::cos(turn)), 0.0);
    EXPECT_LE((seg->point(1.0) - expected).norm(), 1e-12 * l);
    EXPECT_NEAR(seg->curvature(0.3), 1.0 / radius, 1e-14);
  }
  // k = 1, omega not perpendicular to t0: helix with kappa = 0.16.
  const QiChainSegment helix(Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(), {{0.3, 0, 0.4}}, l);
  for (double u : {0.0, 0.5, 1.0}) EXPECT_NEAR(helix.curvature(u), 0.16, 1e-14);
  // Planar k = 2: kappa(u) = (4 phi1 (1-u) + 4 phi2 u) / l, 0.16 .. 0.72.
  const QiChainSegment clothoid(Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(), {{0, 0, 0.2}, {0, 0, 0.9}}, l);
  for (double u : {0.0, 0.25, 0.5, 1.0}) {
    EXPECT_NEAR(clothoid.signedPlanarCurvature(u), (0.8 * (1 - u) + 3.6 * u) / l, 1e-14);
  }
}

TEST(QiChainSegment, CurvatureAndTorsionMatchFiniteDifferences) {
  const QiChainSegment seg = twisted();
  const double l = seg.length(), h = 1e-5;
  for (double u : {0.1, 0.45, 0.9}) {
    const Eigen::Vector3d d1 = (seg.tangent(u + h) - seg.tangent(u - h)) / (2 * h);
    EXPECT_NEAR(seg.curvature(u), d1.norm() / l, 1e-6 * seg.curvature(u));
    const Eigen::Vector3d pp = seg.point(u + h), pm = seg.point(u - h);
    EXPECT_NEAR((pp - pm).norm() / (2 * h * l), 1.0, 1e-7);  // speed 1 in arc length
  }
}

TEST(QiChainSegment, QuadratureConvergesOnATwistedSegment) {
  // Property 9: GL-8 on 8 panels vs GL-20 on 256 panels, <= 1e-12 l.
  const QiChainSegment coarse = twisted({8, 8});
  const QiChainSegment fine = twisted({20, 256});
  for (double u : {0.3, 0.5, 1.0}) {
    EXPECT_LE((coarse.point(u) - fine.point(u)).norm(), 1e-12 * coarse.length());
  }
}

TEST(QiChainSegment, PolylineLengthEqualsSegmentLength) {
  const QiChainSegment seg = twisted();
  const Eigen::MatrixX3d p = seg.points(Eigen::VectorXd::LinSpaced(10000, 0.0, 1.0));
  double poly = 0.0;
  for (Eigen::Index i = 1; i < p.rows(); ++i) poly += (p.row(i) - p.row(i - 1)).norm();
  EXPECT_NEAR(poly / seg.length(), 1.0, 1e-7);
}

TEST(QiChain, JoinsAreG0AndG1ButNotG2) {
  const QiChain c = testdata::chain3dTruth();
  const double total = c.length();
  for (int i = 0; i + 1 < c.segmentCount(); ++i) {
    // End point recomputed independently with a much finer rule.
    const QiChainSegment& s = c.segment(i);
    const QiChainSegment fine(s.start(), s.orientation(0.0), s.omegas(), s.length(), ProductForm::Global,
                              Eigen::Vector3d::UnitX(), {20, 64});
    EXPECT_LE((fine.point(1.0) - c.segment(i + 1).start()).norm(), 1e-12 * total);
    EXPECT_LE(angleBetween(s.tangent(1.0), c.segment(i + 1).tangent(0.0)), 1e-12);
  }
  const QiChain planar = testdata::chain2dTruth();
  const double jump = std::abs(planar.segment(0).signedPlanarCurvature(1.0) - planar.segment(1).signedPlanarCurvature(0.0));
  EXPECT_NEAR(jump, std::abs(4 * 0.35 / 100 - 4 * 0.30 / 120), 1e-12);
}

TEST(QiChain, SyntheticDatasetsMatchSpecChecksums) {
  const testdata::FitDataset c2 = testdata::chain2d();
  EXPECT_LE((c2.points.row(1) - Eigen::RowVector3d(6.399214, 0.086284, 0)).norm(), 2e-6);
  EXPECT_LE((c2.points.row(30) - Eigen::RowVector3d(224.31398, 167.788124, 0)).norm(), 2e-5);
  EXPECT_NEAR(c2.points.sum(), 5997.321998, 1e-5);
  EXPECT_NEAR(testdata::chain2dNoisy().points.sum(), 5998.202014, 1e-5);
  EXPECT_LE((testdata::chain2dNoisy().points.row(0) - Eigen::RowVector3d(0.264044, 0.77146, 0)).norm(), 2e-6);
  const testdata::FitDataset c3 = testdata::chain3d();
  EXPECT_LE((c3.points.row(1) - Eigen::RowVector3d(2.536571, 1.78223, -0.009982)).norm(), 2e-6);
  EXPECT_LE((c3.points.row(69) - Eigen::RowVector3d(50.194655, 271.376931, 49.08238)).norm(), 2e-5);
  EXPECT_NEAR(c3.points.sum(), 12736.535979, 1e-5);
  EXPECT_NEAR(testdata::chain3dNoisy().points.sum(), 12738.409651, 1e-5);
  const testdata::FitDataset sn = testdata::sineNoisy();
  EXPECT_LE((sn.points.row(0) - Eigen::RowVector3d(1.148853, 1.043328, 0)).norm(), 2e-6);
  EXPECT_LE((sn.points.row(1) - Eigen::RowVector3d(6.839346, 6.289369, 0)).norm(), 2e-6);
  EXPECT_NEAR(sn.points.sum(), 3419.866494, 1e-5);
  const Eigen::MatrixX3d sp = testdata::spiral(6).points;
  double poly = 0.0;
  for (Eigen::Index i = 1; i < sp.rows(); ++i) poly += (sp.row(i) - sp.row(i - 1)).norm();
  EXPECT_NEAR(poly, 344.132897, 1e-6);
  std::mt19937 gen(5489);
  std::uint32_t v = 0;
  for (int i = 0; i < 10000; ++i) v = gen();
  EXPECT_EQ(v, 4123659995u);
}

}  // namespace
}  // namespace ffdkit::geometry::quaternion
