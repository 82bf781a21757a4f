#include "ffdkit/geometry/g3/bi_clothoid.h"

#include <cmath>

#include <gtest/gtest.h>

#include "ffdkit/geometry/g3/g3_curve_solver.h"
#include "ffdkit/geometry/g3/g3_error.h"
#include "g3_test_data.h"

namespace ffdkit::geometry::g3 {
namespace {

BiClothoidEnds endsOfSpan(const QuadraticCurvatureSpline& c, int i) {
  BiClothoidEnds e;
  e.startPoint = c.spanStarts().row(i).transpose();
  e.endPoint = c.spanStarts().row(i + 1).transpose();
  e.startAngle = c.bezierOrdinates()[3 * i];
  e.endAngle = c.bezierOrdinates()[3 * i + 3];
  const Eigen::Vector3d q = c.curvatureQuadratic(i);
  e.startCurvature = q[0];
  const double ds = c.spanLength(i);
  e.endCurvature = q[0] + ds * (q[1] + ds * q[2]);
  return e;
}

QuadraticCurvatureSpline t3Curve() {
  const G3SolveResult r = solveG3Curve(testdata::figure2Points(), {Condition::curvature(0, 0.0),
                                                                   Condition::curvature(kLast, 0.0),
                                                                   Condition::tangentAngle(0, 0.45)});
  EXPECT_TRUE(r.converged);
  return *r.curve;
}

// Spec sec. 6.3 T3 [P] bi-clothoid lengths and sec. 7 property 11.
TEST(BiClothoid, MatchesTheReferenceSplitsAndEndDataOfT3) {
  const QuadraticCurvatureSpline c = t3Curve();
  const double expected[7][2] = {{1.7710013, 1.7762342}, {2.4013538, 2.3849001}, {2.1720980, 2.1857916},
                                 {2.4181063, 2.4049617}, {2.8277214, 2.8302370}, {2.4655609, 2.4706982},
                                 {1.9055838, 1.8953475}};
  const Eigen::MatrixX2d p = testdata::figure2Points();
  for (int i = 0; i < 7; ++i) {
    const BiClothoidEnds e = endsOfSpan(c, i);
    const BiClothoidResult r = fitBiClothoid(e, c.spanLength(i));
    ASSERT_TRUE(r.converged) << i;
    EXPECT_LE(r.iterations, 4) << i;
    EXPECT_NEAR(r.arcs[0].length, expected[i][0], 1e-7) << i;
    EXPECT_NEAR(r.arcs[1].length, expected[i][1], 1e-7) << i;
    const double h = (e.endPoint - e.startPoint).norm();
    EXPECT_LE((r.arcs[1].endPoint() - e.endPoint).norm(), 1e-12 * h) << i;
    EXPECT_NEAR(r.arcs[0].startAngle, e.startAngle, 1e-14);
    EXPECT_NEAR(r.arcs[0].startCurvature, e.startCurvature, 1e-14);
    EXPECT_NEAR(r.arcs[1].endAngle(), e.endAngle, 1e-14);
    EXPECT_NEAR(r.arcs[1].endCurvature(), e.endCurvature, 1e-14);
    EXPECT_NEAR(r.arcs[0].endCurvature(), r.arcs[1].startCurvature, 1e-12);
    EXPECT_NEAR(r.arcs[0].endAngle(), r.arcs[1].startAngle, 1e-14);
    EXPECT_LE((r.arcs[0].endPoint() - r.arcs[1].start).norm(), 1e-15 * h);
    EXPECT_LT(std::abs(r.arcs[0].length + r.arcs[1].length - c.spanLength(i)), 0.02 * c.spanLength(i));
  }
}

TEST(BiClothoid, ReproducesASingleClothoidFromAPerturbedStart) {
  ClothoidArc arc;
  arc.start = {1.0, -2.0};
  arc.startAngle = 0.3;
  arc.startCurvature = -0.2;
  arc.sharpness = 0.15;
  arc.length = 4.0;
  BiClothoidEnds e{arc.start, arc.endPoint(), arc.startAngle, arc.endAngle(), arc.startCurvature, arc.endCurvature()};
  const BiClothoidResult r = fitBiClothoid(e, 4.2);
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(r.arcs[0].length + r.arcs[1].length, 4.0, 1e-10);
  for (double s : {0.5, 1.7, 3.1}) {
    const double s1 = s - r.arcs[0].length;
    const Eigen::Vector2d q = s1 < 0 ? r.arcs[0].position(s) : r.arcs[1].position(s1);
    EXPECT_LE((q - arc.position(s)).norm(), 1e-10) << s;
  }
  // The symmetric split reproduces it exactly.
  const auto exact = makeBiClothoid(e, 2.0, 2.0);
  EXPECT_NEAR(exact[0].sharpness, 0.15, 1e-14);
  EXPECT_NEAR(exact[1].sharpness, 0.15, 1e-14);
  EXPECT_LE((exact[1].endPoint() - arc.endPoint()).norm(), 1e-14);
}

TEST(BiClothoid, ClothoidArcIsACircleWithoutSharpnessAndALineWithoutCurvature) {
  ClothoidArc circle{{0.0, 0.0}, 0.0, 0.5, 0.0, 3.0};
  EXPECT_LE((circle.position(3.0) - Eigen::Vector2d(2.0 * std::sin(1.5), 2.0 * (1.0 - std::cos(1.5)))).norm(), 1e-14);
  ClothoidArc line{{1.0, 1.0}, 0.25, 0.0, 0.0, 2.0};
  EXPECT_LE((line.endPoint() - Eigen::Vector2d(1.0 + 2.0 * std::cos(0.25), 1.0 + 2.0 * std::sin(0.25))).norm(), 1e-15);
}

TEST(BiClothoid, RejectsInvalidInput) {
  BiClothoidEnds e;
  e.endPoint = {1.0, 0.0};
  EXPECT_THROW(fitBiClothoid(e, 0.0), G3InputError);
  EXPECT_THROW(makeBiClothoid(e, -1.0, 1.0), G3InputError);
  BiClothoidEnds same;
  EXPECT_THROW(fitBiClothoid(same, 1.0), G3InputError);
  e.startAngle = std::nan("");
  EXPECT_THROW(fitBiClothoid(e, 1.0), G3InputError);
}

}  // namespace
}  // namespace ffdkit::geometry::g3
