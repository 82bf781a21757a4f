#include "ffdkit/geometry/cardinal/s_spline_surface.h"

#include <cmath>

#include <gtest/gtest.h>

#include "ffdkit/geometry/cardinal/cardinal_error.h"
#include "ffdkit/geometry/cardinal/s_spline_curve.h"

namespace ffdkit::geometry::cardinal {
namespace {

PointGrid randomGrid(int rows, int cols, unsigned seed) {
  std::srand(seed);
  PointGrid g(rows, cols);
  for (auto& p : g.data) p = Eigen::Vector3d::Random();
  return g;
}

TEST(SSplineSurface, InterpolatesGridExactly) {
  const PointGrid g = randomGrid(7, 9, 11);
  for (bool closedU : {false, true}) {
    for (bool closedV : {false, true}) {
      SSplineSurfaceOptions o;
      o.closedU = closedU;
      o.closedV = closedV;
      o.beta2U = 5.0;
      o.halfWidthV = 3;
      const SSplineSurface s(g, o);
      for (int i = 0; i < 7; ++i)
        for (int j = 0; j < 9; ++j)
          EXPECT_LT((s.evaluate(i, j) - g(i, j)).norm(), 1e-14) << i << "," << j;
    }
  }
}

TEST(SSplineSurface, IsTensorProductOfCurves) {
  // Section 1.3: an iso-line v = j is the S-spline curve through row j of the grid... and in
  // general Q(u, v) = S-spline in v through the u-curves evaluated at u.
  const PointGrid g = randomGrid(6, 5, 12);
  const SSplineSurface s(g);
  const double u = 2.3, v = 1.7;
  Eigen::MatrixX3d column(5, 3);
  for (int j = 0; j < 5; ++j) column.row(j) = SSplineCurve(g.col(j)).evaluate(u).transpose();
  EXPECT_LT((SSplineCurve(column).evaluate(v) - s.evaluate(u, v)).norm(), 1e-14);
}

TEST(SSplineSurface, MovingOnePointChangesOnlyItsSupport) {
  const PointGrid g = randomGrid(14, 14, 13);
  PointGrid moved = g;
  moved(7, 6) += Eigen::Vector3d(0.1, 0.2, 0.3);
  const SSplineSurface a(g), b(moved);
  for (double u = 0.0; u <= 13.0; u += 0.25) {
    for (double v = 0.0; v <= 13.0; v += 0.25) {
      const double diff = (a.evaluate(u, v) - b.evaluate(u, v)).norm();
      if (std::abs(u - 7) >= 4 || std::abs(v - 6) >= 4) {
        EXPECT_EQ(diff, 0.0) << u << "," << v;
      }
    }
  }
}

TEST(SSplineSurface, RejectsTooSmallGrid) {
  EXPECT_THROW(SSplineSurface(randomGrid(1, 4, 1)), CardinalSplineError);
  SSplineSurfaceOptions o;
  o.closedV = true;
  EXPECT_THROW(SSplineSurface(randomGrid(4, 2, 1), o), CardinalSplineError);
}

}  // namespace
}  // namespace ffdkit::geometry::cardinal
