#include "ffdkit/geometry/cardinal/shape_points.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "ffdkit/geometry/cardinal/cardinal_error.h"
#include "test_support.h"

namespace ffdkit::geometry::cardinal {
namespace {

Eigen::MatrixX3d planar(std::initializer_list<std::pair<double, double>> xy) {
  Eigen::MatrixX3d p(static_cast<Eigen::Index>(xy.size()), 3);
  int r = 0;
  for (const auto& [x, y] : xy) p.row(r++) << x, y, 0;
  return p;
}

SigmaKnots nonUniformKnots() {
  Eigen::VectorXd t(7);
  t << 0, 0.5, 2, 2.7, 4, 6.5, 7;
  return SigmaKnots(t);
}

TEST(HeuristicShapePoints, MatchSpecT10) {
  const Eigen::MatrixX3d p = planar({{0, 0}, {1, 1}, {2, 0}, {3, 1}, {4, 0}, {6, 2}});
  const Eigen::MatrixX3d s = sigmaShapePoints(SigmaKnots::uniform(5), p, ShapeMode::Heuristic);
  EXPECT_LT((s.row(1 + 1) - Eigen::RowVector3d(1.5, 0.5, 0)).norm(), 1e-14);
  EXPECT_LT((s.row(2 + 1) - Eigen::RowVector3d(2.5, 0.5, 0)).norm(), 1e-14);
  EXPECT_LT((s.row(3 + 1) - Eigen::RowVector3d(3.512095, 0.425464, 0)).norm(), 1e-6);
}

TEST(HeuristicShapePoints, KeepCollinearDataOnTheLine) {
  const Eigen::MatrixX3d p = planar({{0, 0}, {0.2, 0.4}, {1, 2}, {1.5, 3}, {3, 6}});
  const SigmaCurve c = interpolateSigmaCurve(SigmaKnots::uniform(4), p, ShapeMode::Heuristic);
  for (double x = 0.0; x <= 4.0; x += 0.1) {
    const Eigen::Vector3d q = c.evaluate(x);
    EXPECT_NEAR(q.y(), 2.0 * q.x(), 1e-13);
  }
}

TEST(HeuristicShapePoints, SimilarityButNotAffineInvariant) {
  // P14': a rotation + uniform scale commutes, a non-uniform scale does not.
  std::srand(31);
  const Eigen::MatrixX3d p = Eigen::MatrixX3d::Random(8, 3);
  const SigmaKnots k = SigmaKnots::uniform(7);
  const Eigen::MatrixX3d s = sigmaShapePoints(k, p, ShapeMode::Heuristic);
  const Eigen::Matrix3d rot = 2.5 * Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())
                                        .toRotationMatrix();
  const Eigen::RowVector3d t(1, -2, 3);
  const Eigen::MatrixX3d sr =
      sigmaShapePoints(k, (p * rot.transpose()).rowwise() + t, ShapeMode::Heuristic);
  EXPECT_LT(((s * rot.transpose()).rowwise() + t - sr).cwiseAbs().maxCoeff(), 1e-12);
  const Eigen::Matrix3d stretch = Eigen::Vector3d(1, 3, 0.5).asDiagonal();
  const Eigen::MatrixX3d ss = sigmaShapePoints(k, p * stretch, ShapeMode::Heuristic);
  EXPECT_GT((s * stretch - ss).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(HeuristicShapePoints, MovingAPointChangesOnlyNearbyShapePoints) {
  // Kuriyama 1996, sec. 3.3.4: moving P_k changes Phat_{k-2..k+1} only.
  std::srand(32);
  const Eigen::MatrixX3d p = Eigen::MatrixX3d::Random(12, 3);
  const SigmaKnots k = SigmaKnots::uniform(11);
  Eigen::MatrixX3d q = p;
  q.row(6) += Eigen::RowVector3d(0.5, 0.1, -0.3);
  const Eigen::MatrixX3d a = sigmaShapePoints(k, p, ShapeMode::Heuristic);
  const Eigen::MatrixX3d b = sigmaShapePoints(k, q, ShapeMode::Heuristic);
  for (int i = -1; i <= 11; ++i) {
    const double d = (a.row(i + 1) - b.row(i + 1)).norm();
    if (i < 4 || i > 7) {
      EXPECT_EQ(d, 0.0) << i;
    }
  }
}

TEST(HeuristicShapePoints, CurveChangesOnlyWithinThreeIntervals) {
  // P7, heuristic default: moving P_k changes the curve only on [t_{k-3}, t_{k+3}].
  std::srand(40);
  const Eigen::MatrixX3d p = Eigen::MatrixX3d::Random(13, 3);
  const SigmaKnots k = SigmaKnots::uniform(12);
  Eigen::MatrixX3d q = p;
  q.row(6) += Eigen::RowVector3d(0.2, 0.4, -0.1);
  const SigmaCurve a = interpolateSigmaCurve(k, p, ShapeMode::Heuristic);
  const SigmaCurve b = interpolateSigmaCurve(k, q, ShapeMode::Heuristic);
  for (int step = 0; step <= 96; ++step) {
    const double x = step / 8.0;
    if (x <= 3.0 || x >= 9.0) {
      EXPECT_EQ((a.evaluate(x) - b.evaluate(x)).norm(), 0.0) << x;
    }
  }
}

TEST(CubicShapePoints, MovingOneShapePointMakesOnlyNearbyIntervalsQuartic) {
  // T13: moving Phat_i of a cubic-mode curve changes it only on (t_{i-1}, t_{i+2}), and only
  // those intervals stop being cubic.
  std::srand(43);
  const SigmaKnots k = nonUniformKnots();
  const SigmaCurve c = interpolateSigmaCurve(k, Eigen::MatrixX3d::Random(7, 3));
  Eigen::MatrixX3d s = c.shapePoints();
  const int i = 3;
  s.row(i - k.shapeFirst()) += Eigen::RowVector3d(0.5, 0.5, 0.5);
  const SigmaCurve moved(k, c.points(), s);
  for (int interval = 0; interval < k.last(); ++interval) {
    const QuarticBezier b = moved.bezier(interval);
    const double fourth = (b[0] - 4 * b[1] + 6 * b[2] - 4 * b[3] + b[4]).norm();
    if (interval >= i - 1 && interval <= i + 1) {
      EXPECT_GT(fourth, 1e-3) << interval;
    } else {
      EXPECT_LT(fourth, 1e-12) << interval;
      for (int step = 0; step <= 10; ++step) {
        const double x = k.knot(interval) + k.delta(interval) * step / 10.0;
        EXPECT_EQ((moved.evaluate(x) - c.evaluate(x)).norm(), 0.0) << x;
      }
    }
  }
}

TEST(CubicShapePoints, MatchSpecT11AndTheClampedSpline) {
  const Eigen::MatrixX3d p = planar({{0, 0}, {1, 1}, {2, 0}, {3, -1}, {4, 0}});
  EndSlopes e;
  e.start = Eigen::Vector3d(1, 1, 0);
  e.end = Eigen::Vector3d(1, 1, 0);
  const SigmaKnots k = SigmaKnots::uniform(4);
  const SigmaCurve c = interpolateSigmaCurve(k, p, ShapeMode::Cubic, e);
  const double y[6] = {-5.0 / 14, 9.0 / 14, 11.0 / 14, -11.0 / 14, -9.0 / 14, 5.0 / 14};
  for (int r = 0; r < 6; ++r) {
    EXPECT_NEAR(c.shapePoints()(r, 0), r - 1 + 0.5, 1e-14);
    EXPECT_NEAR(c.shapePoints()(r, 1), y[r], 1e-14);
  }
  EXPECT_LT((c.evaluate(0.5) - Eigen::Vector3d(0.5, 17.0 / 28, 0)).norm(), 1e-14);
  EXPECT_LT((c.evaluate(2.5) - Eigen::Vector3d(2.5, -5.0 / 7, 0)).norm(), 1e-14);
}

TEST(CubicShapePoints, InteriorTensionMatchesSpecT12) {
  const Eigen::MatrixX3d p = planar({{0, 0}, {1, 1}, {2, 0}, {3, -1}, {4, 0}});
  EndSlopes e;
  e.start = Eigen::Vector3d(1, 1, 0);
  e.end = Eigen::Vector3d(1, 1, 0);
  Eigen::VectorXd beta2(5);
  beta2 << 0, 10, 10, 10, 0;
  const SigmaKnots k(Eigen::VectorXd::LinSpaced(5, 0, 4), beta2);
  const SigmaCurve c = interpolateSigmaCurve(k, p, ShapeMode::Cubic, e);
  const double y[6] = {-0.327004, 0.672996, 0.603376, -0.603376, -0.672996, 0.327004};
  for (int r = 0; r < 6; ++r) EXPECT_NEAR(c.shapePoints()(r, 1), y[r], 5e-7);
  EXPECT_NEAR(c.evaluate(0.5).y(), 0.629747, 5e-7);
}

TEST(CubicShapePoints, ReproduceClampedCubicSplineOnNonUniformKnots) {
  // P9: all beta2 = 0 -> the clamped C2 cubic spline of eq. (2.3), to 1e-12; and P8.
  std::srand(33);
  const SigmaKnots k = nonUniformKnots();
  const Eigen::MatrixX3d p = Eigen::MatrixX3d::Random(7, 3);
  EndSlopes e;
  e.start = Eigen::Vector3d(0.3, -1.0, 2.0);
  e.end = Eigen::Vector3d(-0.5, 0.4, 1.0);
  const SigmaCurve c = interpolateSigmaCurve(k, p, ShapeMode::Cubic, e);
  const int n = k.last();
  const Eigen::Vector3d d0 = *e.start / k.delta(0), dn = *e.end / k.delta(n - 1);
  double worst = 0.0;
  for (double x = 0.0; x <= 7.0; x += 0.01) {
    worst = std::max(worst, (c.evaluate(x) - test::clampedCubicSpline(k.knots(), p, d0, dn, x)).norm());
  }
  EXPECT_LT(worst, 1e-12);
  for (int i = 0; i < n; ++i) {
    const QuarticBezier b = c.bezier(i);
    EXPECT_LT((b[0] - 4 * b[1] + 6 * b[2] - 4 * b[3] + b[4]).norm(), 1e-12) << i;
  }
}

TEST(CubicShapePoints, IndependentOfPhantomWidthsAndEndTension) {
  // P10.
  std::srand(34);
  const Eigen::MatrixX3d p = Eigen::MatrixX3d::Random(7, 3);
  const SigmaKnots a = nonUniformKnots();
  SigmaKnotsOptions o;
  o.phantomBefore = 3.0;
  o.phantomAfter = 0.1;
  Eigen::VectorXd beta2 = Eigen::VectorXd::Zero(7);
  beta2[0] = 4.0;
  beta2[6] = 9.0;
  const SigmaKnots b(a.knots(), beta2, o);
  const SigmaCurve ca = interpolateSigmaCurve(a, p), cb = interpolateSigmaCurve(b, p);
  for (double x = 0.0; x <= 7.0; x += 0.05) EXPECT_LT((ca.evaluate(x) - cb.evaluate(x)).norm(), 1e-12);
}

TEST(CubicShapePoints, AffineInvariantWhenSlopesTransform) {
  // P14 for the cubic and midpoint modes, with tension.
  std::srand(35);
  const Eigen::MatrixX3d p = Eigen::MatrixX3d::Random(7, 3);
  Eigen::VectorXd beta2(7);
  beta2 << 0, 3, 0, 10, 1, 0, 2;
  const SigmaKnots k(nonUniformKnots().knots(), beta2);
  Eigen::Matrix3d a;
  a << 1, 2, 0, 0, 1, -1, 0.5, 0, 3;
  const Eigen::Vector3d t(4, 5, 6);
  const Eigen::MatrixX3d q = (p * a.transpose()).rowwise() + t.transpose();
  EndSlopes e{Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 1)};
  EndSlopes ea{a * *e.start, a * *e.end};
  for (ShapeMode mode : {ShapeMode::Cubic, ShapeMode::Midpoint}) {
    const SigmaCurve c = interpolateSigmaCurve(k, p, mode, e);
    const SigmaCurve d = interpolateSigmaCurve(k, q, mode, ea);
    for (double x = 0.0; x <= 7.0; x += 0.05) {
      EXPECT_LT((d.evaluate(x) - (a * c.evaluate(x) + t)).norm(), 1e-12) << x;
    }
  }
}

TEST(CubicShapePoints, ClosedCircleMatchesSpecT14) {
  const Eigen::MatrixX3d p = planar({{1, 0}, {0, 1}, {-1, 0}, {0, -1}});
  SigmaKnotsOptions o;
  o.closed = true;
  Eigen::VectorXd t(5);
  t << 0, 10, 20, 30, 40;
  const SigmaCurve c = interpolateSigmaCurve(SigmaKnots(t, {}, o), p, ShapeMode::Cubic);
  const double sx[4] = {0.75, -0.75, -0.75, 0.75}, sy[4] = {0.75, 0.75, -0.75, -0.75};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(c.shapePoints()(i, 0), sx[i], 1e-14);
    EXPECT_NEAR(c.shapePoints()(i, 1), sy[i], 1e-14);
    EXPECT_NEAR(c.evaluate(10.0 * i + 5.0).norm(), 0.972272, 5e-7);
  }
}

TEST(SigmaSurfaceShapePoints, BicubicRoutesAgreeAndPatchesAreBicubic) {
  // P11 and P8 for surfaces, with the consistent cross-end rule (Kuriyama 1996, sec. 3.3.5).
  std::srand(36);
  Eigen::VectorXd tu(5), tv(6);
  tu << 0, 1, 2.5, 3, 4.5;
  tv << 0, 2, 3, 3.5, 5, 6;
  Eigen::VectorXd bv = Eigen::VectorXd::Zero(6);
  const SigmaKnots ku(tu), kv(tv, bv);
  PointGrid g(5, 6);
  for (auto& q : g.data) q = Eigen::Vector3d::Random();
  SigmaSurfaceOptions o;
  o.crossCheckRoutes = true;
  o.ends.twists = std::array<Eigen::Vector3d, 4>{Eigen::Vector3d(0.1, 0.2, 0.3),
                                                 Eigen::Vector3d(-0.2, 0, 0.1),
                                                 Eigen::Vector3d::Zero(),
                                                 Eigen::Vector3d(1, 1, 1)};
  const SigmaSurfaceResult r = interpolateSigmaSurface(ku, kv, g, o);
  EXPECT_LT(r.routeDiscrepancy, 1e-12);
  double worst4th = 0.0;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 5; ++j) {
      const QuarticPatch b = r.surface.patch(i, j);
      for (int l = 0; l <= 4; ++l) {
        worst4th = std::max(worst4th, (b[0][l] - 4 * b[1][l] + 6 * b[2][l] - 4 * b[3][l] + b[4][l]).norm());
        worst4th = std::max(worst4th, (b[l][0] - 4 * b[l][1] + 6 * b[l][2] - 4 * b[l][3] + b[l][4]).norm());
      }
    }
  }
  EXPECT_LT(worst4th, 1e-12);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 6; ++j)
      EXPECT_LT((r.surface.evaluate(tu[i], tv[j]) - g(i, j)).norm(), 1e-12);
  // The corner twist is honoured: d2Q/dudv at (u0, v0) = T00 / (Delta^u_0 Delta^v_0).
  EXPECT_LT((r.surface.evaluate(0, 0, 1, 1) * 1.0 * 2.0 - Eigen::Vector3d(0.1, 0.2, 0.3)).norm(), 1e-12);
}

