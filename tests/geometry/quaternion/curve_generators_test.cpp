#include "ffdkit/geometry/quaternion/curve_generators.h"

#include <cmath>

#include <gtest/gtest.h>

#include "ffdkit/geometry/quaternion/quaternion_error.h"
#include "ffdkit/geometry/quaternion/tube_mesh.h"

namespace ffdkit::geometry::quaternion {
namespace {

TEST(CurveGenerators, QiInterpolateIsDeterministicAndRegeneratesAtAnotherDensity) {
  const QiInterpolateParams p = exampleQiInterpolateParams();
  const Polyline a = generateQiInterpolate(p, {64});
  const Polyline b = generateQiInterpolate(p, {64});
  const Polyline fine = generateQiInterpolate(p, {127});
  ASSERT_EQ(a.points.rows(), 64);
  ASSERT_EQ(fine.points.rows(), 127);
  EXPECT_EQ((a.points - b.points).cwiseAbs().maxCoeff(), 0.0);
  for (int k = 0; k < 64; ++k) EXPECT_LE((a.points.row(k) - fine.points.row(2 * k)).norm(), 1e-12);
  // The polyline passes through the data points' neighbourhood at both ends.
  EXPECT_LE((a.points.row(0) - p.points.row(0)).norm(), 1e-14);
  EXPECT_LE((a.points.row(63) - p.points.row(6)).norm(), 1e-9);
}

TEST(CurveGenerators, ProfilesCarryCurvatureAndTorsionAgainstArcLength) {
  const CurveProfile prof = profileSphereTangent(exampleSphereTangentParams(), {101});
  ASSERT_EQ(prof.arcLength.size(), 101);
  EXPECT_NEAR(prof.curvature[0], 1.361835, 1e-6);
  EXPECT_NEAR(prof.torsion[50], 1.278711, 1e-6);
  EXPECT_NEAR(prof.arcLength[100], 2.037009282320, 1e-8);
  const Eigen::MatrixX3d tips = curvatureCombTips(prof, 0.1);
  EXPECT_NEAR((tips.row(0) - prof.points.row(0)).norm(), 0.1 * prof.curvature[0], 1e-12);
  const CurveProfile fit = profileQiFit(exampleQiFitParams(), {200});
  EXPECT_GT(fit.curvature.maxCoeff(), 0.0);
  EXPECT_LE(fit.torsion.cwiseAbs().maxCoeff(), 1e-6);  // planar fit
}

TEST(CurveGenerators, ReportFailuresAndInvalidParamsAsTypedErrors) {
  SphereTangentParams noSolution;
  noSolution.segment.endPoint = Eigen::Vector3d(1, 0.5, 0.5);
  noSolution.segment.endTangent = Eigen::Vector3d(0, -1, 0);
  try {
    generateSphereTangent(noSolution);
    FAIL() << "expected a failure";
  } catch (const QuaternionCurveError& e) {
    EXPECT_NE(std::string(e.what()).find("sphere-tangent"), std::string::npos);
  }
  QiFitParams badBreaks = exampleQiFitParams();
  badBreaks.breaks = {0, 15, 15, 30};
  EXPECT_THROW(generateQiFit(badBreaks), QuaternionCurveError);
  EXPECT_THROW(generateQiInterpolate(exampleQiInterpolateParams(), {1}), QuaternionCurveError);
  EXPECT_THROW(generateQiInterpolate(QiInterpolateParams{}), QuaternionCurveError);
}

TEST(TubeMesh, RingsSurroundThePolylineAtTheRadius) {
  const Polyline line = generateQiInterpolate(exampleQiInterpolateParams(), {40});
  const TriangleMesh tube = tubeMesh(line, 0.05, 10);
  ASSERT_EQ(tube.vertices.rows(), 400);
  ASSERT_EQ(tube.triangles.rows(), 2 * 39 * 10);
  for (int k = 0; k < 40; ++k) {
    for (int j = 0; j < 10; ++j) EXPECT_NEAR((tube.vertices.row(k * 10 + j) - line.points.row(k)).norm(), 0.05, 1e-12);
  }
  EXPECT_THROW(tubeMesh(line, 0.0, 10), QuaternionCurveError);
}

}  // namespace
}  // namespace ffdkit::geometry::quaternion
