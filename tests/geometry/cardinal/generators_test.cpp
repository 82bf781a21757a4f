#include "ffdkit/geometry/cardinal/generators.h"

#include <cmath>

#include <gtest/gtest.h>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

namespace ffdkit::geometry::cardinal {
namespace {

Eigen::MatrixX3d circlePoints(int count, double radius) {
  Eigen::MatrixX3d p(count, 3);
  for (int k = 0; k < count; ++k) {
    p.row(k) << radius * std::cos(2 * M_PI * k / count), radius * std::sin(2 * M_PI * k / count), 0;
  }
  return p;
}

PointGrid wavyGrid(int rows, int cols) {
  PointGrid g(rows, cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) g(i, j) = Eigen::Vector3d(i, j, 0.3 * std::sin(i) * std::cos(0.7 * j));
  return g;
}

TEST(Generators, SSplineCurveSamplesAndIsDeterministic) {
  SSplineCurveParams p;
  p.points = circlePoints(8, 1.0);
  p.options.end = SSplineEnd::Closed;
  const Polyline a = generateSSplineCurve(p, {4});
  const Polyline b = generateSSplineCurve(p, {4});
  EXPECT_TRUE(a.closed);
  ASSERT_EQ(a.points.rows(), 32);
  EXPECT_EQ((a.points - b.points).norm(), 0.0);
  for (int k = 0; k < 8; ++k) EXPECT_LT((a.points.row(4 * k) - p.points.row(k)).norm(), 1e-14);
  EXPECT_EQ(generateSSplineCurve(p, {9}).points.rows(), 72);
}

TEST(Generators, SigmaCurveCurvatureOfACircleIsAboutOneOverRadius) {
  SigmaSplineCurveParams p;
  p.points = circlePoints(24, 2.0);
  p.closed = true;
  p.spacing = KnotSpacing::ChordLength;
  const CurvatureSamples c = sigmaSplineCurveCurvature(p, {8});
  ASSERT_EQ(c.curvature.size(), 24 * 8);
  for (Eigen::Index k = 0; k < c.curvature.size(); ++k) {
    EXPECT_NEAR(c.curvature[k], 0.5, 5e-3);
    EXPECT_NEAR(c.torsion[k], 0.0, 1e-9);
    // The principal normal points to the centre.
    EXPECT_LT(c.normals.row(k).dot(c.points.row(k)), 0.0);
  }
  // Arc length of the closed loop without its last span: 23/24 of the circumference.
  EXPECT_NEAR(c.arcLength[c.arcLength.size() - 1], 2 * M_PI * 2.0 * (1.0 - 1.0 / 192), 1e-3);
  const Polyline line = generateSigmaSplineCurve(p, {8});
  EXPECT_TRUE(line.closed);
  EXPECT_EQ(line.points.rows(), 24 * 8);
}

TEST(Generators, SSplineCurvatureIsFiniteEverywhere) {
  SSplineCurveParams p;
  p.points = circlePoints(24, 3.0).topRows(13);
  // w = 12: with the thesis's w = 4 the truncation makes Q'' jump at every knot by
  // S_0''(w-) (P_{k+w} - P_{k-w}), about 25 % of the curvature here (see
  // SSplineCurve.SecondDerivativeJumpsAtKnotsByTruncationTerm).
  p.options.halfWidth = 12;
  const CurvatureSamples c = sSplineCurveCurvature(p, {5});
  EXPECT_EQ(c.curvature.size(), 61);
  EXPECT_TRUE(c.curvature.allFinite());
  EXPECT_TRUE(c.torsion.allFinite());
  // Mid-curve, beyond the reach of the repeated end points (w = 4), the curve is close to the
  // circle of radius 3.
  EXPECT_NEAR(c.curvature[30], 1.0 / 3.0, 1e-2);
}

TEST(Generators, SurfacesTessellateAtTheRequestedDensity) {
  SSplineSurfaceParams s;
  s.points = wavyGrid(5, 4);
  const TriangleMesh ms = generateSSplineSurface(s, {3, 2});
  EXPECT_EQ(ms.vertices.rows(), 13 * 7);
  SigmaSplineSurfaceParams g;
  g.points = wavyGrid(5, 4);
  g.spacing = KnotSpacing::ChordLength;
  const SurfaceTessellation t = generateSigmaSplineSurfaceWithNormals(g, {3, 2});
  EXPECT_EQ(t.mesh.vertices.rows(), 13 * 7);
  EXPECT_EQ(t.normals.rows(), 13 * 7);
  EXPECT_LT((t.mesh.vertices.row(0).transpose() - g.points(0, 0)).norm(), 1e-12);
}

TEST(Generators, BlendMeshCoversBothSurfacesAndTheGap) {
  SplineBlendParams b;
  b.first.points = wavyGrid(5, 3);
  b.second.points = wavyGrid(5, 4);
  for (auto& p : b.second.points.data) p.y() += 5.0;
  b.second.knotsU = Eigen::VectorXd::LinSpaced(5, 0.0, 4.0);
  b.second.knotsV = Eigen::VectorXd::LinSpaced(4, 0.0, 3.0);
  const TriangleMesh all = generateSplineBlend(b, {2, 2});
  // v spans: 2 (first) + 2 (blend) + 3 (second) = 7; u spans 4.
  EXPECT_EQ(all.vertices.rows(), 9 * 15);
  b.part = BlendPart::BlendOnly;
  EXPECT_EQ(generateSplineBlend(b, {2, 2}).vertices.rows(), 9 * 5);
}

TEST(Generators, ChordLengthKnotsAverageTheChordsOverTheOtherDirection) {
  // generators.h: t_{i+1} - t_i = |P_{i+1} - P_i|, averaged over the other direction for surfaces,
  // written out here over every row and column of an uneven grid (closed v adds the closing chord).
  PointGrid g(4, 5);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 5; ++j) g(i, j) = Eigen::Vector3d(i * i * 0.5 + 0.1 * j, std::exp(0.3 * j) + 0.2 * i, 0.1 * i * j);
  SigmaSplineSurfaceParams params;
  params.points = g;
  params.spacing = KnotSpacing::ChordLength;
  params.closedV = true;
  const SigmaSurface s = buildSigmaSurface(params);
  Eigen::VectorXd tu = Eigen::VectorXd::Zero(4), tv = Eigen::VectorXd::Zero(6);
  for (int i = 0; i + 1 < 4; ++i) {
    double sum = 0.0;
    for (int j = 0; j < 5; ++j) sum += (g(i + 1, j) - g(i, j)).norm();
    tu[i + 1] = tu[i] + sum / 5.0;
  }
  for (int j = 0; j < 5; ++j) {
    double sum = 0.0;
    for (int i = 0; i < 4; ++i) sum += (g(i, (j + 1) % 5) - g(i, j)).norm();
    tv[j + 1] = tv[j] + sum / 4.0;
  }
  EXPECT_LT((s.knotsU.knots() - tu).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((s.knotsV.knots() - tv).cwiseAbs().maxCoeff(), 1e-14);
  // Curves: the plain chord lengths.
  SigmaSplineCurveParams curve;
  curve.points = circlePoints(5, 2.0).topRows(4);
  curve.points(3, 2) = 1.0;
  curve.spacing = KnotSpacing::ChordLength;
  const SigmaCurve c = buildSigmaCurve(curve);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(c.knots().knots()[k + 1] - c.knots().knots()[k], (curve.points.row(k + 1) - curve.points.row(k)).norm(), 1e-14) << k;
  }
}

TEST(Generators, ValidationNamesTheField) {
  SigmaSplineCurveParams p;
  p.points = Eigen::MatrixX3d::Zero(1, 3);
  try {
    p.validate();
    FAIL() << "expected CardinalSplineError";
  } catch (const CardinalSplineError& e) {
    EXPECT_NE(std::string(e.what()).find("SigmaSplineCurveParams.points"), std::string::npos);
  }
  SigmaSplineCurveParams q;
  q.points = circlePoints(4, 1.0);
  q.knots = Eigen::Vector3d(0, 1, 2);
  EXPECT_THROW(q.validate(), CardinalSplineError);
  SSplineSurfaceParams s;
  s.points = wavyGrid(1, 3);
  EXPECT_THROW(s.validate(), CardinalSplineError);
}

}  // namespace
}  // namespace ffdkit::geometry::cardinal