// An independent bicubic spline (de Boor's tensor-product interpolation): 1D clamped cubic
// splines solved here, and bicubic Hermite patches from P, Pu, Pv, Puv at the knots.
// Derivatives at the knots t of the C2 cubic spline through y with end slopes m0, mn.
Eigen::MatrixX3d clampedSplineSlopes(const Eigen::VectorXd& t, const Eigen::MatrixX3d& y, const Eigen::Vector3d& m0,
                                     const Eigen::Vector3d& mn) {
  const Eigen::Index n = t.size() - 1;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n + 1, n + 1);
  Eigen::MatrixX3d b(n + 1, 3);
  a(0, 0) = a(n, n) = 1.0;
  b.row(0) = m0.transpose();
  b.row(n) = mn.transpose();
  for (Eigen::Index i = 1; i < n; ++i) {
    const double h0 = t[i] - t[i - 1], h1 = t[i + 1] - t[i];
    a(i, i - 1) = h1;
    a(i, i) = 2.0 * (h0 + h1);
    a(i, i + 1) = h0;
    b.row(i) = 3.0 * (h1 * (y.row(i) - y.row(i - 1)) / h0 + h0 * (y.row(i + 1) - y.row(i)) / h1);
  }
  return a.partialPivLu().solve(b);
}

