// The curvature comb of a polyline (app/render/include/ffdkit/render/curvature_comb.h): the
// discrete curvature of the circle through three points, its normal, and segment chaining.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "ffdkit/render/curvature_comb.h"
#include "ffdkit/scenes/generator.h"
#include "ffdkit/scenes/scene_file.h"
#include "test_curves.h"

namespace ffdkit::app {
namespace {

using testing::circle;

TEST(CurvatureComb, ACircleHasCurvatureOneOverRadiusTowardTheCentre) {
  const double r = 2.5;
  const Eigen::Vector3d centre(1.0, -2.0, 0.5);
  const CurvatureComb comb = curvatureComb(circle(r, 64, centre), true, 0.8);
  ASSERT_EQ(comb.bases.rows(), 64);  // closed: a tooth at every point
  for (Eigen::Index k = 0; k < comb.bases.rows(); ++k) {
    EXPECT_NEAR(comb.curvature(k), 1.0 / r, 1e-9);  // the circle through 3 points of a circle
    const Eigen::Vector3d base = comb.bases.row(k).transpose(), tip = comb.tips.row(k).transpose();
    EXPECT_NEAR((tip - base).norm(), 0.8 / r, 1e-9);
    EXPECT_LT(((tip - base).normalized() - (centre - base).normalized()).norm(), 1e-9);  // toward the centre
  }
}

TEST(CurvatureComb, AnOpenPolylineHasNoTeethAtItsEnds) {
  const Eigen::MatrixX3d points = circle(1.0, 64);
  const CurvatureComb open = curvatureComb(points, false, 1.0);
  ASSERT_EQ(open.bases.rows(), 62);
  EXPECT_EQ(open.bases.row(0), points.row(1));
  EXPECT_EQ(open.bases.row(61), points.row(62));
  EXPECT_EQ(curvatureComb(points.topRows(2), false, 1.0).bases.rows(), 0);
}

TEST(CurvatureComb, AStraightLineHasZeroLengthTeeth) {
  Eigen::MatrixX3d line(20, 3);
  for (int i = 0; i < 20; ++i) line.row(i) = Eigen::RowVector3d(0.3 * i, 0.17 * i, -0.2 * i);
  const CurvatureComb comb = curvatureComb(line, false, 5.0);
  ASSERT_EQ(comb.bases.rows(), 18);
  EXPECT_LT(comb.curvature.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((comb.tips - comb.bases).cwiseAbs().maxCoeff(), 1e-9);
  // Repeated points: no circle, no tooth, no NaN.
  Eigen::MatrixX3d repeated(3, 3);
  repeated << 0, 0, 0, 0, 0, 0, 1, 0, 0;
  const CurvatureComb degenerate = curvatureComb(repeated, false, 1.0);
  EXPECT_EQ(degenerate.curvature(0), 0.0);
  EXPECT_TRUE(degenerate.tips.allFinite());
}

TEST(CurvatureComb, FollowsADeformation) {
  // A unit circle stretched into the ellipse x/2, y/1: curvature a/b^2 = 2 at (2, 0), b/a^2 = 1/4 at (0, 1).
  const int n = 400;
  Eigen::MatrixX3d points = circle(1.0, n);
  const CurvatureComb before = curvatureComb(points, true, 1.0);
  points.col(0) *= 2.0;
  const CurvatureComb after = curvatureComb(points, true, 1.0);
  EXPECT_GT((after.tips - before.tips).cwiseAbs().maxCoeff(), 0.5);
  EXPECT_NEAR(after.curvature(0), 2.0, 0.01);
  EXPECT_NEAR(after.curvature(n / 4), 0.25, 0.01);
  EXPECT_LT(after.tips(0, 0), after.bases(0, 0) - 1.9);  // still inward: along -x at (2, 0)
}

TEST(CurvatureComb, AgreesWithAGeneratorsExactProfile) {
  // The qi-interpolate sample at rest: the discrete comb of its polyline against the
  // generator's exact curvature and principal normals at the same samples.
  const scenes::Scene scene = scenes::readScene(std::filesystem::path(FFDKIT_SOURCE_DIR "/scenes/examples/qi-interpolate"));
  const scenes::SceneObject& curve = scene.objects().front();
  const auto& source = std::get<scenes::GeneratedSource>(curve.source);
  const scenes::CurvatureProfile exact =
      scenes::builtinGenerators().profile(source.generator, source.parameters, source.density);
  ASSERT_NE(exact.torsion.size(), 0);  // a space curve: its principal normal has no sign choice
  const auto chains = segmentChains(curve.mesh.segments, curve.mesh.points.rows());
  ASSERT_EQ(chains.size(), 1u);
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(chains[0].size()), 3);
  for (std::size_t k = 0; k < chains[0].size(); ++k) points.row(Eigen::Index(k)) = curve.mesh.points.row(chains[0][k]);
  const CurvatureComb comb = curvatureComb(points, false, 1.0);
  const double maxCurvature = exact.curvature.cwiseAbs().maxCoeff();
  double worstCurvature = 0.0, worstNormal = 0.0;
  for (Eigen::Index k = 0; k < comb.bases.rows(); ++k) {
    Eigen::Index nearest = 0;
    const double d2 = (exact.points.rowwise() - comb.bases.row(k)).rowwise().squaredNorm().minCoeff(&nearest);
    ASSERT_LT(d2, 1e-12) << "the polyline samples are the profile's samples";
    const double kappa = std::abs(exact.curvature(nearest));
    worstCurvature = std::max(worstCurvature, std::abs(comb.curvature(k) - kappa) / maxCurvature);
    if (kappa > 0.1 * maxCurvature) {  // the normal is well defined away from straight parts
      const Eigen::Vector3d n = (comb.tips.row(k) - comb.bases.row(k)).transpose().normalized();
      worstNormal = std::max(worstNormal, (n - exact.normals.row(nearest).transpose()).norm());
    }
  }
  RecordProperty("worstCurvature", std::to_string(worstCurvature));
  EXPECT_LT(worstCurvature, 0.03);  // measured 0.007 of the largest curvature (254 samples)
  EXPECT_LT(worstNormal, 0.1);      // measured 0.012
}

TEST(SegmentChains, ChainsSegmentsInCurveOrderAndFindsLoops) {
  // An open chain given out of order and reversed, and a separate triangle loop.
  Eigen::MatrixX2i segments(6, 2);
  segments << 2, 1, 0, 1, 3, 2, 4, 5, 5, 6, 6, 4;
  const auto chains = segmentChains(segments, 7);
  ASSERT_EQ(chains.size(), 2u);
  const std::vector<int> open = chains[0].front() == 0 ? chains[0] : std::vector<int>(chains[0].rbegin(), chains[0].rend());
  EXPECT_EQ(open, std::vector<int>({0, 1, 2, 3}));
  ASSERT_EQ(chains[1].size(), 4u);
  EXPECT_EQ(chains[1].front(), chains[1].back());  // closed
}

}  // namespace
}  // namespace ffdkit::app
