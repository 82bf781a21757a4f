#include "ffdkit/geometry/g3/clothoid_spline.h"

#include <cmath>

#include <gtest/gtest.h>

#include "ffdkit/geometry/g3/g3_error.h"
#include "g3_test_data.h"

namespace ffdkit::geometry::g3 {
namespace {

// Spec sec. 6.3 T2 (Fig. 2(b)): the clothoid spline with the cubic's end curvatures.
TEST(ClothoidSpline, SolvesReferenceCaseT2Figure2b) {
  const Eigen::MatrixX2d p = testdata::figure2Points();
  const ClothoidSplineResult r = solveClothoidSpline(p, -0.10923218, -0.16584946);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_LE(r.iterations, 6);
  const ClothoidSpline& c = *r.curve;
  EXPECT_NEAR(c.length(), 31.724017364, 1e-7);
  const double ds[] = {3.5770489, 4.6993213, 4.2462982, 4.8311177, 5.6375473, 5.0302065, 3.7024776};
  for (int i = 0; i < 7; ++i) EXPECT_NEAR(c.spanLengths()[i], ds[i], 1e-7) << i;
  EXPECT_NEAR(c.tangentAngle(0.0), 0.5467280, 1e-7);
  EXPECT_NEAR(c.curvature(0.0), -0.10923218, 1e-12);
  EXPECT_NEAR(c.curvature(c.length()), -0.16584946, 1e-12);
  for (int i = 0; i < 7; ++i) {
    EXPECT_LE((p.row(i).transpose() + c.spanDisplacement(i, 2) - p.row(i + 1).transpose()).norm(), 1e-10 * 5.7) << i;
  }
}

// Property 4: a clothoid spline is G2 but must fail the G3 test (jumps up to 0.166).
TEST(ClothoidSpline, IsG2ButFailsTheCurvatureDerivativeContinuityTest) {
  const ClothoidSplineResult r = solveClothoidSpline(testdata::figure2Points(), -0.10923218, -0.16584946);
  ASSERT_TRUE(r.converged);
  const ClothoidSpline& c = *r.curve;
  double maxJump = 0.0, maxSharpness = 0.0;
  for (int i = 0; i < 7; ++i) maxSharpness = std::max(maxSharpness, std::abs(c.sharpness(i)));
  for (int i = 1; i < 7; ++i) {
    const double s = c.knots()[i];
    const double left = c.spanLengths()[i - 1];
    const Eigen::Vector3d b = c.bezierOrdinates().segment<3>(2 * (i - 1));
    const double kappaLeft = 2.0 * (b[2] - b[1]) / left;
    EXPECT_NEAR(kappaLeft, c.curvature(s), 1e-12) << i;  // G2 holds
    maxJump = std::max(maxJump, std::abs(c.sharpness(i) - c.sharpness(i - 1)));
  }
  EXPECT_GT(maxJump, 1e-10 * (1.0 + maxSharpness));  // the G3 test fails ...
  EXPECT_NEAR(maxJump, 0.166, 0.005);                // ... by the reference amount
}

TEST(ClothoidSpline, SamplesAgreeWithPointwiseEvaluation) {
  const ClothoidSplineResult r = solveClothoidSpline(testdata::figure2Points(), -0.1, -0.15);
  ASSERT_TRUE(r.converged);
  const CurveSamples s = r.curve->sample(5);
  ASSERT_EQ(s.arcLength.size(), 36);
  for (Eigen::Index k = 0; k < s.arcLength.size(); ++k) {
    EXPECT_LE((s.points.row(k).transpose() - r.curve->position(s.arcLength[k])).norm(), 1e-12);
    EXPECT_NEAR(s.curvature[k], r.curve->curvature(s.arcLength[k]), 1e-12);
  }
}

TEST(ClothoidSpline, RejectsInvalidInput) {
  EXPECT_THROW(solveClothoidSpline(Eigen::MatrixX2d::Zero(1, 2), 0.0, 0.0), G3InputError);
  EXPECT_THROW(solveClothoidSpline(testdata::figure2Points(), std::nan(""), 0.0), G3InputError);
  EXPECT_THROW(ClothoidSpline::fromSpanStarts(Eigen::MatrixX2d::Zero(3, 2), Eigen::VectorXd::Ones(2), Eigen::VectorXd::Zero(3)),
               G3InputError);
}

}  // namespace
}  // namespace ffdkit::geometry::g3