struct HermiteGrid {
  Eigen::VectorXd tu, tv;
  std::vector<Eigen::MatrixX3d> p, pu, pv, puv;  // [i] = column of v-knots j

  Eigen::Vector3d evaluate(double u, double v) const {
    const auto span = [](const Eigen::VectorXd& t, double x) {
      Eigen::Index i = 0;
      while (i + 2 < t.size() && x >= t[i + 1]) ++i;
      return i;
    };
    const Eigen::Index i = span(tu, u), j = span(tv, v);
    const double hu = tu[i + 1] - tu[i], hv = tv[j + 1] - tv[j];
    const double s = (u - tu[i]) / hu, r = (v - tv[j]) / hv;
    const auto h0 = [](double x, int end) { return end ? -2 * x * x * x + 3 * x * x : 2 * x * x * x - 3 * x * x + 1; };
    const auto h1 = [](double x, int end) { return end ? x * x * x - x * x : x * x * x - 2 * x * x + x; };
    Eigen::Vector3d q = Eigen::Vector3d::Zero();
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const Eigen::Index ii = i + a, jj = j + b;
        q += h0(s, a) * h0(r, b) * p[ii].row(jj).transpose() + hu * h1(s, a) * h0(r, b) * pu[ii].row(jj).transpose() +
             hv * h0(s, a) * h1(r, b) * pv[ii].row(jj).transpose() +
             hu * hv * h1(s, a) * h1(r, b) * puv[ii].row(jj).transpose();
      }
    return q;
  }
};

