#include "ffdkit/geometry/cardinal/s_spline_surface.h"

#include <cmath>
#include <string>
#include <algorithm>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

namespace ffdkit::geometry::cardinal {
namespace {

int floorMod(int a, int m) { return ((a % m) + m) % m; }

// Source index of extended index i under the open (repeat) or closed (wrap) end rule.
int sourceIndex(int i, int span, bool closed) {
  return closed ? floorMod(i, span) : std::clamp(i, 0, span);
}

double wrap(double x, int span) {
  x -= span * std::floor(x / span);
  return x >= span ? 0.0 : x;
}

}  // namespace

SSplineSurface::SSplineSurface(const PointGrid& grid, const SSplineSurfaceOptions& options)
    : options_(options),
      basisU_(options.beta2U, options.halfWidthU),
      basisV_(options.beta2V, options.halfWidthV) {
  const int minU = options.closedU ? 3 : 2;
  const int minV = options.closedV ? 3 : 2;
  if (grid.rows < minU || grid.cols < minV) {
    throw CardinalSplineError("SSplineSurface: grid needs >= " + std::to_string(minU) + " x " +
                              std::to_string(minV) + " points (closed directions >= 3), got " +
                              std::to_string(grid.rows) + " x " + std::to_string(grid.cols));
  }
  if (static_cast<int>(grid.data.size()) != grid.rows * grid.cols) {
    throw CardinalSplineError("SSplineSurface: grid data holds " +
                              std::to_string(grid.data.size()) + " points, expected rows*cols = " +
                              std::to_string(grid.rows * grid.cols));
  }
  uSpan_ = options.closedU ? grid.rows : grid.rows - 1;
  vSpan_ = options.closedV ? grid.cols : grid.cols - 1;
  const int wU = options.halfWidthU + 1;
  const int wV = options.halfWidthV + 1;
  // Extension in u for every row, then in v for every extended column (spec §2.6): for the
  // open (repeat) and closed (wrap) rules this is a plain index map in each direction.
  extended_ = PointGrid(uSpan_ + 2 * wU + 1, vSpan_ + 2 * wV + 1);
  for (int i = 0; i < extended_.rows; ++i) {
    const int si = sourceIndex(i - wU, uSpan_, options.closedU);
    for (int j = 0; j < extended_.cols; ++j) {
      extended_(i, j) = grid(si, sourceIndex(j - wV, vSpan_, options.closedV));
    }
  }
}

Eigen::Vector3d SSplineSurface::evaluate(double u, double v, int du, int dv) const {
  if (options_.closedU) u = wrap(u, uSpan_);
  if (options_.closedV) v = wrap(v, vSpan_);
  // Open surfaces: the extension makes the sum defined a little beyond the range; clamp so
  // that the extended grid is never left.
  if (!options_.closedU) u = std::clamp(u, 0.0, static_cast<double>(uSpan_));
  if (!options_.closedV) v = std::clamp(v, 0.0, static_cast<double>(vSpan_));
  const int wU = options_.halfWidthU;
  const int wV = options_.halfWidthV;
  const Limit side = Limit::Value;
  const int uLo = static_cast<int>(std::floor(u)) - wU;
  const int vLo = static_cast<int>(std::floor(v)) - wV;
  const int nU = 2 * wU + 2;
  const int nV = 2 * wV + 2;
  Eigen::VectorXd bv(nV);
  for (int b = 0; b < nV; ++b) bv[b] = basisV_.evaluate(v - (vLo + b), dv, side);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int a = 0; a < nU; ++a) {
    const double bu = basisU_.evaluate(u - (uLo + a), du, side);
    if (bu == 0.0) continue;
    Eigen::Vector3d rowSum = Eigen::Vector3d::Zero();
    const int ei = uLo + a + options_.halfWidthU + 1;
    for (int b = 0; b < nV; ++b) {
      if (bv[b] != 0.0) rowSum += bv[b] * extended_(ei, vLo + b + options_.halfWidthV + 1);
    }
    sum += bu * rowSum;
  }
  return sum;
}

}  // namespace ffdkit::geometry::cardinal
