#include "ffdkit/geometry/cardinal/shape_points.h"

#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/SparseCore>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

#include "../eigen_sparse_lu_instance.h"
#include "floor_mod.h"

namespace ffdkit::geometry::cardinal {
namespace {

using detail::floorMod;

void checkPointCount(const SigmaKnots& knots, Eigen::Index rows, const char* where) {
  if (rows != knots.pointCount()) {
    throw CardinalSplineError(std::string(where) + ": expected " +
                              std::to_string(knots.pointCount()) + " points for the knots, got " +
                              std::to_string(rows));
  }
}

// Data point i with the end extension of Kuriyama 1996, sec. 3.3.4: periodic when closed, point
// reflection through the end points when open (P_{-k} = 2P_0 - P_k, P_{n+k} = 2P_n - P_{n-k}).
Eigen::Vector3d extendedPoint(const SigmaKnots& knots, const Eigen::MatrixX3d& points, int i) {
  const int n = knots.last();
  if (knots.closed()) return points.row(floorMod(i, n)).transpose();
  if (i < 0) return 2.0 * points.row(0).transpose() - extendedPoint(knots, points, -i);
  if (i > n) return 2.0 * points.row(n).transpose() - extendedPoint(knots, points, 2 * n - i);
  return points.row(i).transpose();
}

double boundingBoxDiagonal(const Eigen::MatrixX3d& points) {
  if (points.rows() == 0) return 0.0;
  return (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
}

Eigen::MatrixX3d midpointShapePoints(const SigmaKnots& knots, const Eigen::MatrixX3d& points) {
  Eigen::MatrixX3d out(knots.shapeCount(), 3);
  for (int r = 0; r < knots.shapeCount(); ++r) {
    const int i = r + knots.shapeFirst();
    out.row(r) = 0.5 * (extendedPoint(knots, points, i) + extendedPoint(knots, points, i + 1));
  }
  return out;
}

// Eq. (3.26); terms whose denominator vanishes (coincident points) are dropped.
Eigen::MatrixX3d heuristicShapePoints(const SigmaKnots& knots, const Eigen::MatrixX3d& points) {
  const double eps = 1e-12 * boundingBoxDiagonal(points);
  Eigen::MatrixX3d out(knots.shapeCount(), 3);
  for (int r = 0; r < knots.shapeCount(); ++r) {
    const int i = r + knots.shapeFirst();
    const Eigen::Vector3d pm = extendedPoint(knots, points, i - 1);
    const Eigen::Vector3d p0 = extendedPoint(knots, points, i);
    const Eigen::Vector3d p1 = extendedPoint(knots, points, i + 1);
    const Eigen::Vector3d p2 = extendedPoint(knots, points, i + 2);
    const double chord = (p1 - p0).norm();
    Eigen::Vector3d shape = 0.5 * (p0 + p1);
    const double left = (p1 - pm).norm();
    const double right = (p2 - p0).norm();
    if (left > eps) shape += chord / (6.0 * left) * (p1 - pm);
    if (right > eps) shape += chord / (6.0 * right) * (p0 - p2);
    out.row(r) = shape.transpose();
  }
  return out;
}

}  // namespace

CubicShapeSolver::CubicShapeSolver(const SigmaKnots& knots) : knots_(knots) {
  const int n = knots.last();
  const int size = knots.shapeCount();
  const int first = knots.shapeFirst();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(3 * size));
  const auto column = [&](int shapeIndex) {
    return knots.closed() ? floorMod(shapeIndex, n) : shapeIndex - first;
  };
  int row = 0;
  if (!knots.closed()) {
    // (3.33), start: 4 Chat_{-1,4} Phat_{-1} + 4 Chat_{0,1} Phat_0 = dP_0 + 4(1 - C_{0,1}) P_0.
    entries.emplace_back(row, column(-1), 4.0 * knots.Chat4(-1));
    entries.emplace_back(row, column(0), 4.0 * knots.Chat1(0));
    ++row;
  }
  for (int i = 0; i < n; ++i, ++row) {
    // (3.28): the fourth Bezier difference of interval i vanishes.
    entries.emplace_back(row, column(i - 1), -4.0 * knots.Chat4(i - 1));
    entries.emplace_back(row, column(i), 6.0 - 4.0 * knots.Chat1(i) - 4.0 * knots.Chat3(i));
    entries.emplace_back(row, column(i + 1), -4.0 * knots.Chat0(i + 1));
  }
  if (!knots.closed()) {
    entries.emplace_back(row, column(n - 1), -4.0 * knots.Chat3(n - 1));
    entries.emplace_back(row, column(n), -4.0 * knots.Chat0(n));
  }
  matrix_.resize(size, size);
  matrix_.setFromTriplets(entries.begin(), entries.end());
  matrix_.makeCompressed();
  lu_.compute(matrix_);
  if (lu_.info() != Eigen::Success) {
    throw CardinalSplineError("CubicShapeSolver: the cubic-mode system (3.28) is singular for " +
                              std::to_string(n + 1) + " knots: " + lu_.lastErrorMessage());
  }
}

Eigen::MatrixXd CubicShapeSolver::solve(const Eigen::MatrixXd& values,
                                        const Eigen::MatrixXd& startSlope,
                                        const Eigen::MatrixXd& endSlope) const {
  const SigmaKnots& knots = knots_;
  const int n = knots.last();
  checkPointCount(knots, values.rows(), "CubicShapeSolver::solve");
  const Eigen::Index k = values.cols();
  if (!knots.closed() && (startSlope.rows() != 1 || startSlope.cols() != k ||
                          endSlope.rows() != 1 || endSlope.cols() != k)) {
    throw CardinalSplineError("CubicShapeSolver::solve: end slopes must be 1 x " +
                              std::to_string(k) + ", got " + std::to_string(startSlope.rows()) +
                              " x " + std::to_string(startSlope.cols()) + " and " +
                              std::to_string(endSlope.rows()) + " x " +
                              std::to_string(endSlope.cols()));
  }
  Eigen::MatrixXd rhs(knots.shapeCount(), k);
  const auto value = [&](int i) { return values.row(knots.closed() ? floorMod(i, n) : i); };
  int row = 0;
  if (!knots.closed()) {
    rhs.row(row++) = startSlope + 4.0 * (1.0 - knots.C1(0)) * value(0);
  }
  for (int i = 0; i < n; ++i) {
    rhs.row(row++) = (4.0 * knots.C1(i) - 1.0) * value(i) + (4.0 * knots.C0(i + 1) - 1.0) * value(i + 1);
  }
  if (!knots.closed()) {
    rhs.row(row) = endSlope - 4.0 * (1.0 - knots.C0(n)) * value(n);
  }
  Eigen::MatrixXd x = lu_.solve(rhs);
  if (lu_.info() != Eigen::Success || !x.allFinite()) {
    throw CardinalSplineError("CubicShapeSolver::solve: solving the cubic-mode system failed");
  }
  // A direct solve: check the residual rather than trust it, so an ill-conditioned knot
  // vector is reported instead of returning a wrong shape.
  const double residual = (matrix_ * x - rhs).cwiseAbs().maxCoeff();
  const double scale = 1.0 + rhs.cwiseAbs().maxCoeff() + x.cwiseAbs().maxCoeff();
  if (!(residual <= 1e-9 * scale)) {
    throw CardinalSplineError("CubicShapeSolver::solve: residual " + std::to_string(residual) +
                              " exceeds 1e-9 * " + std::to_string(scale) +
                              " (ill-conditioned knot spacing?)");
  }
  return x;
}

Eigen::MatrixX3d sigmaShapePoints(const SigmaKnots& knots, const Eigen::MatrixX3d& points,
                                  ShapeMode mode, const EndSlopes& slopes) {
  checkPointCount(knots, points.rows(), "sigmaShapePoints");
  switch (mode) {
    case ShapeMode::Midpoint: return midpointShapePoints(knots, points);
    case ShapeMode::Heuristic: return heuristicShapePoints(knots, points);
    case ShapeMode::Cubic: break;
  }
  const int n = knots.last();
  Eigen::MatrixXd start = Eigen::MatrixXd::Zero(1, 3), end = Eigen::MatrixXd::Zero(1, 3);
  if (!knots.closed()) {
    start = slopes.start ? Eigen::MatrixXd(slopes.start->transpose())
                         : Eigen::MatrixXd(points.row(1) - points.row(0));
    end = slopes.end ? Eigen::MatrixXd(slopes.end->transpose())
                     : Eigen::MatrixXd(points.row(n) - points.row(n - 1));
  }
  return CubicShapeSolver(knots).solve(points, start, end);
}

SigmaCurve interpolateSigmaCurve(const SigmaKnots& knots, const Eigen::MatrixX3d& points,
                                 ShapeMode mode, const EndSlopes& slopes) {
  return SigmaCurve(knots, points, sigmaShapePoints(knots, points, mode, slopes));
}

namespace {

// Grid <-> batched right-hand sides. "Along u": one row per u index, 3 columns per v index.
Eigen::MatrixXd packAlongU(const PointGrid& g) {
  Eigen::MatrixXd m(g.rows, 3 * g.cols);
  for (int i = 0; i < g.rows; ++i)
    for (int j = 0; j < g.cols; ++j) m.block<1, 3>(i, 3 * j) = g(i, j).transpose();
  return m;
}
PointGrid unpackAlongU(const Eigen::MatrixXd& m) {
  PointGrid g(static_cast<int>(m.rows()), static_cast<int>(m.cols() / 3));
  for (int i = 0; i < g.rows; ++i)
    for (int j = 0; j < g.cols; ++j) g(i, j) = m.block<1, 3>(i, 3 * j).transpose();
  return g;
}
Eigen::MatrixXd packAlongV(const PointGrid& g) {
  Eigen::MatrixXd m(g.cols, 3 * g.rows);
  for (int i = 0; i < g.rows; ++i)
    for (int j = 0; j < g.cols; ++j) m.block<1, 3>(j, 3 * i) = g(i, j).transpose();
  return m;
}
PointGrid unpackAlongV(const Eigen::MatrixXd& m) {
  PointGrid g(static_cast<int>(m.cols() / 3), static_cast<int>(m.rows()));
  for (int i = 0; i < g.rows; ++i)
    for (int j = 0; j < g.cols; ++j) g(i, j) = m.block<1, 3>(j, 3 * i).transpose();
  return g;
}
// Flattens an #k x 3 matrix of per-curve vectors to one 1 x 3k row.
Eigen::MatrixXd flatten(const Eigen::MatrixXd& m) {
  Eigen::MatrixXd row(1, 3 * m.rows());
  for (Eigen::Index k = 0; k < m.rows(); ++k) row.block<1, 3>(0, 3 * k) = m.row(k).head<3>();
  return row;
}
Eigen::MatrixXd endData(const std::optional<Eigen::MatrixX3d>& given, Eigen::Index count,
                        const Eigen::MatrixXd& chord, const char* name) {
  if (!given) return chord;
  if (given->rows() != count) {
    throw CardinalSplineError(std::string("interpolateSigmaSurface: ends.") + name + " must be " +
                              std::to_string(count) + " x 3, got " +
                              std::to_string(given->rows()) + " x 3");
  }
  return Eigen::MatrixXd(*given);
}

// Shape points along u of every column of g (or along v of every row) for the local modes.
PointGrid localShapesAlongU(const SigmaKnots& knots, const PointGrid& g, ShapeMode mode) {
  PointGrid out(knots.shapeCount(), g.cols);
  for (int j = 0; j < g.cols; ++j) {
    const Eigen::MatrixX3d s = sigmaShapePoints(knots, g.col(j), mode);
    for (int r = 0; r < out.rows; ++r) out(r, j) = s.row(r).transpose();
  }
  return out;
}
PointGrid localShapesAlongV(const SigmaKnots& knots, const PointGrid& g, ShapeMode mode) {
  PointGrid out(g.rows, knots.shapeCount());
  for (int i = 0; i < g.rows; ++i) {
    const Eigen::MatrixX3d s = sigmaShapePoints(knots, g.row(i), mode);
    for (int r = 0; r < out.cols; ++r) out(i, r) = s.row(r).transpose();
  }
  return out;
}

}  // namespace

SigmaSurfaceResult interpolateSigmaSurface(const SigmaKnots& knotsU, const SigmaKnots& knotsV,
                                           const PointGrid& points,
                                           const SigmaSurfaceOptions& options) {
  const int rows = knotsU.pointCount();
  const int cols = knotsV.pointCount();
  if (points.rows != rows || points.cols != cols ||
      static_cast<int>(points.data.size()) != rows * cols) {
    throw CardinalSplineError("interpolateSigmaSurface: expected a " + std::to_string(rows) +
                              " x " + std::to_string(cols) + " point grid for the knots, got " +
                              std::to_string(points.rows) + " x " + std::to_string(points.cols));
  }
  SigmaSurfaceResult result{SigmaSurface{knotsU, knotsV, points, {}, {}, {}}, 0.0};
  SigmaSurface& s = result.surface;
  if (options.mode != ShapeMode::Cubic) {
    s.Pu = localShapesAlongU(knotsU, points, options.mode);
    s.Pv = localShapesAlongV(knotsV, points, options.mode);
    // sec. 3.3.4: Puv = (H_v(Pu) + H_u(Pv)) / 2.
    const PointGrid a = localShapesAlongV(knotsV, s.Pu, options.mode);
    const PointGrid b = localShapesAlongU(knotsU, s.Pv, options.mode);
    s.Puv = PointGrid(a.rows, a.cols);
    for (std::size_t k = 0; k < a.data.size(); ++k) s.Puv.data[k] = 0.5 * (a.data[k] + b.data[k]);
    return result;
  }

  const CubicShapeSolver solverU(knotsU);
  const CubicShapeSolver solverV(knotsV);
  const SurfaceEndData& ends = options.ends;
  const int m = rows - 1;
  const int n = cols - 1;
  // Cross-boundary derivative data, one row per curve (chord rule by default, Kuriyama 1996,
  // sec. 3.2.2).
  Eigen::MatrixXd uStart = Eigen::MatrixXd::Zero(cols, 3), uEnd = uStart;
  Eigen::MatrixXd vStart = Eigen::MatrixXd::Zero(rows, 3), vEnd = vStart;
  if (!knotsU.closed()) {
    uStart = endData(ends.uStart, cols, points.row(1) - points.row(0), "uStart");
    uEnd = endData(ends.uEnd, cols, points.row(m) - points.row(m - 1), "uEnd");
  }
  if (!knotsV.closed()) {
    vStart = endData(ends.vStart, rows, points.col(1) - points.col(0), "vStart");
    vEnd = endData(ends.vEnd, rows, points.col(n) - points.col(n - 1), "vEnd");
  }
  std::array<Eigen::Vector3d, 4> twist;
  twist.fill(Eigen::Vector3d::Zero());
  if (ends.twists) twist = *ends.twists;
  const auto asRow = [](const Eigen::Vector3d& v) { return Eigen::MatrixXd(v.transpose()); };

  s.Pu = unpackAlongU(solverU.solve(packAlongU(points), flatten(uStart), flatten(uEnd)));
  s.Pv = unpackAlongV(solverV.solve(packAlongV(points), flatten(vStart), flatten(vEnd)));

  // u-route: the u-system on every v-shape column with (X, Y) = (Puv, Pv). Its end data are
  // the v-shape values of the cross-boundary derivatives: the consistent rule of
  // Kuriyama 1996, sec. 3.3.5.
  Eigen::MatrixXd pvuStart = Eigen::MatrixXd::Zero(knotsV.shapeCount(), 3), pvuEnd = pvuStart;
  if (!knotsU.closed() && !options.thesisZeroCrossDefaults) {
    pvuStart = solverV.solve(uStart, asRow(twist[0]), asRow(twist[1]));
    pvuEnd = solverV.solve(uEnd, asRow(twist[2]), asRow(twist[3]));
  }
  s.Puv = unpackAlongU(solverU.solve(packAlongU(s.Pv), flatten(pvuStart), flatten(pvuEnd)));

  if (options.crossCheckRoutes) {
    Eigen::MatrixXd puvStart = Eigen::MatrixXd::Zero(knotsU.shapeCount(), 3), puvEnd = puvStart;
    if (!knotsV.closed() && !options.thesisZeroCrossDefaults) {
      puvStart = solverU.solve(vStart, asRow(twist[0]), asRow(twist[2]));
      puvEnd = solverU.solve(vEnd, asRow(twist[1]), asRow(twist[3]));
    }
    const PointGrid other =
        unpackAlongV(solverV.solve(packAlongV(s.Pu), flatten(puvStart), flatten(puvEnd)));
    for (std::size_t k = 0; k < other.data.size(); ++k) {
      result.routeDiscrepancy =
          std::max(result.routeDiscrepancy, (other.data[k] - s.Puv.data[k]).norm());
    }
  }
  return result;
}

}  // namespace ffdkit::geometry::cardinal
