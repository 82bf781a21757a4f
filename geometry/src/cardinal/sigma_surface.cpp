#include "ffdkit/geometry/cardinal/sigma_surface.h"

#include <cmath>
#include <string>

#include "ffdkit/geometry/cardinal/cardinal_error.h"
#include "ffdkit/geometry/cardinal/sigma_curve.h"

#include "floor_mod.h"

namespace ffdkit::geometry::cardinal {
namespace {

using detail::floorMod;

// Grid row/column of knot index i and of shape index i along one direction.
int pointSlot(const SigmaKnots& k, int i) { return k.closed() ? floorMod(i, k.last()) : i; }
int shapeSlot(const SigmaKnots& k, int i) {
  return k.closed() ? floorMod(i, k.last()) : i - k.shapeFirst();
}

void checkGrid(const PointGrid& g, int rows, int cols, const char* name) {
  if (g.rows != rows || g.cols != cols || static_cast<int>(g.data.size()) != rows * cols) {
    throw CardinalSplineError(std::string("SigmaSurface: grid ") + name + " must be " +
                              std::to_string(rows) + " x " + std::to_string(cols) + ", got " +
                              std::to_string(g.rows) + " x " + std::to_string(g.cols));
  }
}

}  // namespace

void SigmaSurface::validate() const {
  checkGrid(P, knotsU.pointCount(), knotsV.pointCount(), "P");
  checkGrid(Pu, knotsU.shapeCount(), knotsV.pointCount(), "Pu");
  checkGrid(Pv, knotsU.pointCount(), knotsV.shapeCount(), "Pv");
  checkGrid(Puv, knotsU.shapeCount(), knotsV.shapeCount(), "Puv");
}

QuarticPatch SigmaSurface::patch(int i, int j) const {
  if (i < 0 || i >= knotsU.intervalCount() || j < 0 || j >= knotsV.intervalCount()) {
    throw CardinalSplineError("SigmaSurface::patch: interval (" + std::to_string(i) + ", " +
                              std::to_string(j) + ") outside 0.." +
                              std::to_string(knotsU.intervalCount() - 1) + " x 0.." +
                              std::to_string(knotsV.intervalCount() - 1));
  }
  // Step 1 (Kuriyama 1996, sec. 3.3.3): the u-curve rule on interval i for the v-items that
  // interval j uses: knot columns j, j+1 (data P, Pu) and shape columns j-1, j, j+1 (data Pv, Puv).
  const auto uBezier = [&](const PointGrid& knotData, const PointGrid& shapeData, int col) {
    return sigmaIntervalBezier(knotsU, i, knotData(pointSlot(knotsU, i), col),
                               knotData(pointSlot(knotsU, i + 1), col),
                               shapeData(shapeSlot(knotsU, i - 1), col),
                               shapeData(shapeSlot(knotsU, i), col),
                               shapeData(shapeSlot(knotsU, i + 1), col));
  };
  const QuarticBezier k0 = uBezier(P, Pu, pointSlot(knotsV, j));
  const QuarticBezier k1 = uBezier(P, Pu, pointSlot(knotsV, j + 1));
  const QuarticBezier sm = uBezier(Pv, Puv, shapeSlot(knotsV, j - 1));
  const QuarticBezier s0 = uBezier(Pv, Puv, shapeSlot(knotsV, j));
  const QuarticBezier sp = uBezier(Pv, Puv, shapeSlot(knotsV, j + 1));
  // Step 2: the v-curve rule on interval j for each of the five u-Bezier rows.
  QuarticPatch b;
  for (int k = 0; k <= 4; ++k) {
    const QuarticBezier col = sigmaIntervalBezier(knotsV, j, k0[k], k1[k], sm[k], s0[k], sp[k]);
    for (int l = 0; l <= 4; ++l) b[k][l] = col[l];
  }
  return b;
}

Eigen::Vector3d evaluateQuarticPatch(const QuarticPatch& b, double s, double t, int du, int dv) {
  QuarticBezier column;
  for (int k = 0; k <= 4; ++k) {
    QuarticBezier row;
    for (int l = 0; l <= 4; ++l) row[l] = b[k][l];
    column[k] = evaluateQuarticBezier(row, t, dv);
  }
  return evaluateQuarticBezier(column, s, du);
}

Eigen::Vector3d SigmaSurface::evaluate(double u, double v, int du, int dv) const {
  double s = 0.0, t = 0.0;
  const int i = knotsU.locate(u, s);
  const int j = knotsV.locate(v, t);
  return evaluateQuarticPatch(patch(i, j), s, t, du, dv) /
         (std::pow(knotsU.delta(i), du) * std::pow(knotsV.delta(j), dv));
}

}  // namespace ffdkit::geometry::cardinal
