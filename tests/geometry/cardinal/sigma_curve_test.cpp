#include "ffdkit/geometry/cardinal/sigma_curve.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "ffdkit/geometry/cardinal/cardinal_error.h"
#include "test_support.h"

namespace ffdkit::geometry::cardinal {
namespace {

using test::sigmaBasis;

SigmaKnots mixedKnots(bool closed) {
  Eigen::VectorXd t(6);
  t << 0, 1, 3, 4, 7, 8;
  Eigen::VectorXd b = closed ? Eigen::VectorXd(5) : Eigen::VectorXd(6);
  if (closed) {
    b << 0, 2, 0, 7, 1;
  } else {
    b << 0, 2, 0, 7, 1, 0;
  }
  SigmaKnotsOptions o;
  o.closed = closed;
  return SigmaKnots(t, b, o);
}

SigmaCurve randomCurve(const SigmaKnots& k, unsigned seed) {
  std::srand(seed);
  return SigmaCurve(k, Eigen::MatrixX3d::Random(k.pointCount(), 3),
                    Eigen::MatrixX3d::Random(k.shapeCount(), 3));
}

TEST(SigmaBasis, UniformValuesMatchSpecT7) {
  const SigmaKnots k = SigmaKnots::uniform(7);
  const double xs[4] = {2.5, 3.25, 3.5, 3.75};
  const double sigma[4] = {0.3125, 0.738281, 0.3125, 0.050781};
  for (int a = 0; a < 4; ++a) EXPECT_NEAR(sigmaBasis(k, 3, xs[a], false), sigma[a], 5e-7);
  const double hx[6] = {2.5, 3.25, 3.5, 3.75, 4.5, 5.5};
  const double hat[6] = {-0.0625, 0.328125, 0.5, 0.328125, -0.0625, 0};
  for (int a = 0; a < 6; ++a) EXPECT_NEAR(sigmaBasis(k, 3, hx[a], true), hat[a], 5e-7);
}

TEST(SigmaBasis, TensionValuesMatchSpecT8) {
  Eigen::VectorXd beta2(8);
  beta2 << 0, 0, 5, 25, 100, 0, 0, 0;
  const SigmaKnots k(Eigen::VectorXd::LinSpaced(8, 0, 7), beta2);
  EXPECT_NEAR(sigmaBasis(k, 3, 2.5, false), 0.3125, 1e-14);
  EXPECT_NEAR(sigmaBasis(k, 3, 3.5, false), 0.3125, 1e-14);
  EXPECT_NEAR(sigmaBasis(k, 3, 3.5, true), 0.401967, 5e-7);
  EXPECT_NEAR(sigmaBasis(k, 3, 4.5, true), -0.006696, 5e-7);
}

TEST(SigmaBasis, NonUniformClosedValuesMatchSpecT9) {
  Eigen::VectorXd t(13);
  t << 0, 4, 6, 8, 12, 14, 16, 20, 24, 28, 32, 36, 40;
  SigmaKnotsOptions o;
  o.closed = true;
  const SigmaKnots k(t, {}, o);
  EXPECT_NEAR(sigmaBasis(k, 1, 3, false), 0.949219, 5e-7);
  EXPECT_NEAR(sigmaBasis(k, 1, 5, false), 0.25, 1e-14);
  EXPECT_NEAR(sigmaBasis(k, 1, 3, true), -0.28125, 1e-14);
  EXPECT_NEAR(sigmaBasis(k, 1, 5, true), 0.520833, 5e-7);
  EXPECT_NEAR(sigmaBasis(k, 1, 7, true), -0.0625, 1e-14);
}

TEST(SigmaBasis, CardinalAtKnotsAndPartitionOfUnity) {
  // P3 and P4, open (with phantoms) and closed, mixed tension, non-uniform knots.
  for (bool closed : {false, true}) {
    const SigmaKnots k = mixedKnots(closed);
    for (int i = 0; i < k.pointCount(); ++i) {
      for (int j = 0; j <= k.last(); ++j) {
        const double expected = (i == j || (closed && i == 0 && j == k.last())) ? 1.0 : 0.0;
        EXPECT_NEAR(sigmaBasis(k, i, k.knot(j), false), expected, 1e-14);
      }
    }
    for (int i = k.shapeFirst(); i < k.shapeFirst() + k.shapeCount(); ++i) {
      for (int j = 0; j <= k.last(); ++j) EXPECT_NEAR(sigmaBasis(k, i, k.knot(j), true), 0.0, 1e-14);
    }
    const Eigen::Vector3d c(0.3, -2.0, 5.0);
    const SigmaCurve constant(k, c.transpose().replicate(k.pointCount(), 1),
                              c.transpose().replicate(k.shapeCount(), 1));
    for (double x = 0.0; x <= 8.0; x += 0.1) {
      EXPECT_LT((constant.evaluate(x) - c).norm(), 1e-13) << x;
    }
  }
}

TEST(SigmaBasis, UniformCardinalBasisIgnoresTension) {
  // P17: on uniform knots sigma_i does not depend on beta2 (C_{i,0} = C_{i,1} = 1).
  Eigen::VectorXd beta2(8);
  beta2 << 3, 0, 50, 7, 0, 1, 9, 0;
  const SigmaKnots plain = SigmaKnots::uniform(7);
  const SigmaKnots tense(plain.knots(), beta2);
  for (int i = 0; i <= 7; ++i) {
    for (int step = 0; step <= 70; ++step) {
      const double x = step / 10.0;
      EXPECT_NEAR(sigmaBasis(plain, i, x, false), sigmaBasis(tense, i, x, false), 1e-14);
    }
  }
}

TEST(SigmaCurve, InterpolatesWhateverTheShapePoints) {
  for (bool closed : {false, true}) {
    const SigmaCurve c = randomCurve(mixedKnots(closed), 21);
    for (int i = 0; i < c.knots().pointCount(); ++i) {
      EXPECT_LT((c.evaluate(c.knots().knot(i)) - c.point(i)).norm(), 1e-12);
    }
  }
}

TEST(SigmaCurve, IsG2WithBeta2JumpAtEveryKnot) {
  // P6: Q' continuous, Q''(t+) - Q''(t-) = beta2_i Q'(t-), from the Bezier pieces.
  for (bool closed : {false, true}) {
    const SigmaCurve c = randomCurve(mixedKnots(closed), 22);
    const SigmaKnots& k = c.knots();
    const int first = closed ? 0 : 1;
    for (int i = first; i < k.last() + (closed ? 1 : 0); ++i) {
      const int left = (i - 1 + k.last()) % k.last();
      const int right = i % k.last();
      const double dl = k.delta(left), dr = k.delta(right);
      const Eigen::Vector3d d1l = evaluateQuarticBezier(c.bezier(left), 1.0, 1) / dl;
      const Eigen::Vector3d d1r = evaluateQuarticBezier(c.bezier(right), 0.0, 1) / dr;
      const Eigen::Vector3d d2l = evaluateQuarticBezier(c.bezier(left), 1.0, 2) / (dl * dl);
      const Eigen::Vector3d d2r = evaluateQuarticBezier(c.bezier(right), 0.0, 2) / (dr * dr);
      EXPECT_LT((d1l - d1r).norm(), 1e-12) << "knot " << i;
      EXPECT_LT((d2r - d2l - k.beta2(i) * d1l).norm(), 1e-10) << "knot " << i;
    }
  }
}

TEST(SigmaCurve, LocalSupportOfPointsAndShapePoints) {
  // P7: P_k affects (t_{k-1}, t_{k+1}); Phat_k affects (t_{k-1}, t_{k+2}); bitwise elsewhere.
  const SigmaKnots k = SigmaKnots::uniform(9);
  const SigmaCurve base = randomCurve(k, 23);
  Eigen::MatrixX3d p = base.points();
  p.row(4) += Eigen::RowVector3d(1, 1, 1);
  Eigen::MatrixX3d s = base.shapePoints();
  s.row(4 - k.shapeFirst()) += Eigen::RowVector3d(1, 1, 1);
  const SigmaCurve movedP(k, p, base.shapePoints()), movedS(k, base.points(), s);
  for (double x = 0.0; x <= 9.0; x += 0.125) {
    const double dp = (movedP.evaluate(x) - base.evaluate(x)).norm();
    const double ds = (movedS.evaluate(x) - base.evaluate(x)).norm();
    if (x <= 3.0 || x >= 5.0) {
      EXPECT_EQ(dp, 0.0) << x;
    }
    if (x <= 3.0 || x >= 6.0) {
      EXPECT_EQ(ds, 0.0) << x;
    }
    if (x > 3.0 && x < 5.0) {
      EXPECT_GT(dp, 0.0) << x;
    }
  }
}

TEST(SigmaCurve, ReversedDataAndKnotsGiveReversedCurve) {
  // P15 for sigma: knots t -> T - t, data and shape points reversed.
  const SigmaKnots k = mixedKnots(false);
  const SigmaCurve c = randomCurve(k, 24);
  const int n = k.last();
  Eigen::VectorXd t(n + 1), b(n + 1);
  for (int i = 0; i <= n; ++i) {
    t[i] = k.end() + k.start() - k.knot(n - i);
    b[i] = k.beta2(n - i);
  }
  const SigmaKnots rk(t, b);
  const SigmaCurve r(rk, c.points().colwise().reverse(), c.shapePoints().colwise().reverse());
  for (double x = 0.0; x <= 8.0; x += 0.1) {
    EXPECT_LT((c.evaluate(x) - r.evaluate(8.0 - x)).norm(), 1e-13) << x;
  }
}

TEST(SigmaCurve, RejectsWrongSizes) {
  const SigmaKnots k = SigmaKnots::uniform(3);
  EXPECT_THROW(SigmaCurve(k, Eigen::MatrixX3d::Zero(3, 3), Eigen::MatrixX3d::Zero(5, 3)),
               CardinalSplineError);
  EXPECT_THROW(SigmaCurve(k, Eigen::MatrixX3d::Zero(4, 3), Eigen::MatrixX3d::Zero(4, 3)),
               CardinalSplineError);
}

TEST(QuarticBezierPiece, ReproducesTheSubSegment) {
  std::srand(25);
  QuarticBezier b;
  for (auto& p : b) p = Eigen::Vector3d::Random();
  const QuarticBezier piece = quarticBezierPiece(b, 0.2, 0.7);
  for (double s = 0.0; s <= 1.0; s += 0.1) {
    EXPECT_LT((evaluateQuarticBezier(piece, s) - evaluateQuarticBezier(b, 0.2 + 0.5 * s)).norm(),
              1e-15);
  }
}

}  // namespace
}  // namespace ffdkit::geometry::cardinal
