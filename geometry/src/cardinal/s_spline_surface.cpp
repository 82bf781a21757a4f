#include "ffdkit/geometry/cardinal/s_spline_surface.h"

#include <cmath>
#include <string>
#include <vector>
#include <algorithm>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

#include "floor_mod.h"

namespace ffdkit::geometry::cardinal {
namespace {

using detail::floorMod;

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
      basisU_(options.beta2U, options.halfWidthU, options.degreeU),
      basisV_(options.beta2V, options.halfWidthV, options.degreeV) {
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
  // Extension in u for every row, then in v for every extended column (Kuriyama 1996, sec. 3.2.4):
  // for the open (repeat) and closed (wrap) rules this is a plain index map in each direction.
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

SSplineSurface::GridSamples SSplineSurface::sampleGrid(const Eigen::VectorXd& us,
                                                      const Eigen::VectorXd& vs) const {
  const int wU = options_.halfWidthU, wV = options_.halfWidthV;
  const int nU = 2 * wU + 2, nV = 2 * wV + 2;
  const auto prepare = [](double x, bool closed, int span) {
    if (closed) return wrap(x, span);
    return std::clamp(x, 0.0, static_cast<double>(span));
  };
  // Basis values (and first derivatives) of every sample along v, once.
  const auto countV = static_cast<int>(vs.size());
  Eigen::MatrixXd bv(countV, nV), dbv(countV, nV);
  std::vector<int> vLo(static_cast<std::size_t>(countV));
  for (int b = 0; b < countV; ++b) {
    const double v = prepare(vs[b], options_.closedV, vSpan_);
    vLo[static_cast<std::size_t>(b)] = static_cast<int>(std::floor(v)) - wV;
    for (int l = 0; l < nV; ++l) {
      bv(b, l) = basisV_.evaluate(v - (vLo[static_cast<std::size_t>(b)] + l), 0, Limit::Value);
      dbv(b, l) = basisV_.evaluate(v - (vLo[static_cast<std::size_t>(b)] + l), 1, Limit::Value);
    }
  }
  GridSamples out;
  const Eigen::Index total = us.size() * vs.size();
  out.points.resize(total, 3);
  out.du.resize(total, 3);
  out.dv.resize(total, 3);
  // Per u sample: the u-combinations of all extended columns, then short sums along v.
  Eigen::MatrixX3d row(extended_.cols, 3), drow(extended_.cols, 3);
  for (Eigen::Index a = 0; a < us.size(); ++a) {
    const double u = prepare(us[a], options_.closedU, uSpan_);
    const int uLo = static_cast<int>(std::floor(u)) - wU;
    row.setZero();
    drow.setZero();
    for (int k = 0; k < nU; ++k) {
      const double bu = basisU_.evaluate(u - (uLo + k), 0, Limit::Value);
      const double dbu = basisU_.evaluate(u - (uLo + k), 1, Limit::Value);
      if (bu == 0.0 && dbu == 0.0) continue;
      const int ei = uLo + k + wU + 1;
      for (int j = 0; j < extended_.cols; ++j) {
        const Eigen::RowVector3d e = extended_(ei, j).transpose();
        row.row(j) += bu * e;
        drow.row(j) += dbu * e;
      }
    }
    for (int b = 0; b < countV; ++b) {
      Eigen::RowVector3d p = Eigen::RowVector3d::Zero(), pu = p, pv = p;
      const int base = vLo[static_cast<std::size_t>(b)] + wV + 1;
      for (int l = 0; l < nV; ++l) {
        p += bv(b, l) * row.row(base + l);
        pv += dbv(b, l) * row.row(base + l);
        pu += bv(b, l) * drow.row(base + l);
      }
      const Eigen::Index r = a * countV + b;
      out.points.row(r) = p;
      out.du.row(r) = pu;
      out.dv.row(r) = pv;
    }
  }
  return out;
}

}  // namespace ffdkit::geometry::cardinal
