#include "ffdkit/geometry/cardinal/sigma_refinement.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

namespace ffdkit::geometry::cardinal {

SigmaKnots refinedKnots(const SigmaKnots& knots, const std::vector<double>& newKnots) {
  const double t0 = knots.start(), tn = knots.end();
  const double tol = 1e-9 * (tn - t0);
  std::vector<double> all(knots.knots().data(), knots.knots().data() + knots.last() + 1);
  std::vector<char> inserted(all.size(), 0);
  for (double x : newKnots) {
    if (!(x > t0 && x < tn)) {
      throw CardinalSplineError("refinedKnots: new knot " + std::to_string(x) +
                                " must lie strictly inside (" + std::to_string(t0) + ", " +
                                std::to_string(tn) + ")");
    }
    const auto pos = std::lower_bound(all.begin(), all.end(), x);
    const bool nearNext = pos != all.end() && *pos - x <= tol;
    const bool nearPrev = pos != all.begin() && x - *(pos - 1) <= tol;
    if (nearNext || nearPrev) continue;
    const auto offset = pos - all.begin();
    all.insert(pos, x);
    inserted.insert(inserted.begin() + offset, 1);
  }
  const int count = static_cast<int>(all.size());
  const int betaCount = knots.closed() ? count - 1 : count;
  Eigen::VectorXd t = Eigen::Map<Eigen::VectorXd>(all.data(), count);
  Eigen::VectorXd beta2 = Eigen::VectorXd::Zero(betaCount);
  int old = 0;
  for (int k = 0; k < betaCount; ++k) {
    if (inserted[static_cast<std::size_t>(k)]) continue;
    beta2[k] = knots.beta2(old++);
  }
  return SigmaKnots(t, beta2, knots.options());
}

SigmaCurve refine(const SigmaCurve& curve, const std::vector<double>& newKnots) {
  const SigmaKnots& oldKnots = curve.knots();
  SigmaKnots k = refinedKnots(oldKnots, newKnots);
  const int g = k.last();
  std::vector<QuarticBezier> pieces(static_cast<std::size_t>(g));
  int oldInterval = 0;
  for (int i = 0; i < g; ++i) {
    const double a = k.knot(i), b = k.knot(i + 1);
    while (oldInterval < oldKnots.last() - 1 && oldKnots.knot(oldInterval + 1) <= 0.5 * (a + b)) {
      ++oldInterval;
    }
    const double left = oldKnots.knot(oldInterval);
    const double width = oldKnots.delta(oldInterval);
    // sec. 3.3.6: split the quartic piece by de Casteljau at the new knots.
    pieces[static_cast<std::size_t>(i)] =
        quarticBezierPiece(curve.bezier(oldInterval), std::clamp((a - left) / width, 0.0, 1.0),
                           std::clamp((b - left) / width, 0.0, 1.0));
  }
  Eigen::MatrixX3d points(k.pointCount(), 3);
  Eigen::MatrixX3d shapes(k.shapeCount(), 3);
  const int first = k.shapeFirst();
  for (int i = 0; i < g; ++i) {
    const QuarticBezier& b = pieces[static_cast<std::size_t>(i)];
    if (i < k.pointCount()) points.row(i) = b[0].transpose();
    shapes.row(i - first) = b[2].transpose();
  }
  if (!k.closed()) {
    points.row(g) = pieces.back()[4].transpose();
    // Kuriyama 1996, sec. 3.3.6 (gap in the thesis): the open-end shape points from b1 of the first
    // piece and b3 of the last, with the coefficients of the new knot vector.
    const Eigen::RowVector3d start =
        (pieces.front()[1].transpose() - k.C1(0) * points.row(0) - k.Chat1(0) * shapes.row(0 - first)) /
        k.Chat4(-1);
    const Eigen::RowVector3d end = (pieces.back()[3].transpose() - k.C0(g) * points.row(g) -
                                    k.Chat3(g - 1) * shapes.row(g - 1 - first)) /
                                   k.Chat0(g);
    shapes.row(-1 - first) = start;
    shapes.row(g - first) = end;
  }
  return SigmaCurve(std::move(k), std::move(points), std::move(shapes));
}

namespace {

// Refines along u every column j of the pair (knot data, shape data) as one sigma curve.
void refineAlongU(const SigmaKnots& knots, const std::vector<double>& newKnots,
                  const PointGrid& pointData, const PointGrid& shapeData, PointGrid& pointsOut,
                  PointGrid& shapesOut, SigmaKnots& knotsOut) {
  for (int j = 0; j < pointData.cols; ++j) {
    const SigmaCurve c = refine(SigmaCurve(knots, pointData.col(j), shapeData.col(j)), newKnots);
    if (j == 0) {
      knotsOut = c.knots();
      pointsOut = PointGrid(static_cast<int>(c.points().rows()), pointData.cols);
      shapesOut = PointGrid(static_cast<int>(c.shapePoints().rows()), pointData.cols);
    }
    for (int i = 0; i < pointsOut.rows; ++i) pointsOut(i, j) = c.points().row(i).transpose();
    for (int i = 0; i < shapesOut.rows; ++i) shapesOut(i, j) = c.shapePoints().row(i).transpose();
  }
}

PointGrid transposed(const PointGrid& g) {
  PointGrid t(g.cols, g.rows);
  for (int i = 0; i < g.rows; ++i)
    for (int j = 0; j < g.cols; ++j) t(j, i) = g(i, j);
  return t;
}

}  // namespace

SigmaSurface refine(const SigmaSurface& surface, const std::vector<double>& newU,
                    const std::vector<double>& newV) {
  surface.validate();
  SigmaSurface out = surface;
  if (!newU.empty()) {
    // Knot columns carry (P, Pu), shape columns (Pv, Puv) along u (Kuriyama 1996, sec. 3.3.6).
    refineAlongU(surface.knotsU, newU, surface.P, surface.Pu, out.P, out.Pu, out.knotsU);
    refineAlongU(surface.knotsU, newU, surface.Pv, surface.Puv, out.Pv, out.Puv, out.knotsU);
  }
  if (!newV.empty()) {
    const SigmaSurface mid = out;
    PointGrid p, pv, pu, puv;
    refineAlongU(mid.knotsV, newV, transposed(mid.P), transposed(mid.Pv), p, pv, out.knotsV);
    refineAlongU(mid.knotsV, newV, transposed(mid.Pu), transposed(mid.Puv), pu, puv, out.knotsV);
    out.P = transposed(p);
    out.Pv = transposed(pv);
    out.Pu = transposed(pu);
    out.Puv = transposed(puv);
  }
  out.validate();
  return out;
}

}  // namespace ffdkit::geometry::cardinal