TEST(SigmaSurfaceShapePoints, BicubicModeIsTheTensorProductSplineOfItsEndData) {
  // P11 on the geometry, not through the library's routeDiscrepancy: with all beta2 = 0 and
  // explicit end data (u-end slopes per row, v-end slopes per column, corner twists) the cubic-mode
  // surface must be the unique C2 bicubic spline of those data, built here independently by
  // de Boor's construction: Pu along the knot rows, Pv along the knot columns, the boundary twists
  // along the two v-end rows from the corner twists, and Puv along the columns from Pu.
  std::srand(40);
  Eigen::VectorXd tu(5), tv(6);
  tu << 0, 1, 2.5, 3, 4.5;
  tv << 0, 2, 3, 3.5, 5, 6;
  const SigmaKnots ku(tu, Eigen::VectorXd::Zero(5)), kv(tv, Eigen::VectorXd::Zero(6));
  PointGrid g(5, 6);
  for (auto& q : g.data) q = Eigen::Vector3d::Random();
  SigmaSurfaceOptions o;
  o.ends.uStart = Eigen::MatrixX3d::Random(6, 3);
  o.ends.uEnd = Eigen::MatrixX3d::Random(6, 3);
  o.ends.vStart = Eigen::MatrixX3d::Random(5, 3);
  o.ends.vEnd = Eigen::MatrixX3d::Random(5, 3);
  o.ends.twists = std::array<Eigen::Vector3d, 4>{Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(-0.2, 0, 0.1),
                                                 Eigen::Vector3d(0.5, -0.4, 0), Eigen::Vector3d(1, 1, 1)};
  // The end data are in the local parameters of the end intervals (shape_points.h): the global
  // slopes divide by the end interval's length, the twists by both.
  const double du0 = tu[1] - tu[0], du1 = tu[4] - tu[3], dv0 = tv[1] - tv[0], dv1 = tv[5] - tv[4];
  const Eigen::MatrixX3d uStart = *o.ends.uStart / du0, uEnd = *o.ends.uEnd / du1;
  const Eigen::MatrixX3d vStart = *o.ends.vStart / dv0, vEnd = *o.ends.vEnd / dv1;
  const auto& t = *o.ends.twists;  // (u0,v0), (u0,vn), (um,v0), (um,vn)
  const std::array<Eigen::Vector3d, 4> tw{t[0] / (du0 * dv0), t[1] / (du0 * dv1), t[2] / (du1 * dv0), t[3] / (du1 * dv1)};

  HermiteGrid ref{tu, tv, {}, {}, {}, {}};
  Eigen::MatrixX3d pu(5 * 6, 3);  // row i + 5 j
  for (int j = 0; j < 6; ++j) {
    Eigen::MatrixX3d row(5, 3);
    for (int i = 0; i < 5; ++i) row.row(i) = g(i, j).transpose();
    const Eigen::MatrixX3d slopes = clampedSplineSlopes(tu, row, uStart.row(j), uEnd.row(j));
    for (int i = 0; i < 5; ++i) pu.row(i + 5 * j) = slopes.row(i);
  }
  const Eigen::MatrixX3d twistStart = clampedSplineSlopes(tu, vStart, tw[0], tw[2]);
  const Eigen::MatrixX3d twistEnd = clampedSplineSlopes(tu, vEnd, tw[1], tw[3]);
  for (int i = 0; i < 5; ++i) {
    Eigen::MatrixX3d column(6, 3), columnPu(6, 3);
    for (int j = 0; j < 6; ++j) {
      column.row(j) = g(i, j).transpose();
      columnPu.row(j) = pu.row(i + 5 * j);
    }
    ref.p.push_back(column);
    ref.pu.push_back(columnPu);
    ref.pv.push_back(clampedSplineSlopes(tv, column, vStart.row(i), vEnd.row(i)));
    ref.puv.push_back(clampedSplineSlopes(tv, columnPu, twistStart.row(i), twistEnd.row(i)));
  }

  const SigmaSurface s = interpolateSigmaSurface(ku, kv, g, o).surface;
  double worst = 0.0;
  for (double u = 0.0; u <= 4.5; u += 0.125)
    for (double v = 0.0; v <= 6.0; v += 0.125) worst = std::max(worst, (s.evaluate(u, v) - ref.evaluate(u, v)).norm());
  EXPECT_LT(worst, 1e-12);
  // The negative control (Kuriyama 1996, sec. 3.3.5): the thesis' literal zero cross-end data make the
  // two routes disagree, and the surface is no longer that spline.
  o.thesisZeroCrossDefaults = true;
  const SigmaSurface literal = interpolateSigmaSurface(ku, kv, g, o).surface;
  double off = 0.0;
  for (double u = 0.0; u <= 4.5; u += 0.125)
    for (double v = 0.0; v <= 6.0; v += 0.125) off = std::max(off, (literal.evaluate(u, v) - ref.evaluate(u, v)).norm());
  EXPECT_GT(off, 1e-3);
}

