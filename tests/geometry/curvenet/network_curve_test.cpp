#include "ffdkit/geometry/curvenet/network_curve.h"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace ffdkit::geometry::curvenet {
namespace {

Eigen::MatrixX3d wavyPoints(int n) {
  Eigen::MatrixX3d p(n, 3);
  for (int k = 0; k < n; ++k) p.row(k) << 0.4 * k, std::sin(0.9 * k), 0.2 * k * k * 0.1;
  return p;
}

Eigen::MatrixX3d unitCircle(int n) {
  Eigen::MatrixX3d p(n, 3);
  for (int k = 0; k < n; ++k) {
    const double th = 2 * std::numbers::pi * k / n;
    p.row(k) << std::cos(th), std::sin(th), 0.0;
  }
  return p;
}

double jumpAtBreaks(const NetworkCurve& c, int derivative) {
  double jump = 0.0;
  for (std::size_t k = 0; k + 1 < c.segments().size(); ++k) {
    const double t = c.segments()[k].t1;
    const double h = 1e-9 * c.period();
    // Evaluate each side's polynomial at the breakpoint itself.
    const CurveSegment& left = c.segments()[k];
    Eigen::Vector3d fromLeft = Eigen::Vector3d::Zero();
    for (int j = derivative; j < left.coefficients.rows(); ++j) {
      double f = 1.0;
      for (int r = 0; r < derivative; ++r) f *= j - r;
      fromLeft += f * std::pow(t - left.t0, j - derivative) * left.coefficients.row(j).transpose();
    }
    (void)h;
    jump = std::max(jump, (fromLeft - c.evaluate(t, derivative)).norm());
  }
  return jump;
}

TEST(NetworkCurve, CubicSplineInterpolatesItsPointsAtChordLengthKnots) {
  const Eigen::MatrixX3d p = wavyPoints(7);
  const NetworkCurve c = interpolateCubicSpline(p, false);
  double t = 0.0;
  for (int k = 0; k < 7; ++k) {
    EXPECT_LE((c.evaluate(t) - p.row(k).transpose()).norm(), 1e-13);
    if (k < 6) t += (p.row(k + 1) - p.row(k)).norm();
  }
  EXPECT_NEAR(c.tMax(), t, 1e-13);
}

TEST(NetworkCurve, LongPenStrokeInterpolatesEveryPoint) {
  Eigen::MatrixX3d p(2000, 3);
  for (int k = 0; k < 2000; ++k) p.row(k) << std::cos(0.01 * k), std::sin(0.013 * k), 0.001 * k;
  const NetworkCurve c = interpolateCubicSpline(p, false);
  EXPECT_EQ(c.segments().size(), 1999u);
  for (int k = 0; k < 1999; k += 97) EXPECT_LE((c.evaluate(c.segments()[k].t0) - p.row(k).transpose()).norm(), 1e-12);
}

TEST(NetworkCurve, CubicSplineIsC2AtBreakpoints) {
  for (KnotSpacing s : {KnotSpacing::ChordLength, KnotSpacing::Centripetal, KnotSpacing::AffineInvariant}) {
    const NetworkCurve c = interpolateCubicSpline(wavyPoints(8), false, s);
    for (int d = 0; d <= 2; ++d) EXPECT_LE(jumpAtBreaks(c, d), 1e-10) << "derivative " << d;
  }
}

TEST(NetworkCurve, ClosedSplineIsPeriodicAndC2AcrossTheSeam) {
  const NetworkCurve c = interpolateCubicSpline(unitCircle(8), true);
  EXPECT_TRUE(c.closed());
  for (int d = 0; d <= 2; ++d) {
    EXPECT_LE((c.evaluate(c.tMin(), d) - c.evaluate(c.tMax() - 1e-12, d)).norm(), 1e-9) << d;
    EXPECT_LE((c.evaluate(0.3, d) - c.evaluate(0.3 + 2 * c.period(), d)).norm(), 1e-12);
    EXPECT_LE(jumpAtBreaks(c, d), 1e-10);
  }
  // 8 points on the unit circle: the spline stays close to it.
  for (int k = 0; k < 64; ++k) EXPECT_NEAR(c.evaluate(c.period() * k / 64.0).norm(), 1.0, 2e-3);
}

TEST(NetworkCurve, OpenCurveExtrapolatesWithItsEndPolynomial) {
  const NetworkCurve c = interpolateCubicSpline(wavyPoints(5), false);
  // Past the end the last segment continues: C^inf there, so a Taylor step matches.
  const double t = c.tMax(), h = 0.05;
  const Eigen::Vector3d taylor = c.evaluate(t) + h * c.evaluate(t, 1) + h * h / 2 * c.evaluate(t, 2) +
                                 h * h * h / 6 * c.evaluate(t, 3);
  EXPECT_LE((c.evaluate(t + h) - taylor).norm(), 1e-12);
}

TEST(NetworkCurve, BSplineSingleSpanIsTheBezierCurve) {
  Eigen::MatrixX3d ctrl(4, 3);
  ctrl << 0, 0, 0, 1, 2, 0, 3, 2, 1, 4, 0, 0;
  const NetworkCurve c = bsplineCurve(ctrl, 3, {0, 0, 0, 0, 1, 1, 1, 1}, false);
  for (double t : {0.0, 0.2, 0.5, 0.9, 1.0}) {
    const double s = 1 - t;
    const Eigen::Vector3d bez = s * s * s * ctrl.row(0).transpose() + 3 * s * s * t * ctrl.row(1).transpose() +
                                3 * s * t * t * ctrl.row(2).transpose() + t * t * t * ctrl.row(3).transpose();
    EXPECT_LE((c.evaluate(t) - bez).norm(), 1e-13);
  }
}

TEST(NetworkCurve, PeriodicBSplineIsClosedAndC2) {
  const NetworkCurve c = bsplineCurve(unitCircle(6), 3, {0, 1, 2, 3, 4, 5, 6}, true);
  EXPECT_LE((c.evaluate(0.0) - c.evaluate(6.0 - 1e-13)).norm(), 1e-10);
  for (int d = 0; d <= 2; ++d) EXPECT_LE(jumpAtBreaks(c, d), 1e-10);
  // Uniform cubic B-spline: C(k) = (P_{k-1} + 4 P_k + P_{k+1}) / 6 at the knots, shifted by the
  // periodic indexing (span k covers control points k..k+3).
  const Eigen::MatrixX3d p = unitCircle(6);
  const Eigen::Vector3d expected = (p.row(0) + 4 * p.row(1) + p.row(2)).transpose() / 6.0;
  EXPECT_LE((c.evaluate(0.0) - expected).norm(), 1e-12);
}

TEST(NetworkCurve, RejectsBadInputWithClearMessages) {
  EXPECT_THROW(interpolateCubicSpline(Eigen::MatrixX3d::Zero(1, 3), false), CurveInputError);
  Eigen::MatrixX3d dup(3, 3);
  dup << 0, 0, 0, 0, 0, 0, 1, 0, 0;
  try {
    interpolateCubicSpline(dup, false);
    FAIL();
  } catch (const CurveInputError& e) {
    EXPECT_NE(std::string(e.what()).find("points 0 and 1 coincide"), std::string::npos) << e.what();
  }
  EXPECT_THROW(bsplineCurve(unitCircle(4), 3, {0, 1, 2}, false), CurveInputError);
}

TEST(NetworkCurve, FitsThePlaneOfAPlanarCurveOnly) {
  const auto plane = fitCurvePlane(interpolateCubicSpline(unitCircle(8), true));
  ASSERT_TRUE(plane.has_value());
  EXPECT_NEAR(std::abs(plane->normal.z()), 1.0, 1e-12);
  Eigen::MatrixX3d helix(8, 3);
  for (int k = 0; k < 8; ++k) helix.row(k) << std::cos(k * 0.8), std::sin(k * 0.8), 0.3 * k;
  EXPECT_FALSE(fitCurvePlane(interpolateCubicSpline(helix, false)).has_value());
  Eigen::MatrixX3d line(3, 3);
  line << 0, 0, 0, 1, 1, 0, 2, 2, 0;
  EXPECT_FALSE(fitCurvePlane(interpolateCubicSpline(line, false)).has_value());
}

TEST(NetworkCurve, CorrectionSplineInterpolatesDisplacementsAndKeepsC2) {
  const NetworkCurve c = interpolateCubicSpline(unitCircle(8), true);
  const std::vector<double> ts{0.1, 1.7, 3.9};
  Eigen::MatrixX3d d(3, 3);
  d << 0.01, -0.02, 0, 0.0, 0.03, 0, -0.02, 0.01, 0;
  const NetworkCurve corrected = c.plus(correctionSpline(c, ts, d));
  for (int k = 0; k < 3; ++k) {
    EXPECT_LE((corrected.evaluate(ts[k]) - c.evaluate(ts[k]) - d.row(k).transpose()).norm(), 1e-14);
  }
  for (int deriv = 0; deriv <= 2; ++deriv) EXPECT_LE(jumpAtBreaks(corrected, deriv), 1e-10);
  // In-plane displacements keep the curve in its plane z = 0.
  for (int k = 0; k < 50; ++k) EXPECT_LE(std::abs(corrected.evaluate(c.period() * k / 50.0).z()), 1e-15);
}

}  // namespace
}  // namespace ffdkit::geometry::curvenet
