#include "ffdkit/geometry/g3/g3_curve_generator.h"

#include <gtest/gtest.h>

#include "ffdkit/geometry/g3/g3_error.h"
#include "g3_test_data.h"

namespace ffdkit::geometry::g3 {
namespace {

std::vector<Eigen::Vector2d> toVector(const Eigen::MatrixX2d& m) {
  std::vector<Eigen::Vector2d> v;
  for (Eigen::Index i = 0; i < m.rows(); ++i) v.emplace_back(m.row(i).transpose());
  return v;
}

G3CurveParams figure2c() {
  G3CurveParams p;
  p.points = toVector(testdata::figure2Points());
  p.conditions = {Condition::curvature(0, -0.10923218), Condition::curvature(kLast, -0.16584946),
                  Condition::tangentAngle(0, 0.546728)};
  p.z = 1.5;
  return p;
}

TEST(G3CurveGenerator, PolylinePassesThroughTheDataPointsAtEveryDensity) {
  const G3CurveParams params = figure2c();
  for (int perSpan : {4, 32}) {
    const Polyline line = generateG3Curve(params, {perSpan});
    ASSERT_EQ(line.points.rows(), 7 * perSpan + 1);
    EXPECT_FALSE(line.closed);
    for (int i = 0; i <= 7; ++i) {
      EXPECT_LE((line.points.row(i * perSpan).head<2>().transpose() - params.points[i]).norm(), 1e-10) << i;
    }
    EXPECT_TRUE((line.points.col(2).array() == 1.5).all());
  }
}

TEST(G3CurveGenerator, IsDeterministic) {
  const G3CurveParams params = figure2c();
  EXPECT_EQ(generateG3Curve(params, {16}).points, generateG3Curve(params, {16}).points);
}

TEST(G3CurveGenerator, SamplesCurvatureAgainstArcLength) {
  const G3CurveParams params = figure2c();
  const QuadraticCurvatureSpline curve = buildG3Curve(params);
  const CurveSamples samples = sampleG3Curve(params, {8});
  ASSERT_EQ(samples.curvature.size(), 57);
  for (Eigen::Index k = 0; k < samples.curvature.size(); ++k) {
    EXPECT_NEAR(samples.curvature[k], curve.curvature(samples.arcLength[k]), 1e-12);
  }
  EXPECT_NEAR(samples.arcLength[56], 31.944481581, 1e-7);
}

TEST(G3CurveGenerator, ClothoidOutputFollowsTheCurveWithPiecewiseLinearCurvature) {
  G3CurveParams params;
  params.points = toVector(testdata::figure5Points());
  params.clothoidLevels = 2;
  const CurveSamples samples = sampleG3Curve(params, {32});
  ASSERT_EQ(samples.points.rows(), 11 * 4 * 8 + 1);
  EXPECT_LE((samples.points.row(0).transpose() - params.points.front()).norm(), 1e-12);
  EXPECT_LE((samples.points.row(samples.points.rows() - 1).transpose() - params.points.back()).norm(), 1e-9);
  G3CurveParams exact = params;
  exact.clothoidLevels = 0;
  const QuadraticCurvatureSpline curve = buildG3Curve(exact);
  EXPECT_NEAR(samples.arcLength[samples.arcLength.size() - 1], curve.length(), 0.01 * curve.length());
}

TEST(G3CurveGenerator, ThrowsOnInvalidParamsAndOnFailedSolves) {
  G3CurveParams params = figure2c();
  params.clothoidLevels = -1;
  EXPECT_THROW(params.validate(), G3InputError);
  params.clothoidLevels = 0;
  params.points.resize(1);
  EXPECT_THROW(generateG3Curve(params), G3InputError);
  EXPECT_THROW(generateG3Curve(figure2c(), {0}), G3InputError);
  G3CurveParams infeasible = figure2c();
  infeasible.conditions = {Condition::curvature(0, 0.0), Condition::curvature(kLast, 0.0),
                           Condition::totalLength(31.724017364)};
  EXPECT_THROW(generateG3Curve(infeasible), G3SolveError);
}

}  // namespace
}  // namespace ffdkit::geometry::g3
