#include "ffdkit/geometry/g3/g3_curve_solver.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "ffdkit/geometry/g3/cubic_spline_initial_guess.h"
#include "ffdkit/geometry/g3/g3_error.h"
#include "g3_test_data.h"

namespace ffdkit::geometry::g3 {
namespace {

using Kind = Condition::Kind;

double maxChord(const Eigen::MatrixX2d& p) {
  return (p.bottomRows(p.rows() - 1) - p.topRows(p.rows() - 1)).rowwise().norm().maxCoeff();
}

void expectSpanLengths(const QuadraticCurvatureSpline& c, std::initializer_list<double> expected, double tol) {
  ASSERT_EQ(static_cast<size_t>(c.spanCount()), expected.size());
  int i = 0;
  for (double e : expected) {
    EXPECT_NEAR(c.spanLength(i), e, tol) << "Delta s_" << i;
    ++i;
  }
}

// Spec sec. 7 property 1: each span integrated on its own with twice the panels lands on the
// next point; chaining from p_0 reaches p_n.
void expectInterpolates(const QuadraticCurvatureSpline& c, const Eigen::MatrixX2d& p) {
  const double h = maxChord(p);
  Eigen::Vector2d chained = p.row(0).transpose();
  for (int i = 0; i < c.spanCount(); ++i) {
    const Eigen::Vector2d d = c.spanDisplacement(i, 2);
    EXPECT_LE((p.row(i).transpose() + d - p.row(i + 1).transpose()).norm(), 1e-10 * h) << "span " << i;
    chained += d;
  }
  EXPECT_LE((chained - p.row(p.rows() - 1).transpose()).norm(), c.spanCount() * 1e-10 * h);
}

// Property 7: arc longer than chord.
void expectArcsLongerThanChords(const QuadraticCurvatureSpline& c, const Eigen::MatrixX2d& p) {
  for (int i = 0; i < c.spanCount(); ++i) EXPECT_GT(c.spanLength(i), (p.row(i + 1) - p.row(i)).norm()) << i;
}

// Property 9: quadratic convergence, ||f_{k+1}|| / ||f_k||^2 bounded while above rounding.
void expectQuadraticConvergence(const G3SolveResult& r) {
  EXPECT_LE(r.iterations, 6);
  for (size_t k = 1; k < r.residualHistory.size(); ++k) {
    const double prev = r.residualHistory[k - 1];
    if (prev < 1e-5 || r.residualHistory[k] < 1e-12) continue;
    EXPECT_LE(r.residualHistory[k] / (prev * prev), 50.0) << "iteration " << k;
  }
}

std::vector<Condition> t1Conditions() {
  return {Condition::curvature(0, -0.10923218), Condition::curvature(kLast, -0.16584946),
          Condition::tangentAngle(0, 0.546728)};
}

TEST(G3CurveSolver, AnalyticJacobianMatchesCentralDifferences) {
  const Eigen::MatrixX2d p = testdata::figure2Points();
  std::vector<Condition> conditions = {Condition::curvature(0, -0.1), Condition::radiusOfCurvature(3, 4.0),
                                       Condition::clothoidSpan(2), Condition::circularArcSpan(5),
                                       Condition::partialLength(1, 3, 12.0), Condition::naturalEnds(),
                                       Condition::tangentAngle(4, 1.0), Condition::curvature(kLast, 0.2)};
  G3SolverOptions options;
  Eigen::VectorXd v = initialGuessFromCubicSpline(p).unknowns;
  v.tail(10) += Eigen::VectorXd::LinSpaced(10, -0.3, 0.4);
  const G3SystemEvaluation e = evaluateG3System(p, conditions, v, options);
  ASSERT_EQ(e.jacobian.rows(), 14 + 10);
  for (Eigen::Index j = 0; j < v.size(); ++j) {
    const double h = 1e-6 * (1.0 + std::abs(v[j]));
    Eigen::VectorXd vp = v, vm = v;
    vp[j] += h;
    vm[j] -= h;
    const Eigen::VectorXd fd =
        (evaluateG3System(p, conditions, vp, options).residual - evaluateG3System(p, conditions, vm, options).residual) /
        (2.0 * h);
    for (Eigen::Index r = 0; r < fd.size(); ++r) {
      EXPECT_NEAR(e.jacobian(r, j), fd[r], 1e-7 * (1.0 + std::abs(fd[r]))) << "row " << r << " column " << j;
    }
  }
}

// Spec sec. 6.3 T1 (Fig. 2(c)).
TEST(G3CurveSolver, SolvesReferenceCaseT1Figure2c) {
  const Eigen::MatrixX2d p = testdata::figure2Points();
  const G3SolveResult r = solveG3Curve(p, t1Conditions());
  ASSERT_TRUE(r.converged) << r.message;
  const QuadraticCurvatureSpline& c = *r.curve;
  EXPECT_NEAR(c.length(), 31.944481581, 1e-7);
  expectSpanLengths(c, {3.5693457, 4.7597531, 4.3288554, 4.8419044, 5.6629093, 4.9261586, 3.8555550}, 1e-7);
  const double psi[] = {0.5467280, -0.2466653, -1.0684910, 0.1186784, 1.1997861, 0.9396946, 0.4227374, -0.7992170};
  const double kappa[] = {-0.1092322, -0.2855481, 0.0711000, 0.3398163, 0.0707497, -0.0587900, -0.2763666, -0.1658495};
  for (int i = 0; i <= 7; ++i) {
    EXPECT_NEAR(c.tangentAngle(c.knots()[i]), psi[i], 1e-7) << i;
    EXPECT_NEAR(c.curvature(c.knots()[i]), kappa[i], 1e-7) << i;
  }
  const double d[] = {0.5467280, 0.4167655, -0.3385698, -1.6192850, 0.2930048, 1.5750218, 0.8047771, 0.9026775, -0.5860698, -0.7992170};
  for (int j = 0; j < 10; ++j) EXPECT_NEAR(c.deBoor()[j], d[j], 1e-7) << "d_" << j - 1;
  const CurveSamples samples = c.sample(1024);
  EXPECT_NEAR(samples.curvature.minCoeff(), -0.370156, 1e-5);
  EXPECT_NEAR(samples.curvature.maxCoeff(), 0.352378, 1e-5);
  expectInterpolates(c, p);
  expectArcsLongerThanChords(c, p);
  expectQuadraticConvergence(r);
  EXPECT_LE(r.scaledResidualInf, 1e-10);  // property 6 for the condition rows too
  EXPECT_FALSE(r.underdetermined);
  EXPECT_TRUE(r.warnings.empty());
}

TEST(G3CurveSolver, SolvesReferenceCaseT3WithNaturalEndsAndStartTangent) {
  const Eigen::MatrixX2d p = testdata::figure2Points();
  const G3SolveResult r = solveG3Curve(
      p, {Condition::curvature(0, 0.0), Condition::curvature(kLast, 0.0), Condition::tangentAngle(0, 0.45)});
  ASSERT_TRUE(r.converged) << r.message;
  const QuadraticCurvatureSpline& c = *r.curve;
  EXPECT_NEAR(c.length(), 31.882869227, 1e-7);
  expectSpanLengths(c, {3.5456247, 4.7793278, 4.3495823, 4.8219043, 5.6560003, 4.9389775, 3.7914522}, 1e-7);
  const double psi[] = {0.45, -0.2189428, -1.0869408, 0.1379544, 1.1805076, 0.9607201, 0.3858482, -0.6457849};
  const double dkappa[] = {-0.1534938, -0.0122800, 0.1655053, -0.0422369, -0.0699992, 0.0247746, -0.1203229, 0.2754571};
  for (int i = 0; i <= 7; ++i) {
    EXPECT_NEAR(c.tangentAngle(c.knots()[i]), psi[i], 1e-7) << i;
    EXPECT_NEAR(c.curvatureDerivative(c.knots()[i]), dkappa[i], 1e-7) << i;
  }
  double margin = 1e9;
  for (int i = 0; i < 7; ++i) margin = std::min(margin, c.spanLength(i) - (p.row(i + 1) - p.row(i)).norm());
  EXPECT_NEAR(margin, 0.0195, 1e-4);
  expectInterpolates(c, p);
  expectQuadraticConvergence(r);
}

TEST(G3CurveSolver, SolvesReferenceCaseT4Figure3) {
  const Eigen::MatrixX2d p = testdata::figure3Points();
  const G3SolveResult r = solveG3Curve(
      p, {Condition::curvature(0, 0.43212079), Condition::curvature(kLast, -0.40518471), Condition::tangentAngle(0, 2.65)});
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_NEAR(r.curve->length(), 43.763128326, 1e-7);
  expectSpanLengths(*r.curve,
                    {8.0106532, 3.5248789, 4.2217057, 4.5265259, 5.4241213, 1.9404612, 3.9139173, 7.8089125, 2.0511782,
                     2.3407741},
                    1e-7);
  expectInterpolates(*r.curve, p);
  expectArcsLongerThanChords(*r.curve, p);
  expectQuadraticConvergence(r);
}

TEST(G3CurveSolver, SolvesReferenceCaseT5Figure4) {
  const Eigen::MatrixX2d p = testdata::figure4Points();
  const G3SolveResult r = solveG3Curve(p, {Condition::curvature(0, -0.08229731), Condition::curvature(kLast, -0.06879707),
                                           Condition::tangentAngle(0, 0.83)});
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_NEAR(r.curve->length(), 55.859545841, 1e-7);
  expectSpanLengths(*r.curve,
                    {2.7661442, 2.7353061, 2.7856842, 2.7875164, 2.8409799, 2.8525296, 2.8395098, 2.7755664, 2.7518558,
                     2.8457500, 2.8285769, 2.7793143, 2.7876749, 2.7743749, 2.7842813, 2.7772999, 2.7994102, 2.8216504,
                     2.7882910, 2.7378297},
                    1e-7);
  expectInterpolates(*r.curve, p);
  expectQuadraticConvergence(r);
}

// Derivatives 0..3 of the position at `at` from one side only: the degree-6 polynomial through
// the 7 positions at at + side * k * h, k = 1..7, differentiated at `at` (sampling the curve's
// geometry, independent of its curvature formulas and of the solver's diagnostics).
std::array<Eigen::Vector2d, 4> oneSidedDerivatives(const QuadraticCurvatureSpline& c, double at, double side, double h) {
  Eigen::Matrix<double, 7, 7> v;
  Eigen::Matrix<double, 7, 2> y;
  for (int k = 0; k < 7; ++k) {
    const double sigma = side * (k + 1);
    for (int m = 0; m < 7; ++m) v(k, m) = std::pow(sigma, m);
    y.row(k) = c.position(at + sigma * h).transpose();
  }
  const Eigen::Matrix<double, 7, 2> a = v.partialPivLu().solve(y);
  std::array<Eigen::Vector2d, 4> d;
  double factorial = 1.0;
  for (int m = 0; m < 4; ++m) {
    if (m > 0) factorial *= m;
    d[m] = a.row(m).transpose() * factorial / std::pow(h, m);
  }
  return d;
}

TEST(G3CurveSolver, SolvedCurvesAreG3AtEveryJointBySampledPositions) {
  // Kuroda et al. 1997, sec. 2: the curvature is C1 at every interior knot (G3). From the left and from the right
  // of each joint: positions meet (G0), kappa = x' y'' - y' x'' and its derivative
  // x' y''' - y' x''' agree (the speed is 1 in arc length).
  struct Case {
    const char* name;
    Eigen::MatrixX2d points;
    std::vector<Condition> conditions;
  };
  const Case cases[] = {{"T1", testdata::figure2Points(), t1Conditions()},
                        {"T4", testdata::figure3Points(),
                         {Condition::curvature(0, 0.43212079), Condition::curvature(kLast, -0.40518471), Condition::tangentAngle(0, 2.65)}},
                        {"T5", testdata::figure4Points(),
                         {Condition::curvature(0, -0.08229731), Condition::curvature(kLast, -0.06879707), Condition::tangentAngle(0, 0.83)}}};
  const auto kappa = [](const std::array<Eigen::Vector2d, 4>& d) { return d[1].x() * d[2].y() - d[1].y() * d[2].x(); };
  const auto slope = [](const std::array<Eigen::Vector2d, 4>& d) { return d[1].x() * d[3].y() - d[1].y() * d[3].x(); };
  for (const Case& k : cases) {
    const G3SolveResult r = solveG3Curve(k.points, k.conditions);
    ASSERT_TRUE(r.converged) << k.name << ": " << r.message;
    const QuadraticCurvatureSpline& c = *r.curve;
    double worstGap = 0.0, worstKappa = 0.0, worstSlope = 0.0, biggestSlope = 0.0;
    for (int i = 1; i < c.spanCount(); ++i) {
      const double s = c.knots()[i];
      const double h = 0.005 * std::min(c.spanLength(i - 1), c.spanLength(i));
      const auto left = oneSidedDerivatives(c, s, -1.0, h), right = oneSidedDerivatives(c, s, 1.0, h);
      worstGap = std::max(worstGap, (left[0] - right[0]).norm());
      worstKappa = std::max(worstKappa, std::abs(kappa(left) - kappa(right)));
      worstSlope = std::max(worstSlope, std::abs(slope(left) - slope(right)));
      biggestSlope = std::max(biggestSlope, std::abs(slope(left)));
      // The joint is where the data point is (the sampled curve, not the solver's residual).
      EXPECT_LE((left[0] - k.points.row(i).transpose()).norm(), 1e-9 * c.length()) << k.name << " knot " << i;
    }
    std::printf("[G3 joints] %s: gap %.2e, kappa jump %.2e, kappa' jump %.2e (|kappa'| up to %.3f)\n", k.name, worstGap,
                worstKappa, worstSlope, biggestSlope);
    // With h = 0.005 span lengths the one-sided fits are good to ~1e-12 (position), ~4e-9
    // (kappa) and ~1.5e-6 (kappa'); the truncation error falls like h^7 / h^5 / h^4, so the
    // remaining jumps are the estimate's, not the curve's. A G2-only joint would jump in kappa' by
    // ~kappa'' x span, about 0.1 here.
    EXPECT_LE(worstGap, 1e-11 * c.length()) << k.name;
    EXPECT_LE(worstKappa, 1e-7) << k.name;
    EXPECT_LE(worstSlope, 2e-5) << k.name;
    EXPECT_GT(biggestSlope, 1e-2) << k.name;  // kappa' is not trivially 0: the check has something to see
  }
}

TEST(G3CurveSolver, SolvesReferenceCaseT6Figure5WithUnwrappedAngles) {
  const Eigen::MatrixX2d p = testdata::figure5Points();
  const G3SolveResult r = solveG3Curve(
      p, {Condition::curvature(0, 0.0), Condition::curvature(kLast, 0.0), Condition::tangentAngle(0, 1.95)});
  ASSERT_TRUE(r.converged) << r.message;
  const QuadraticCurvatureSpline& c = *r.curve;
  EXPECT_NEAR(c.length(), 74.607140760, 1e-7);
  expectSpanLengths(c,
                    {6.0476769, 7.6311174, 4.3133864, 6.3688450, 5.9038831, 6.1387271, 8.2515478, 8.8245026, 8.1990900,
                     6.9225913, 6.0057731},
                    1e-7);
  EXPECT_NEAR(c.tangentAngle(c.length()), -6.0238627, 1e-7);
  const CurveSamples samples = c.sample(1024);
  EXPECT_NEAR(samples.curvature.minCoeff(), -0.485585, 1e-5);
  EXPECT_NEAR(samples.curvature.maxCoeff(), 0.365532, 1e-5);
  EXPECT_LT(samples.tangentAngle.minCoeff(), -9.1);
  expectInterpolates(c, p);
  expectQuadraticConvergence(r);
}

// Spec sec. 6.4 S1: a curve of the family is reproduced.
TEST(G3CurveSolver, ReproducesAKnownCubicTangentAngle) {
  const G3SolveResult r = solveG3Curve(
      testdata::s1Points(), {Condition::curvature(0, -0.25), Condition::curvature(kLast, 0.05), Condition::tangentAngle(0, 0.3)});
  ASSERT_TRUE(r.converged) << r.message;
  const Eigen::VectorXd knots = testdata::s1Knots();
  // The points carry 12 decimals, which bounds the achievable agreement.
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(r.curve->spanLength(i), knots[i + 1] - knots[i], 1e-11) << i;
  for (double s = 0.0; s < 10.0; s += 0.5) {
    EXPECT_NEAR(r.curve->tangentAngle(s), testdata::s1Angle(s), 1e-11) << s;
    EXPECT_NEAR(r.curve->curvature(s), testdata::s1Curvature(s), 1e-11) << s;
  }
}

// S2: circle of radius 5.
TEST(G3CurveSolver, ReproducesACircle) {
  const double angles[] = {0, 0.4, 1.1, 1.5, 2.3, 2.9};
  Eigen::MatrixX2d p(6, 2);
  for (int i = 0; i < 6; ++i) p.row(i) << 5 * std::sin(angles[i]), 5 * (1 - std::cos(angles[i]));
  const G3SolveResult r =
      solveG3Curve(p, {Condition::curvature(0, 0.2), Condition::curvature(kLast, 0.2), Condition::tangentAngle(0, 0.0)});
  ASSERT_TRUE(r.converged) << r.message;
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(r.curve->spanLength(i), 5 * (angles[i + 1] - angles[i]), 1e-13) << i;
  for (double s = 0.0; s < r.curve->length(); s += 0.3) EXPECT_NEAR(r.curve->curvature(s), 0.2, 1e-13) << s;
}

// S3: straight line.
TEST(G3CurveSolver, ReproducesAStraightLine) {
  Eigen::MatrixX2d p(5, 2);
  p << 1, 1, 2, 3, 2.5, 4, 4, 7, 4.2, 7.4;
  const double direction = std::atan2(2.0, 1.0);
  const G3SolveResult r = solveG3Curve(
      p, {Condition::curvature(0, 0.0), Condition::curvature(kLast, 0.0), Condition::tangentAngle(0, direction)});
  ASSERT_TRUE(r.converged) << r.message;
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(r.curve->spanLength(i), (p.row(i + 1) - p.row(i)).norm(), 1e-13);
  for (Eigen::Index j = 0; j < 7; ++j) EXPECT_NEAR(r.curve->deBoor()[j], direction, 1e-13);
}

// Property 8: rigid motions and scaling (square systems).
TEST(G3CurveSolver, IsInvariantUnderRotationTranslationScalingAndReversal) {
  const Eigen::MatrixX2d p = testdata::figure2Points();
  const G3SolveResult base = solveG3Curve(p, t1Conditions());
  ASSERT_TRUE(base.converged);
  const double phi = 0.7;
  Eigen::Matrix2d rot;
  rot << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
  const Eigen::MatrixX2d moved = (p * rot.transpose()).rowwise() + Eigen::RowVector2d(-3.0, 8.0);
  const G3SolveResult rotated = solveG3Curve(
      moved, {Condition::curvature(0, -0.10923218), Condition::curvature(kLast, -0.16584946),
              Condition::tangentAngle(0, 0.546728 + phi)});
  ASSERT_TRUE(rotated.converged);
  EXPECT_LE((rotated.curve->spanLengths() - base.curve->spanLengths()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE((rotated.curve->deBoor().array() - phi - base.curve->deBoor().array()).abs().maxCoeff(), 1e-12);

  const double lambda = 2.5;
  const G3SolveResult scaled = solveG3Curve(
      lambda * p, {Condition::curvature(0, -0.10923218 / lambda), Condition::curvature(kLast, -0.16584946 / lambda),
                   Condition::tangentAngle(0, 0.546728)});
  ASSERT_TRUE(scaled.converged);
  EXPECT_LE((scaled.curve->spanLengths() - lambda * base.curve->spanLengths()).cwiseAbs().maxCoeff(), 1e-11);

  // Reversal: psi -> psi + pi, kappa -> -kappa, conditions move to the other end.
  const Eigen::MatrixX2d reversedPoints = p.colwise().reverse();
  const double endAngle = base.curve->tangentAngle(base.curve->length());
  const G3SolveResult reversed = solveG3Curve(
      reversedPoints, {Condition::curvature(0, 0.16584946), Condition::curvature(kLast, 0.10923218),
                       Condition::tangentAngle(kLast, 0.546728 + std::numbers::pi)});
  ASSERT_TRUE(reversed.converged) << reversed.message;
  EXPECT_LE((reversed.curve->spanLengths().reverse() - base.curve->spanLengths()).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_NEAR(std::remainder(reversed.curve->tangentAngle(0.0) - endAngle - std::numbers::pi, 2 * std::numbers::pi), 0.0,
              1e-11);
}

// Spec sec. 6.1 (d) and property 10: kappa_0 = kappa_n = 0 with the clothoid spline's length is
// infeasible; it must end as a failure, never as "converged".
TEST(G3CurveSolver, ReportsFigure2dAsInfeasible) {
  const Eigen::MatrixX2d p = testdata::figure2Points();
  const std::vector<Condition> conditions = {Condition::curvature(0, 0.0), Condition::curvature(kLast, 0.0),
                                             Condition::totalLength(31.724017364)};
  const G3SolveResult r = solveG3Curve(p, conditions);
  EXPECT_FALSE(r.converged);
  EXPECT_FALSE(r.curve.has_value());
  EXPECT_NE(r.status, G3SolveStatus::Converged);
  EXPECT_GT(r.scaledResidualInf, 1e-6);
  EXPECT_TRUE(r.unknowns.allFinite());

  G3SolverOptions paper;
  paper.paperMode = true;
  const G3SolveResult rp = solveG3Curve(p, conditions, paper);
  EXPECT_FALSE(rp.converged);
  EXPECT_FALSE(rp.curve.has_value());

  G3SolverOptions plain;
  plain.continuation = ContinuationMode::Off;
  const G3SolveResult rd = solveG3Curve(p, conditions, plain);
  EXPECT_FALSE(rd.converged);
  EXPECT_NEAR(rd.residualNorm, 0.0673, 0.01);  // where the damped solver stalls ([P])
}

TEST(G3CurveSolver, ContinuationReachesFeasibleTargetsAndFlagsFigure2dAsLikelyInfeasible) {
  G3SolverOptions always;
  always.continuation = ContinuationMode::Always;
  const G3SolveResult t1 = solveG3Curve(testdata::figure2Points(), t1Conditions(), always);
  ASSERT_TRUE(t1.converged) << t1.message;
  EXPECT_GT(t1.continuationStages, 1);
  EXPECT_NEAR(t1.curve->length(), 31.944481581, 1e-7);
  const G3SolveResult d = solveG3Curve(
      testdata::figure2Points(),
      {Condition::curvature(0, 0.0), Condition::curvature(kLast, 0.0), Condition::totalLength(31.724017364)}, always);
  EXPECT_FALSE(d.converged);
  EXPECT_EQ(d.status, G3SolveStatus::LikelyInfeasible) << d.message;
}

// A point far from the others for the curvature targets makes the spans turn thousands of
// radians, each integrated on 4096 quadrature panels: the solve stops at its work budget
// (maxTangentEvaluationsPerSpan) instead of running on (fuzz_generator found this 4-point
// curve taking 5 s in a release build). The infeasible figure 2d above, whose continuation
// runs the most stages of the reference cases, stays within the budget.
TEST(G3CurveSolver, StopsAtItsWorkBudgetWhenSpansTurnThousandsOfRadians) {
  Eigen::MatrixX2d p(4, 2);
  p << 0.6, 10.5, 4.0, 11.2, 7.2, 7.9, 10.6, 46728.0;
  const std::vector<Condition> conditions = {Condition::curvature(0, -0.10923218), Condition::curvature(kLast, -0.16584946)};
  const G3SolveResult r = solveG3Curve(p, conditions);
  EXPECT_EQ(r.status, G3SolveStatus::WorkLimit) << r.message;
  EXPECT_FALSE(r.converged);
  EXPECT_FALSE(r.curve.has_value());
  EXPECT_STREQ(toString(r.status), "work limit reached (the curve turns too much between its points)");
  // The same points with a budget too small for any solve stop there too, and a budget is
  // an option like the others: it must be positive.
  G3SolverOptions tiny;
  tiny.maxTangentEvaluationsPerSpan = 1.0;
  EXPECT_EQ(solveG3Curve(testdata::figure2Points(), t1Conditions(), tiny).status, G3SolveStatus::WorkLimit);
  G3SolverOptions none;
  none.maxTangentEvaluationsPerSpan = 0.0;
  EXPECT_THROW(solveG3Curve(testdata::figure2Points(), t1Conditions(), none), G3InputError);
}

// A feasible length (the T3 curve's length) with the same end curvatures solves.
TEST(G3CurveSolver, SolvesAFeasibleTotalLengthCondition) {
  const G3SolveResult r = solveG3Curve(testdata::figure2Points(), {Condition::curvature(0, 0.0),
                                                                   Condition::curvature(kLast, 0.0),
                                                                   Condition::totalLength(31.882869227)});
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_NEAR(r.curve->length(), 31.882869227, 1e-9);
}

// Spec sec. 3.7: paper mode (4 undamped pseudo-inverse steps) leaves ~2e-7 on Fig. 3(b).
TEST(G3CurveSolver, PaperModeTakesExactlyFourUndampedSteps) {
  G3SolverOptions paper;
  paper.paperMode = true;
  const G3SolveResult r = solveG3Curve(testdata::figure3Points(),
                                       {Condition::curvature(0, 0.43212079), Condition::curvature(kLast, -0.40518471)},
                                       paper);
  EXPECT_EQ(r.iterations, 4);
  ASSERT_EQ(r.residualHistory.size(), 5u);
  EXPECT_GT(r.residualNorm, 1e-7);  // [P]: about 2e-7 left after 4 steps
  EXPECT_LT(r.residualNorm, 5e-7);
  EXPECT_FALSE(r.converged);  // below the 1e-12 tolerance only after a 5th step
  paper.paperMode = false;
  const G3SolveResult full = solveG3Curve(testdata::figure3Points(),
                                          {Condition::curvature(0, 0.43212079), Condition::curvature(kLast, -0.40518471)},
                                          paper);
  ASSERT_TRUE(full.converged);
  EXPECT_EQ(full.iterations, 5);
}

// Underdetermined (2-condition) examples: min-norm, compared loosely.
TEST(G3CurveSolver, SolvesTheTwoConditionFiguresWithMinimumNormSteps) {
  struct Case {
    const char* name;
    Eigen::MatrixX2d points;
    std::vector<Condition> conditions;
    double length;
    double startAngle;  // [P] psi(0) of the min-norm solution; NaN: not given
  };
  const std::vector<Case> cases = {
      {"Fig. 2(e)", testdata::figure2Points(), {Condition::clothoidSpan(0), Condition::clothoidSpan(kLast)}, 32.0902, std::nan("")},
      {"Fig. 2(f)", testdata::figure2Points(), {Condition::circularArcSpan(0)}, 31.9954, std::nan("")},
      {"Fig. 2 B10", testdata::figure2Points(), {Condition::naturalEnds()}, 31.8834, 0.4539},
      {"Fig. 3(b)", testdata::figure3Points(),
       {Condition::curvature(0, 0.43212079), Condition::curvature(kLast, -0.40518471)}, 43.7641, 2.6498},
      {"Fig. 4(b)", testdata::figure4Points(),
       {Condition::curvature(0, -0.08229731), Condition::curvature(kLast, -0.06879707)}, 55.8596, 0.8305},
      {"Fig. 5 B10", testdata::figure5Points(), {Condition::naturalEnds()}, 74.6084, std::nan("")},
  };
  for (const Case& c : cases) {
    const G3SolveResult r = solveG3Curve(c.points, c.conditions);
    ASSERT_TRUE(r.converged) << c.name << ": " << r.message;
    EXPECT_TRUE(r.underdetermined);
    EXPECT_EQ(r.warnings.size(), 1u) << c.name;
    EXPECT_LE(r.iterations, 8) << c.name;
    EXPECT_NEAR(r.curve->length(), c.length, 2e-3 * c.length) << c.name;
    if (!std::isnan(c.startAngle)) {
      EXPECT_NEAR(r.curve->tangentAngle(0.0), c.startAngle, 2e-3) << c.name;
    }
    expectInterpolates(*r.curve, c.points);
  }
}

TEST(G3CurveSolver, MeetsClothoidAndCircularArcSpanConditions) {
  const Eigen::MatrixX2d p = testdata::figure2Points();
  const G3SolveResult e = solveG3Curve(p, {Condition::clothoidSpan(0), Condition::clothoidSpan(kLast)});
  ASSERT_TRUE(e.converged);
  EXPECT_NEAR(e.curve->curvatureQuadratic(0)[2], 0.0, 1e-12);
  EXPECT_NEAR(e.curve->curvatureQuadratic(6)[2], 0.0, 1e-12);
  EXPECT_NEAR(e.curve->curvature(0.0), -0.1733, 2e-3);
  EXPECT_NEAR(e.curve->curvature(e.curve->length()), -0.5553, 5e-3);
  const G3SolveResult f = solveG3Curve(p, {Condition::circularArcSpan(0)});
  ASSERT_TRUE(f.converged);
  const Eigen::Vector3d q = f.curve->curvatureQuadratic(0);
  EXPECT_NEAR(q[1], 0.0, 1e-12);
  EXPECT_NEAR(q[2], 0.0, 1e-12);
  EXPECT_NEAR(q[0], -0.27246, 2e-3);
}

TEST(G3CurveSolver, MeetsInteriorTangentCurvatureAndRadiusConditions) {
  const Eigen::MatrixX2d p = testdata::figure2Points();
  const G3SolveResult r = solveG3Curve(
      p, {Condition::tangentAngle(3, 0.12), Condition::curvature(5, -0.06), Condition::radiusOfCurvature(2, 14.0)});
  ASSERT_TRUE(r.converged) << r.message;
  const QuadraticCurvatureSpline& c = *r.curve;
  EXPECT_NEAR(c.tangentAngle(c.knots()[3]), 0.12, 1e-10);
  EXPECT_NEAR(c.curvature(c.knots()[5]), -0.06, 1e-10);
  EXPECT_NEAR(c.curvature(c.knots()[2]), 1.0 / 14.0, 1e-10);
}

TEST(G3CurveSolver, AlignsTangentTargetsToTheNearestBranch) {
  const G3SolveResult r = solveG3Curve(
      testdata::figure2Points(),
      {Condition::curvature(0, -0.10923218), Condition::curvature(kLast, -0.16584946),
       Condition::tangentAngle(0, 0.546728 + 4.0 * std::numbers::pi)});
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(r.curve->length(), 31.944481581, 1e-7);
}

TEST(G3CurveSolver, AcceptsACustomCondition) {
  // d_0 - d_{-1} = 0 and d_{n+1} - d_n = 0 written by hand, plus psi(0) = 0.45 (T3 in linear form).
  const Eigen::MatrixX2d p = testdata::figure2Points();
  constexpr int n = 7;
  auto startFlat = [](const Eigen::VectorXd& v, Eigen::Ref<Eigen::RowVectorXd> g) {
    g[n] = -1.0;
    g[n + 1] = 1.0;
    return v[n + 1] - v[n];
  };
  const G3SolveResult r = solveG3Curve(p, {Condition::customCondition("flat start", startFlat),
                                           Condition::curvature(kLast, 0.0), Condition::tangentAngle(0, 0.45)});
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_NEAR(r.curve->length(), 31.882869227, 1e-7);
}

TEST(G3CurveSolver, LevenbergMarquardtReachesTheSameCurvesAndFailsOnFigure2d) {
  G3SolverOptions lm;
  lm.globalization = Globalization::LevenbergMarquardt;
  const G3SolveResult t1 = solveG3Curve(testdata::figure2Points(), t1Conditions(), lm);
  ASSERT_TRUE(t1.converged) << t1.message;
  EXPECT_NEAR(t1.curve->length(), 31.944481581, 1e-7);
  EXPECT_LE(t1.iterations, 8);
  const G3SolveResult t6 = solveG3Curve(
      testdata::figure5Points(), {Condition::curvature(0, 0.0), Condition::curvature(kLast, 0.0), Condition::tangentAngle(0, 1.95)},
      lm);
  ASSERT_TRUE(t6.converged) << t6.message;
  EXPECT_NEAR(t6.curve->length(), 74.607140760, 1e-7);
  const G3SolveResult b10 = solveG3Curve(testdata::figure2Points(), {Condition::naturalEnds()}, lm);
  ASSERT_TRUE(b10.converged) << b10.message;
  EXPECT_NEAR(b10.curve->length(), 31.8834, 2e-3 * 31.8834);
  const G3SolveResult d = solveG3Curve(
      testdata::figure2Points(),
      {Condition::curvature(0, 0.0), Condition::curvature(kLast, 0.0), Condition::totalLength(31.724017364)}, lm);
  EXPECT_FALSE(d.converged);
  EXPECT_FALSE(d.curve.has_value());
}

TEST(G3CurveSolver, ReportsASingularSystemAsAFailure) {
  // a_3 = 0 twice on span 0: three rows, but only two independent ones.
  const G3SolveResult r =
      solveG3Curve(testdata::figure2Points(), {Condition::clothoidSpan(0), Condition::circularArcSpan(0)});
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.status, G3SolveStatus::SingularJacobian);
  EXPECT_FALSE(r.curve.has_value());
  const G3SolveResult ok = solveG3Curve(testdata::figure2Points(), t1Conditions());
  EXPECT_GT(ok.jacobianConditionNumber, 1.0);
  EXPECT_LT(ok.jacobianConditionNumber, 1e8);
}

TEST(G3CurveSolver, FitsMoreThanThreeConditionsByLeastSquaresWhenAllowed) {
  // T1 plus its own (7-digit) interior curvature: nearly consistent, so the fit lands next to T1.
  std::vector<Condition> conditions = t1Conditions();
  conditions.push_back(Condition::curvature(1, -0.2855481));
  G3SolverOptions over;
  over.allowOverdetermined = true;
  const G3SolveResult r = solveG3Curve(testdata::figure2Points(), conditions, over);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_NEAR(r.curve->length(), 31.944481581, 1e-5);
  EXPECT_LT(r.scaledResidualInf, 1e-5);
  EXPECT_EQ(r.warnings.size(), 1u);
}

TEST(G3CurveSolver, SolvesOneAndTwoSpanCurves) {
  Eigen::MatrixX2d two(2, 2);
  two << 0, 0, 3, 4;
  const G3SolveResult line = solveG3Curve(two, {Condition::naturalEnds(), Condition::tangentAngle(0, std::atan2(4.0, 3.0))});
  ASSERT_TRUE(line.converged) << line.message;
  EXPECT_NEAR(line.curve->length(), 5.0, 1e-13);
  // Three points on a circle of radius 2 (centre (0, 2)), with the circle's end curvatures and start tangent.
  Eigen::MatrixX2d three(3, 2);
  three << 0, 0, 2 * std::sin(0.8), 2 * (1 - std::cos(0.8)), 2 * std::sin(2.0), 2 * (1 - std::cos(2.0));
  const G3SolveResult arc =
      solveG3Curve(three, {Condition::curvature(0, 0.5), Condition::curvature(kLast, 0.5), Condition::tangentAngle(0, 0.0)});
  ASSERT_TRUE(arc.converged) << arc.message;
  EXPECT_NEAR(arc.curve->spanLength(0), 1.6, 1e-12);
  EXPECT_NEAR(arc.curve->spanLength(1), 2.4, 1e-12);
}

TEST(G3CurveSolver, RejectsInvalidInput) {
  const Eigen::MatrixX2d p = testdata::figure2Points();
  EXPECT_THROW(solveG3Curve(p, {Condition::curvature(9, 0.0)}), G3InputError);
  EXPECT_THROW(solveG3Curve(p, {Condition::clothoidSpan(7)}), G3InputError);
  EXPECT_THROW(solveG3Curve(p, {Condition::naturalEnds(), Condition::naturalEnds()}), G3InputError);
  G3SolverOptions reject;
  reject.underdetermined = UnderdeterminedPolicy::Reject;
  EXPECT_THROW(solveG3Curve(p, {Condition::naturalEnds()}, reject), G3InputError);
  EXPECT_THROW(solveG3Curve(p, t1Conditions(), {}, Eigen::VectorXd::Ones(5)), G3InputError);
  Eigen::MatrixX2d dup = p;
  dup.row(3) = dup.row(2);
  EXPECT_THROW(solveG3Curve(dup, t1Conditions()), G3InputError);
  // Each invalid option on its own is refused (not only in combination).
  const auto bad = [&](auto&& spoil) {
    G3SolverOptions o;
    spoil(o);
    EXPECT_THROW(solveG3Curve(p, t1Conditions(), o), G3InputError);
  };
  bad([](G3SolverOptions& o) { o.maxIterations = 0; });
  bad([](G3SolverOptions& o) { o.quadratureNodes = 1; });
  bad([](G3SolverOptions& o) { o.maxTurnPerPanel = 0.0; });
  bad([](G3SolverOptions& o) { o.tolerance = 0.0; });
  bad([](G3SolverOptions& o) { o.lineSearchFloor = -1.0; });
  bad([](G3SolverOptions& o) { o.minContinuationStep = std::nan(""); });
  EXPECT_TRUE(solveG3Curve(p, t1Conditions(), G3SolverOptions{}).converged);
}

}  // namespace
}  // namespace ffdkit::geometry::g3