TEST(SigmaSurfaceShapePoints, ThesisZeroDefaultBreaksTheRouteAgreement) {
  // Kuriyama 1996, sec. 3.3.5: with the literal zero cross-end data the two routes differ.
  std::srand(37);
  PointGrid g(5, 5);
  for (auto& q : g.data) q = Eigen::Vector3d::Random();
  SigmaSurfaceOptions o;
  o.crossCheckRoutes = true;
  o.thesisZeroCrossDefaults = true;
  const auto k = SigmaKnots::uniform(4);
  EXPECT_GT(interpolateSigmaSurface(k, k, g, o).routeDiscrepancy, 1e-3);
}

TEST(SigmaSurfaceShapePoints, BicubicSurfaceReproducesCurveSplineAlongBoundary) {
  // The knot rows are sigma curves with the curve-mode shape points: the boundary v = t_0 is
  // the clamped spline through the first column with the given end slopes.
  std::srand(38);
  PointGrid g(6, 4);
  for (auto& q : g.data) q = Eigen::Vector3d::Random();
  const auto ku = SigmaKnots::uniform(5), kv = SigmaKnots::uniform(3);
  const SigmaSurface s = interpolateSigmaSurface(ku, kv, g).surface;
  const SigmaCurve c = interpolateSigmaCurve(ku, g.col(0));
  for (double u = 0.0; u <= 5.0; u += 0.1) EXPECT_LT((s.evaluate(u, 0.0) - c.evaluate(u)).norm(), 1e-12);
}

