#include "ffdkit/geometry/cardinal/sigma_refinement.h"

#include <gtest/gtest.h>

#include "ffdkit/geometry/cardinal/cardinal_error.h"
#include "ffdkit/geometry/cardinal/shape_points.h"

namespace ffdkit::geometry::cardinal {
namespace {

SigmaKnots specT15Knots(bool closed) {
  Eigen::VectorXd t(6);
  t << 0, 1, 3, 4, 7, 8;
  SigmaKnotsOptions o;
  o.closed = closed;
  Eigen::VectorXd b(closed ? 5 : 6);
  if (closed) {
    b << 0, 2, 0, 7, 1;
  } else {
    b << 0, 2, 0, 7, 1, 0;
  }
  return SigmaKnots(t, b, o);
}

TEST(SigmaRefinement, CurveGeometryUnchangedSpecT15) {
  // P12 / T15: insert {0.3, 2, 2.5, 5.5, 7.9}; max difference < 1e-12; new beta2 = 0.
  const std::vector<double> inserted = {0.3, 2, 2.5, 5.5, 7.9};
  for (bool closed : {false, true}) {
    std::srand(41);
    const SigmaKnots k = specT15Knots(closed);
    const SigmaCurve c(k, Eigen::MatrixX3d::Random(k.pointCount(), 3),
                       Eigen::MatrixX3d::Random(k.shapeCount(), 3));
    const SigmaCurve r = refine(c, inserted);
    ASSERT_EQ(r.knots().last(), k.last() + 5);
    double worst = 0.0;
    for (int step = 0; step <= 800; ++step) {
      const double x = step / 100.0;
      worst = std::max(worst, (r.evaluate(x) - c.evaluate(x)).norm());
    }
    EXPECT_LT(worst, 1e-12) << (closed ? "closed" : "open");
    const Eigen::VectorXd& t = r.knots().knots();
    for (int i = 0; i < r.knots().beta2Values().size(); ++i) {
      const bool isNew = std::find(inserted.begin(), inserted.end(), t[i]) != inserted.end();
      if (isNew) {
        EXPECT_EQ(r.knots().beta2(i), 0.0);
      }
    }
    EXPECT_EQ(r.knots().beta2(6), 7.0);  // the old knot t = 4 keeps its tension
  }
}

TEST(SigmaRefinement, IgnoresDuplicatesAndRejectsOutsideKnots) {
  const SigmaCurve c = interpolateSigmaCurve(SigmaKnots::uniform(3), Eigen::MatrixX3d::Random(4, 3));
  EXPECT_EQ(refine(c, {1.0, 1.5, 1.5}).knots().last(), 4);
  EXPECT_THROW(refine(c, {3.0}), CardinalSplineError);
  EXPECT_THROW(refine(c, {-0.5}), CardinalSplineError);
}

TEST(SigmaRefinement, SurfaceGeometryUnchanged) {
  std::srand(42);
  Eigen::VectorXd tu(5);
  tu << 0, 1, 2.5, 3, 4.5;
  Eigen::VectorXd bu(5);
  bu << 0, 3, 0, 1, 0;
  const SigmaKnots ku(tu, bu);
  SigmaKnotsOptions closed;
  closed.closed = true;
  Eigen::VectorXd tv(5);
  tv << 0, 2, 3, 3.5, 6;
  const SigmaKnots kv(tv, Eigen::Vector4d(0, 2, 0, 5), closed);
  SigmaSurface s{ku, kv, PointGrid(5, 4), PointGrid(6, 4), PointGrid(5, 4), PointGrid(6, 4)};
  for (PointGrid* g : {&s.P, &s.Pu, &s.Pv, &s.Puv})
    for (auto& p : g->data) p = Eigen::Vector3d::Random();
  const SigmaSurface r = refine(s, {0.5, 2.0, 4.0}, {1.0, 3.2, 5.0});
  EXPECT_EQ(r.knotsU.last(), 7);
  EXPECT_EQ(r.knotsV.last(), 7);
  double worst = 0.0;
  for (int a = 0; a <= 45; ++a)
    for (int b = 0; b <= 60; ++b)
      worst = std::max(worst, (r.evaluate(a / 10.0, b / 10.0) - s.evaluate(a / 10.0, b / 10.0)).norm());
  EXPECT_LT(worst, 1e-12);
}

}  // namespace
}  // namespace ffdkit::geometry::cardinal
