#include "ffdkit/geometry/cardinal/sigma_knots.h"

#include <gtest/gtest.h>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

namespace ffdkit::geometry::cardinal {
namespace {

TEST(SigmaKnots, CoefficientsWithMixedTensionMatchSpecT8) {
  Eigen::VectorXd beta2(8);
  beta2 << 0, 0, 5, 25, 100, 0, 0, 0;
  const SigmaKnots k(Eigen::VectorXd::LinSpaced(8, 0, 7), beta2);
  EXPECT_NEAR(k.D(1), 4.0, 1e-15);
  EXPECT_NEAR(k.D(2), 17.0 / 3.0, 1e-14);
  EXPECT_NEAR(k.D(3), 37.0 / 3.0, 1e-14);
  EXPECT_NEAR(k.D(4), 112.0 / 3.0, 1e-13);
  EXPECT_NEAR(k.Chat1(3), 3.0 / 37.0, 1e-15);
  EXPECT_NEAR(k.Chat3(3), 3.0 / 112.0, 1e-15);
  // Uniform spacing: C_{i,0} = C_{i,1} = 1 whatever the tension.
  for (int i = 0; i <= 7; ++i) {
    EXPECT_NEAR(k.C0(i), 1.0, 1e-15);
    EXPECT_NEAR(k.C1(i), 1.0, 1e-15);
  }
}

TEST(SigmaKnots, NonUniformClosedCoefficientsMatchSpecT9) {
  Eigen::VectorXd t(13);
  t << 0, 4, 6, 8, 12, 14, 16, 20, 24, 28, 32, 36, 40;
  SigmaKnotsOptions o;
  o.closed = true;
  const SigmaKnots k(t, {}, o);
  EXPECT_NEAR(k.D(1), 1.5, 1e-15);
  EXPECT_NEAR(k.C0(1), 1.5, 1e-15);
  EXPECT_NEAR(k.C1(1), 0.75, 1e-15);
  EXPECT_NEAR(k.Chat0(1), -2.0 / 3.0, 1e-15);
  EXPECT_NEAR(k.Chat1(1), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(k.Chat3(1), 0.25, 1e-15);
  EXPECT_NEAR(k.Chat4(1), -0.25, 1e-15);
  // Periodic wrap of widths and knots.
  EXPECT_DOUBLE_EQ(k.delta(-1), 4.0);
  EXPECT_DOUBLE_EQ(k.delta(12), 4.0);
  EXPECT_DOUBLE_EQ(k.knot(13), 44.0);
  double s = 0.0;
  EXPECT_EQ(k.locate(41.0, s), 0);
  EXPECT_DOUBLE_EQ(s, 0.25);
}

TEST(SigmaKnots, OpenPhantomWidthsDefaultToEndIntervals) {
  Eigen::VectorXd t(4);
  t << 0, 1, 3, 4;
  const SigmaKnots k(t);
  EXPECT_DOUBLE_EQ(k.delta(-1), 1.0);
  EXPECT_DOUBLE_EQ(k.delta(3), 1.0);
  SigmaKnotsOptions o;
  o.phantomBefore = 5.0;
  EXPECT_DOUBLE_EQ(SigmaKnots(t, {}, o).delta(-1), 5.0);
  double s = 0.0;
  EXPECT_EQ(k.locate(4.0, s), 2);
  EXPECT_DOUBLE_EQ(s, 1.0);
  EXPECT_EQ(k.locate(1.0, s), 1);
  EXPECT_DOUBLE_EQ(s, 0.0);
}

TEST(SigmaKnots, RejectsBadInput) {
  Eigen::VectorXd t(3);
  t << 0, 1, 1;
  EXPECT_THROW(SigmaKnots{t}, CardinalSplineError);
  t << 0, 1, 2;
  EXPECT_THROW(SigmaKnots(t, Eigen::VectorXd::Zero(2)), CardinalSplineError);
  EXPECT_THROW(SigmaKnots(t, Eigen::Vector3d(0, -1, 0)), CardinalSplineError);
  SigmaKnotsOptions closed;
  closed.closed = true;
  EXPECT_THROW(SigmaKnots(t, {}, closed), CardinalSplineError);
}

}  // namespace
}  // namespace ffdkit::geometry::cardinal
