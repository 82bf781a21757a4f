#include "ffdkit/geometry/g3/cubic_spline_initial_guess.h"

#include <gtest/gtest.h>

#include "ffdkit/geometry/g3/g3_error.h"
#include "g3_test_data.h"

namespace ffdkit::geometry::g3 {
namespace {

// Spec sec. 6.1 (a): the not-a-knot chord-length cubic of Fig. 2 ([P] values).
TEST(CubicSplineInitialGuess, MatchesTheReferenceCubicOfFigure2) {
  const CubicSplineInitialGuess guess = initialGuessFromCubicSpline(testdata::figure2Points());
  EXPECT_NEAR(guess.curvatureAtPoints[0], -0.10923218, 1e-8);
  EXPECT_NEAR(guess.curvatureAtPoints[7], -0.16584946, 1e-8);
  EXPECT_NEAR(guess.tangentAtPoints[0], 0.60570889, 1e-8);
  const double knots[] = {0, 3.6459, 8.2780, 12.4576, 17.2200, 22.8600, 27.8351, 31.6063};
  double s = 0.0;
  for (int i = 0; i < 7; ++i) {
    s += guess.spanLengths[i];
    EXPECT_NEAR(s, knots[i + 1], 1e-4) << i;
  }
  ASSERT_EQ(guess.unknowns.size(), 2 * 7 + 3);
  EXPECT_EQ(guess.deBoor[0], guess.tangentAtPoints[0]);
}

TEST(CubicSplineInitialGuess, MatchesTheReferenceCubicsOfFigures3And4) {
  const CubicSplineInitialGuess g3 = initialGuessFromCubicSpline(testdata::figure3Points());
  EXPECT_NEAR(g3.curvatureAtPoints[0], 0.43212079, 1e-8);
  EXPECT_NEAR(g3.curvatureAtPoints[10], -0.40518471, 1e-8);
  EXPECT_NEAR(g3.length, 41.7391, 1e-4);
  const CubicSplineInitialGuess g4 = initialGuessFromCubicSpline(testdata::figure4Points());
  EXPECT_NEAR(g4.curvatureAtPoints[0], -0.08229731, 1e-8);
  EXPECT_NEAR(g4.curvatureAtPoints[20], -0.06879707, 1e-8);
  EXPECT_NEAR(g4.length, 55.8057, 1e-4);
}

TEST(CubicSplineInitialGuess, UnwrapsTheTangentAngleAlongALoopingCurve) {
  // Fig. 5 turns through more than 2 pi; the angle must decrease continuously, never jump.
  const CubicSplineInitialGuess g = initialGuessFromCubicSpline(testdata::figure5Points());
  for (Eigen::Index j = 1; j < g.deBoor.size(); ++j) EXPECT_LT(std::abs(g.deBoor[j] - g.deBoor[j - 1]), 2.5) << j;  // a 2 pi jump would show
  EXPECT_LT(g.deBoor[g.deBoor.size() - 1] - g.deBoor[0], -2.0 * 3.14159);
}

TEST(CubicSplineInitialGuess, IsExactForCollinearPoints) {
  Eigen::MatrixX2d p(4, 2);
  p << 0, 0, 1, 2, 1.5, 3, 4, 8;
  const CubicSplineInitialGuess g = initialGuessFromCubicSpline(p);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(g.spanLengths[i], (p.row(i + 1) - p.row(i)).norm(), 1e-13);
  for (Eigen::Index j = 0; j < g.deBoor.size(); ++j) EXPECT_NEAR(g.deBoor[j], std::atan2(2.0, 1.0), 1e-13);
}

TEST(CubicSplineInitialGuess, HandlesTwoAndThreePoints) {
  Eigen::MatrixX2d two(2, 2);
  two << 0, 0, 3, 4;
  EXPECT_NEAR(initialGuessFromCubicSpline(two).length, 5.0, 1e-13);
  Eigen::MatrixX2d three(3, 2);
  three << 0, 0, 1, 1, 2, 0;
  const CubicSplineInitialGuess g = initialGuessFromCubicSpline(three);
  EXPECT_NEAR(g.spanLengths[0], g.spanLengths[1], 1e-12);  // the parabola is symmetric
  EXPECT_NEAR(g.deBoor[0], -g.deBoor[4], 1e-12);
}

TEST(CubicSplineInitialGuess, RejectsCoincidentConsecutivePoints) {
  Eigen::MatrixX2d p(3, 2);
  p << 0, 0, 1, 1, 1, 1;
  EXPECT_THROW(initialGuessFromCubicSpline(p), G3InputError);
  EXPECT_THROW(initialGuessFromCubicSpline(Eigen::MatrixX2d::Zero(1, 2)), G3InputError);
}

}  // namespace
}  // namespace ffdkit::geometry::g3