TEST(SigmaSurfaceShapePoints, LocalModesInterpolateClosedSurfaces) {
  std::srand(39);
  PointGrid g(5, 6);
  for (auto& q : g.data) q = Eigen::Vector3d::Random();
  const auto ku = SigmaKnots::uniform(5, true), kv = SigmaKnots::uniform(5);
  for (ShapeMode mode : {ShapeMode::Heuristic, ShapeMode::Midpoint, ShapeMode::Cubic}) {
    SigmaSurfaceOptions o;
    o.mode = mode;
    o.crossCheckRoutes = true;
    const SigmaSurfaceResult r = interpolateSigmaSurface(ku, kv, g, o);
    if (mode == ShapeMode::Cubic) {
      EXPECT_LT(r.routeDiscrepancy, 1e-12);
    }
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 6; ++j) EXPECT_LT((r.surface.evaluate(i, j) - g(i, j)).norm(), 1e-12);
    // periodic in u: the seam joins C1
    EXPECT_LT((r.surface.evaluate(5.0 - 1e-12, 2.5, 1, 0) - r.surface.evaluate(0.0, 2.5, 1, 0)).norm(), 1e-9);
  }
}

TEST(SigmaShapePoints, RejectsWrongPointCount) {
  EXPECT_THROW(sigmaShapePoints(SigmaKnots::uniform(3), Eigen::MatrixX3d::Zero(3, 3), ShapeMode::Cubic),
               CardinalSplineError);
}

}  // namespace
}  // namespace ffdkit::geometry::cardinal
