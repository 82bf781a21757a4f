// Closed surfaces: the closedness check names the open or misoriented edge, and the enclosed
// volume and centroid match closed forms.
#include "ffdkit/ffd/closed_surface.h"

#include <gtest/gtest.h>

#include "closed_surfaces.h"

namespace ffdkit::ffd {
namespace {

TEST(ClosedSurface, BoxVolumeAndCentroidMatchTheirClosedForms) {
  const testing::TestMesh box = testing::boxMesh({1, 2, 3}, {3, 2.5, 7});
  const ClosedSurface surface(box.triangles, 8);
  EXPECT_NEAR(enclosedVolume(box.points, surface), 2.0 * 0.5 * 4.0, 1e-14);
  EXPECT_LT((enclosedCentroid(box.points, surface) - Eigen::Vector3d(2, 2.25, 5)).norm(), 1e-14);
}

TEST(ClosedSurface, SphereVolumeConvergesToFourThirdsPiRCubed) {
  const testing::TestMesh sphere = testing::sphereMesh({0.3, -0.2, 0.1}, 2.0, 200, 400);
  const ClosedSurface surface(sphere.triangles, sphere.points.rows());
  // A polyhedron inscribed in the sphere: below 4/3 pi r^3 by O(h^2).
  const double exact = 4.0 / 3.0 * M_PI * 8.0;
  const double volume = enclosedVolume(sphere.points, surface);
  EXPECT_LT(volume, exact);
  EXPECT_GT(volume, exact * (1 - 1e-3));
  EXPECT_LT((enclosedCentroid(sphere.points, surface) - Eigen::Vector3d(0.3, -0.2, 0.1)).norm(), 1e-12);
}

TEST(ClosedSurface, RejectsAnOpenSurfaceNamingTheEdgeAndTriangle) {
  testing::TestMesh box = testing::boxMesh({0, 0, 0}, {1, 1, 1});
  TriangleMatrix open = box.triangles.topRows(11);
  try {
    ClosedSurface surface(open, 8);
    FAIL() << "no error";
  } catch (const ConstraintError& e) {
    EXPECT_NE(std::string(e.what()).find("open"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("triangle"), std::string::npos) << e.what();
  }
}

TEST(ClosedSurface, RejectsInconsistentOrientationAndBadIndices) {
  testing::TestMesh box = testing::boxMesh({0, 0, 0}, {1, 1, 1});
  TriangleMatrix flipped = box.triangles;
  std::swap(flipped(3, 1), flipped(3, 2));
  EXPECT_THROW(ClosedSurface(flipped, 8), ConstraintError);
  TriangleMatrix bad = box.triangles;
  bad(0, 0) = 8;
  EXPECT_THROW(ClosedSurface(bad, 8), ConstraintError);
  bad(0, 0) = bad(0, 1);
  EXPECT_THROW(ClosedSurface(bad, 8), ConstraintError);
  EXPECT_THROW(enclosedVolume(Eigen::MatrixX3d::Zero(7, 3), ClosedSurface(box.triangles, 8)), ConstraintError);
}

}  // namespace
}  // namespace ffdkit::ffd
