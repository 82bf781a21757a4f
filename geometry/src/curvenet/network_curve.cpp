#include "ffdkit/geometry/curvenet/network_curve.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "../eigen_sparse_lu_instance.h"

namespace ffdkit::geometry::curvenet {
namespace {

// Piegl & Tiller, The NURBS Book, A2.2: the degree+1 nonzero basis functions on span s.
Eigen::VectorXd basisFunctions(const std::vector<double>& knots, int degree, int span, double t) {
  Eigen::VectorXd n = Eigen::VectorXd::Zero(degree + 1);
  Eigen::VectorXd left(degree + 1), right(degree + 1);
  n[0] = 1.0;
  for (int j = 1; j <= degree; ++j) {
    left[j] = t - knots[span + 1 - j];
    right[j] = knots[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = n[r] / (right[r + 1] + left[j - r]);
      n[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    n[j] = saved;
  }
  return n;
}

// Polynomial pieces of a B-spline (knots, control points already wrapped for periodic curves)
// over spans [first, last]: each span's polynomial is recovered exactly from degree+1 samples.
std::vector<CurveSegment> spansToSegments(const std::vector<double>& knots, int degree,
                                          const Eigen::MatrixX3d& ctrl, int first, int last) {
  std::vector<CurveSegment> segments;
  for (int s = first; s <= last; ++s) {
    const double t0 = knots[s], t1 = knots[s + 1];
    if (!(t1 > t0)) continue;
    const double h = t1 - t0;
    Eigen::MatrixXd vander(degree + 1, degree + 1);
    Eigen::MatrixX3d values(degree + 1, 3);
    for (int q = 0; q <= degree; ++q) {
      const double sigma = (degree == 0) ? 0.5 : 0.1 + 0.8 * q / degree;
      const Eigen::VectorXd n = basisFunctions(knots, degree, s, t0 + sigma * h);
      values.row(q).setZero();
      for (int r = 0; r <= degree; ++r) values.row(q) += n[r] * ctrl.row(s - degree + r);
      for (int j = 0; j <= degree; ++j) vander(q, j) = std::pow(sigma, j);
    }
    Eigen::MatrixX3d a = vander.partialPivLu().solve(values);
    for (int j = 0; j <= degree; ++j) a.row(j) /= std::pow(h, j);
    segments.push_back({t0, t1, a});
  }
  return segments;
}

std::vector<double> periodicKnots(const std::vector<double>& breaks, int degree) {
  const int n = static_cast<int>(breaks.size()) - 1;
  const double period = breaks.back() - breaks.front();
  std::vector<double> knots(n + 2 * degree + 1);
  for (int j = 0; j < static_cast<int>(knots.size()); ++j) {
    const int idx = j - degree;
    const int q = static_cast<int>(std::floor(static_cast<double>(idx) / n));
    knots[j] = breaks[idx - q * n] + q * period;
  }
  return knots;
}

}  // namespace

NetworkCurve::NetworkCurve(std::vector<CurveSegment> segments, bool closed)
    : segments_(std::move(segments)), closed_(closed) {
  if (segments_.empty()) throw CurveInputError("network curve needs >= 1 segment, got 0");
  for (std::size_t k = 0; k < segments_.size(); ++k) {
    if (!(segments_[k].t1 > segments_[k].t0) || segments_[k].coefficients.rows() < 1) {
      std::ostringstream msg;
      msg << "network curve segment " << k << " needs t1 > t0 and >= 1 coefficient row, got ["
          << segments_[k].t0 << ", " << segments_[k].t1 << "]";
      throw CurveInputError(msg.str());
    }
    if (k > 0 && std::abs(segments_[k].t0 - segments_[k - 1].t1) >
                      1e-12 * (1.0 + std::abs(segments_[k].t0))) {
      throw CurveInputError("network curve segments must be contiguous in t");
    }
  }
}

double NetworkCurve::wrap(double t) const {
  if (!closed_) return t;
  const double p = period();
  double w = t - p * std::floor((t - tMin()) / p);
  if (w >= tMax()) w -= p;
  if (w < tMin()) w = tMin();
  return w;
}

int NetworkCurve::segmentIndex(double t) const {
  const auto it = std::upper_bound(segments_.begin(), segments_.end(), t,
                                   [](double value, const CurveSegment& s) { return value < s.t1; });
  if (it == segments_.end()) return static_cast<int>(segments_.size()) - 1;
  return static_cast<int>(it - segments_.begin());
}

Eigen::Vector3d NetworkCurve::evaluate(double t, int derivative) const {
  const double tw = wrap(t);
  const CurveSegment& seg = segments_[segmentIndex(tw)];
  const double s = tw - seg.t0;
  const int degree = static_cast<int>(seg.coefficients.rows()) - 1;
  Eigen::Vector3d result = Eigen::Vector3d::Zero();
  // Horner on the derivative's coefficients j!/(j-k)! a_j.
  for (int j = degree; j >= derivative; --j) {
    double factor = 1.0;
    for (int r = 0; r < derivative; ++r) factor *= (j - r);
    result = result * s + factor * seg.coefficients.row(j).transpose();
  }
  return result;
}

NetworkCurve NetworkCurve::plus(const NetworkCurve& displacement) const {
  if (displacement.segments_.size() != segments_.size()) {
    throw CurveInputError("curve correction: displacement has different breakpoints");
  }
  std::vector<CurveSegment> sum = segments_;
  for (std::size_t k = 0; k < sum.size(); ++k) {
    const Eigen::MatrixX3d& d = displacement.segments_[k].coefficients;
    Eigen::MatrixX3d& c = sum[k].coefficients;
    if (d.rows() > c.rows()) {
      Eigen::MatrixX3d grown = Eigen::MatrixX3d::Zero(d.rows(), 3);
      grown.topRows(c.rows()) = c;
      c = grown;
    }
    c.topRows(d.rows()) += d;
  }
  return NetworkCurve(std::move(sum), closed_);
}

void NetworkCurve::sample(int perSegment, Eigen::MatrixX3d& points,
                          Eigen::VectorXd& parameters) const {
  const int m = static_cast<int>(segments_.size());
  const int count = m * perSegment + (closed_ ? 0 : 1);
  points.resize(count, 3);
  parameters.resize(count);
  int row = 0;
  for (const CurveSegment& seg : segments_) {
    for (int q = 0; q < perSegment; ++q) {
      parameters[row] = seg.t0 + (seg.t1 - seg.t0) * q / perSegment;
      points.row(row) = evaluate(parameters[row]).transpose();
      ++row;
    }
  }
  if (!closed_) {
    parameters[row] = tMax();
    points.row(row) = evaluate(tMax()).transpose();
  }
}

NetworkCurve interpolateCubicSpline(const Eigen::MatrixX3d& points, bool closed,
                                    KnotSpacing spacing) {
  const int n = static_cast<int>(points.rows());
  if (n < (closed ? 3 : 2)) {
    std::ostringstream msg;
    msg << "cubic spline interpolation needs >= " << (closed ? 3 : 2) << " points ("
        << (closed ? "closed" : "open") << "), got " << n;
    throw CurveInputError(msg.str());
  }
  const int segs = closed ? n : n - 1;
  auto point = [&](int k) -> Eigen::Vector3d { return points.row(((k % n) + n) % n).transpose(); };
  Eigen::VectorXd h(segs);
  Eigen::Matrix2d sigmaInv = Eigen::Matrix2d::Identity();
  Eigen::Matrix<double, 3, 2> frame = Eigen::Matrix<double, 3, 2>::Zero();
  bool affine = spacing == KnotSpacing::AffineInvariant;
  if (affine) {
    const Eigen::RowVector3d mean = points.colwise().mean();
    const Eigen::MatrixX3d centred = points.rowwise() - mean;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(centred.transpose() * centred / n);
    frame.col(0) = eig.eigenvectors().col(2);
    frame.col(1) = eig.eigenvectors().col(1);
    const Eigen::Vector2d ev(eig.eigenvalues()[2], eig.eigenvalues()[1]);
    if (ev[1] <= 1e-12 * ev[0]) {
      affine = false;  // collinear points: the covariance is singular, fall back to chords
    } else {
      sigmaInv = Eigen::Vector2d(1.0 / ev[0], 1.0 / ev[1]).asDiagonal();
    }
  }
  for (int k = 0; k < segs; ++k) {
    const Eigen::Vector3d d = point(k + 1) - point(k);
    const double chord = d.norm();
    if (!(chord > 0.0)) {
      std::ostringstream msg;
      msg << "cubic spline interpolation needs distinct consecutive points; points " << k
          << " and " << (k + 1) % n << " coincide";
      throw CurveInputError(msg.str());
    }
    if (spacing == KnotSpacing::Centripetal) {
      h[k] = std::sqrt(chord);
    } else if (affine) {
      const Eigen::Vector2d q = frame.transpose() * d;
      h[k] = std::sqrt(q.dot(sigmaInv * q));
    } else {
      h[k] = chord;
    }
  }
  // Tangent system (2.3), sec. 2.3.2: rows for interior (or all, periodic) points. Tridiagonal
  // (cyclic when closed), so sparse: pen strokes can have many points.
  std::vector<Eigen::Triplet<double>> a;
  Eigen::MatrixX3d rhs(n, 3);
  for (int i = 0; i < n; ++i) {
    const bool first = !closed && i == 0, last = !closed && i == n - 1;
    if (first) {
      a.emplace_back(0, 0, 2.0);
      a.emplace_back(0, 1, 1.0);
      rhs.row(0) = 3.0 * (point(1) - point(0)).transpose() / h[0];
    } else if (last) {
      a.emplace_back(i, i - 1, 1.0);
      a.emplace_back(i, i, 2.0);
      rhs.row(i) = 3.0 * (point(i) - point(i - 1)).transpose() / h[i - 1];
    } else {
      const double hp = h[(i - 1 + segs) % segs], hc = h[i % segs];
      a.emplace_back(i, (i - 1 + n) % n, hc);  // duplicates (n = 2 wraps) are summed
      a.emplace_back(i, i, 2.0 * (hp + hc));
      a.emplace_back(i, (i + 1) % n, hp);
      rhs.row(i) = 3.0 * ((hc / hp) * (point(i) - point(i - 1)) +
                          (hp / hc) * (point(i + 1) - point(i)))
                             .transpose();
    }
  }
  Eigen::SparseMatrix<double> system(n, n);
  system.setFromTriplets(a.begin(), a.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(system);
  if (lu.info() != Eigen::Success) {
    throw CurveInputError("cubic spline interpolation: the tangent system is singular (" +
                          std::to_string(n) + " points)");
  }
  const Eigen::MatrixX3d tangents = lu.solve(rhs);
  std::vector<CurveSegment> segments;
  double t = 0.0;
  for (int k = 0; k < segs; ++k) {
    const double hk = h[k];
    const Eigen::RowVector3d p0 = point(k).transpose(), p1 = point(k + 1).transpose();
    const Eigen::RowVector3d d0 = tangents.row(k), d1 = tangents.row((k + 1) % n);
    Eigen::MatrixX3d c(4, 3);
    c.row(0) = p0;
    c.row(1) = d0;
    c.row(2) = (3.0 * (p1 - p0) / hk - 2.0 * d0 - d1) / hk;
    c.row(3) = (d0 + d1 - 2.0 * (p1 - p0) / hk) / (hk * hk);
    segments.push_back({t, t + hk, c});
    t += hk;
  }
  return NetworkCurve(std::move(segments), closed);
}

NetworkCurve bsplineCurve(const Eigen::MatrixX3d& controlPoints, int degree,
                          const std::vector<double>& knots, bool closed) {
  const int n = static_cast<int>(controlPoints.rows());
  std::ostringstream msg;
  if (degree < 1) {
    msg << "B-spline degree must be >= 1, got " << degree;
    throw CurveInputError(msg.str());
  }
  for (std::size_t k = 1; k < knots.size(); ++k) {
    if (knots[k] < knots[k - 1] || (closed && !(knots[k] > knots[k - 1]))) {
      msg << "B-spline knots must be " << (closed ? "strictly increasing" : "nondecreasing")
          << "; knot " << k << " = " << knots[k] << " after " << knots[k - 1];
      throw CurveInputError(msg.str());
    }
  }
  if (closed) {
    if (n < degree + 1 || static_cast<int>(knots.size()) != n + 1) {
      msg << "closed B-spline of degree " << degree << " needs >= " << degree + 1
          << " control points and #controlPoints + 1 = " << n + 1 << " breakpoints, got " << n
          << " control points and " << knots.size() << " breakpoints";
      throw CurveInputError(msg.str());
    }
    Eigen::MatrixX3d wrapped(n + degree, 3);
    for (int i = 0; i < n + degree; ++i) wrapped.row(i) = controlPoints.row(i % n);
    const std::vector<double> ext = periodicKnots(knots, degree);
    return NetworkCurve(spansToSegments(ext, degree, wrapped, degree, degree + n - 1), true);
  }
  if (n < degree + 1 || static_cast<int>(knots.size()) != n + degree + 1) {
    msg << "open B-spline of degree " << degree << " needs >= " << degree + 1
        << " control points and #controlPoints + degree + 1 = " << n + degree + 1
        << " knots, got " << n << " control points and " << knots.size() << " knots";
    throw CurveInputError(msg.str());
  }
  if (!(knots[n] > knots[degree])) throw CurveInputError("open B-spline has an empty domain");
  return NetworkCurve(spansToSegments(knots, degree, controlPoints, degree, n - 1), false);
}

std::optional<Plane> fitCurvePlane(const NetworkCurve& curve, double relativeTolerance) {
  Eigen::MatrixX3d pts;
  Eigen::VectorXd params;
  curve.sample(16, pts, params);
  const Eigen::RowVector3d mean = pts.colwise().mean();
  const Eigen::MatrixX3d centred = pts.rowwise() - mean;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(centred.transpose() * centred);
  const double extent = (pts.colwise().maxCoeff() - pts.colwise().minCoeff()).norm();
  if (!(extent > 0.0)) return std::nullopt;
  const Eigen::Vector3d normal = eig.eigenvectors().col(0);
  // A straight curve lies in a pencil of planes: no unique drawing plane.
  if (std::sqrt(std::max(0.0, eig.eigenvalues()[1]) / pts.rows()) < 1e-9 * extent) {
    return std::nullopt;
  }
  const double off = (centred * normal).cwiseAbs().maxCoeff();
  if (off > relativeTolerance * extent) return std::nullopt;
  return Plane{mean.transpose(), normal};
}

NetworkCurve correctionSpline(const NetworkCurve& curve, const std::vector<double>& parameters,
                              const Eigen::MatrixX3d& displacements) {
  constexpr int kDegree = 3;
  std::vector<double> breaks;
  for (const CurveSegment& s : curve.segments()) breaks.push_back(s.t0);
  breaks.push_back(curve.tMax());
  const int spans = static_cast<int>(breaks.size()) - 1;
  std::vector<double> knots;
  int controls = 0;
  if (curve.closed()) {
    knots = periodicKnots(breaks, kDegree);
    controls = spans;
  } else {
    knots.assign(kDegree, breaks.front());
    knots.insert(knots.end(), breaks.begin(), breaks.end());
    knots.insert(knots.end(), kDegree, breaks.back());
    controls = spans + kDegree;
  }
  const int rows = static_cast<int>(parameters.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(rows, controls);
  for (int r = 0; r < rows; ++r) {
    const double t = curve.wrap(parameters[r]);
    int span = kDegree + static_cast<int>(std::upper_bound(breaks.begin(), breaks.end(), t) -
                                          breaks.begin()) - 1;
    span = std::clamp(span, kDegree, kDegree + spans - 1);
    const Eigen::VectorXd nb = basisFunctions(knots, kDegree, span, t);
    for (int q = 0; q <= kDegree; ++q) {
      const int col = curve.closed() ? (span - kDegree + q) % controls : span - kDegree + q;
      a(r, col) += nb[q];
    }
  }
  Eigen::MatrixX3d coefficients = Eigen::MatrixX3d::Zero(controls, 3);
  if (rows > 0) coefficients = a.completeOrthogonalDecomposition().solve(displacements);
  if (curve.closed()) {
    Eigen::MatrixX3d wrapped(controls + kDegree, 3);
    for (int i = 0; i < controls + kDegree; ++i) wrapped.row(i) = coefficients.row(i % controls);
    return NetworkCurve(spansToSegments(knots, kDegree, wrapped, kDegree, kDegree + spans - 1),
                        true);
  }
  return NetworkCurve(spansToSegments(knots, kDegree, coefficients, kDegree, kDegree + spans - 1),
                      false);
}

}  // namespace ffdkit::geometry::curvenet
