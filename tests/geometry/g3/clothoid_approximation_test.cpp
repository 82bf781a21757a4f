#include "ffdkit/geometry/g3/clothoid_approximation.h"

#include <cmath>

#include <gtest/gtest.h>

#include "ffdkit/geometry/g3/g3_curve_solver.h"
#include "ffdkit/geometry/g3/g3_error.h"
#include "g3_test_data.h"

namespace ffdkit::geometry::g3 {
namespace {

QuadraticCurvatureSpline solved(const Eigen::MatrixX2d& p, const std::vector<Condition>& c) {
  const G3SolveResult r = solveG3Curve(p, c);
  EXPECT_TRUE(r.converged) << r.message;
  return *r.curve;
}

void expectG2Chain(const ClothoidApproximation& a, double h) {
  for (size_t k = 1; k < a.arcs.size(); ++k) {
    const ClothoidArc& prev = a.arcs[k - 1];
    const ClothoidArc& next = a.arcs[k];
    EXPECT_LE((prev.endPoint() - next.start).norm(), 1e-10 * h) << k;
    EXPECT_NEAR(prev.endAngle(), next.startAngle, 1e-12) << k;
    EXPECT_NEAR(prev.endCurvature(), next.startCurvature, 1e-12) << k;
  }
}

// Spec sec. 6.3 T3 [P]: max Hausdorff 0.0192 (bi-clothoid), 0.00119 (4-clothoid); property 11.
TEST(ClothoidApproximation, MeetsTheReferenceErrorsOfT3) {
  const Eigen::MatrixX2d p = testdata::figure2Points();
  const QuadraticCurvatureSpline c =
      solved(p, {Condition::curvature(0, 0.0), Condition::curvature(kLast, 0.0), Condition::tangentAngle(0, 0.45)});
  const ClothoidApproximation bi = approximateByClothoids(c);
  ASSERT_TRUE(bi.converged);
  ASSERT_EQ(bi.arcs.size(), 14u);
  ClothoidApproximationOptions four;
  four.subdivisionLevels = 2;
  const ClothoidApproximation quad = approximateByClothoids(c, four);
  ASSERT_TRUE(quad.converged);
  ASSERT_EQ(quad.arcs.size(), 28u);
  EXPECT_NEAR(bi.maxHausdorff, 0.0192, 0.1 * 0.0192);
  EXPECT_NEAR(quad.maxHausdorff, 0.00119, 0.1 * 0.00119);
  EXPECT_LE(quad.maxHausdorff, bi.maxHausdorff / 8.0);
  const double h = 5.0;
  expectG2Chain(bi, h);
  expectG2Chain(quad, h);
  for (const auto& span : bi.spans) EXPECT_LT(std::abs(span.lengthDeviation), 0.02);
}

// Spec sec. 6.2 Fig. 5 [P] (B10, linear form): bi-clothoid 0.1035 / 0.0623, 4-clothoid 0.00614 / 0.0175.
TEST(ClothoidApproximation, MeetsTheReferenceErrorsOfFigure5) {
  const QuadraticCurvatureSpline c = solved(testdata::figure5Points(), {Condition::naturalEnds()});
  const ClothoidApproximation bi = approximateByClothoids(c);
  ClothoidApproximationOptions four;
  four.subdivisionLevels = 2;
  const ClothoidApproximation quad = approximateByClothoids(c, four);
  ASSERT_TRUE(bi.converged && quad.converged);
  EXPECT_NEAR(bi.maxHausdorff, 0.1035, 0.1 * 0.1035);
  EXPECT_NEAR(bi.maxCurvatureDeviation, 0.0623, 0.1 * 0.0623);
  EXPECT_NEAR(quad.maxHausdorff, 0.00614, 0.1 * 0.00614);
  EXPECT_NEAR(quad.maxCurvatureDeviation, 0.0175, 0.1 * 0.0175);
  EXPECT_LE(quad.maxHausdorff, bi.maxHausdorff / 8.0);
  // The worst bi-clothoid span is span 8, where curvature is highest.
  int worst = 0;
  for (int i = 0; i < c.spanCount(); ++i) {
    if (bi.spans[i].hausdorff > bi.spans[worst].hausdorff) worst = i;
  }
  EXPECT_EQ(worst, 8);
  double maxLengthDeviation = 0.0;  // [P]: 1.5 % at span 1, under the 2 % warning level
  for (const auto& span : bi.spans) maxLengthDeviation = std::max(maxLengthDeviation, std::abs(span.lengthDeviation));
  EXPECT_NEAR(maxLengthDeviation, 0.015, 0.002);
  EXPECT_TRUE(bi.warnings.empty());
  expectG2Chain(bi, 7.5);
  expectG2Chain(quad, 7.5);
}

TEST(ClothoidApproximation, ReproducesClothoidSpansExactly) {
  // Fig. 2(e): both end spans are clothoid arcs.
  const QuadraticCurvatureSpline c =
      solved(testdata::figure2Points(), {Condition::clothoidSpan(0), Condition::clothoidSpan(kLast)});
  const ClothoidApproximation bi = approximateByClothoids(c);
  for (int i : {0, 6}) {
    const SpanApproximationError& e = bi.spans[i];
    EXPECT_NEAR(e.lengthDeviation, 0.0, 1e-15) << i;
    EXPECT_LT(e.hausdorff, 1e-9) << i;
    EXPECT_LT(e.maxCurvatureDeviation, 1e-12) << i;
    EXPECT_EQ(bi.junctionFractions[i], 0.5);
  }
  EXPECT_GT(bi.spans[3].hausdorff, 1e-4);  // a general span is only approximated
}

TEST(ClothoidApproximation, DeeperSubdivisionKeepsReducingTheError) {
  const QuadraticCurvatureSpline c = solved(testdata::figure3Points(), {Condition::curvature(0, 0.43212079),
                                                                        Condition::curvature(kLast, -0.40518471),
                                                                        Condition::tangentAngle(0, 2.65)});
  double previous = 1e9;
  for (int level = 1; level <= 3; ++level) {
    ClothoidApproximationOptions o;
    o.subdivisionLevels = level;
    o.errorSamplesPerSpan = 256;
    const ClothoidApproximation a = approximateByClothoids(c, o);
    ASSERT_TRUE(a.converged) << level;
    EXPECT_EQ(a.arcs.size(), static_cast<size_t>(10 << level));
    EXPECT_LT(a.maxHausdorff, previous / 4.0) << level;
    previous = a.maxHausdorff;
  }
}

TEST(ClothoidApproximation, RejectsInvalidOptions) {
  Eigen::VectorXd ds = Eigen::VectorXd::Ones(2);
  const QuadraticCurvatureSpline c = QuadraticCurvatureSpline::fromStartPoint({0, 0}, ds, Eigen::VectorXd::Zero(5));
  ClothoidApproximationOptions o;
  o.subdivisionLevels = 0;
  EXPECT_THROW(approximateByClothoids(c, o), G3InputError);
  o.subdivisionLevels = 1;
  o.errorSamplesPerSpan = 2;
  EXPECT_THROW(approximateByClothoids(c, o), G3InputError);
}

}  // namespace
}  // namespace ffdkit::geometry::g3
