#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

namespace ffdkit::ffd {

/// What basis one lattice axis uses (Kuriyama 1996, sec. 6.3.2, eq. (6.1): Bernstein or B-spline).
/// A description, independent of the number of control points; a Lattice resolves it into an
/// AxisSpline for its count. Value type; cheap to copy.
struct AxisBasis {
  /// The kind of basis along one axis.
  enum class Kind {
    Bernstein,      ///< degree count-1, parameter domain [0, 1] (Sederberg & Parry 1986).
    BSpline,        ///< clamped; uniform knots unless `knots` is given.
    PeriodicBSpline ///< closed axis (the angle of a cylindrical lattice), uniform knots, domain [0, 1).
  };

  Kind kind = Kind::BSpline;  ///< Bernstein, clamped B-spline (default) or periodic B-spline.
  int degree = 3;          ///< B-spline degree, 1 <= degree <= count-1 (ignored for Bernstein).
  Eigen::VectorXd knots;   ///< BSpline only: explicit non-decreasing knots of length count+degree+1,
                           ///< empty = clamped uniform on [0, 1]. The domain is [knots[degree], knots[count]].

  /// The Bernstein (Bezier) basis of degree count-1 (Sederberg & Parry 1986).
  static AxisBasis bernstein() { return AxisBasis{Kind::Bernstein, 0, {}}; }
  /// Clamped uniform B-spline (the default basis) of the given degree.
  static AxisBasis bspline(int degree = 3) { return AxisBasis{Kind::BSpline, degree, {}}; }
  /// Clamped or unclamped B-spline with explicit non-uniform knots (size count+degree+1).
  static AxisBasis bsplineWithKnots(int degree, Eigen::VectorXd knots) {
    return AxisBasis{Kind::BSpline, degree, std::move(knots)};
  }
  /// A periodic (closed) uniform B-spline of the given degree, for an angular axis.
  static AxisBasis periodic(int degree = 3) { return AxisBasis{Kind::PeriodicBSpline, degree, {}}; }
};

/// An AxisBasis resolved for `count` control points: the knot vector, the parameter domain,
/// the cells (non-empty knot spans inside the domain) and the Greville abscissae.
/// Bernstein is the single-span B-spline with knots 0^(count) 1^(count), so one code path
/// evaluates every basis.
class AxisSpline {
 public:
  AxisSpline() = default;
  /// @throws LatticeError if count < 2, the degree is out of [1, count-1], or the knots are bad
  /// (wrong length, decreasing, non-finite, empty domain). `axisName` goes into the message.
  AxisSpline(const AxisBasis& basis, int count, const char* axisName = "axis");

  /// The basis as given.
  const AxisBasis& basis() const { return basis_; }
  /// Number of control points along the axis.
  int count() const { return count_; }
  /// Polynomial degree (count-1 for Bernstein).
  int degree() const { return degree_; }
  /// True for a periodic (closed) axis.
  bool periodic() const { return periodic_; }
  /// Lower end of the parameter domain.
  double domainMin() const { return lo_; }
  /// Upper end of the parameter domain.
  double domainMax() const { return hi_; }
  /// Number of cells (non-empty knot spans inside the domain).
  int cellCount() const { return static_cast<int>(cellSpan_.size()); }
  /// The full knot vector.
  const std::vector<double>& knots() const { return knots_; }
  /// Knot index of the span of cell c.
  int cellSpan(int cell) const { return cellSpan_[cell]; }
  /// Lower parameter of cell `cell`.
  double cellMin(int cell) const { return knots_[cellSpan_[cell]]; }
  /// Upper parameter of cell `cell`.
  double cellMax(int cell) const { return knots_[cellSpan_[cell] + 1]; }
  /// Cell containing t; t outside the domain goes to the first / last cell (extrapolation).
  /// Periodic axes wrap t into [0, 1) first (see wrap()).
  int cellOf(double t) const;
  /// Periodic axes: t mod 1 in [0, 1); other axes: t unchanged.
  double wrap(double t) const;
  /// Control point index (along this axis) of the r-th basis function non-zero on the cell.
  int controlIndex(int cell, int r) const {
    const int i = cellSpan_[cell] - degree_ + r;
    return periodic_ ? (i % count_ + count_) % count_ : i;
  }
  /// The degree+1 non-zero basis values (and optionally derivatives) on `cell` at t.
  void basis(int cell, double t, double* values, double* derivatives = nullptr) const;
  /// Greville abscissae, one per control point (periodic: in [0, 1), possibly wrapped).
  const Eigen::VectorXd& greville() const { return greville_; }

 private:
  AxisBasis basis_;
  int count_ = 0;
  int degree_ = 0;
  bool periodic_ = false;
  double lo_ = 0.0;
  double hi_ = 1.0;
  std::vector<double> knots_;
  std::vector<int> cellSpan_;
  std::vector<double> breaks_;  // cell boundaries, cellCount()+1 values
  // Per cell, the reciprocals of the Cox-de Boor denominators (degree*(degree+1)/2 values):
  // divisions dominated Newton embedding, and the knots of a cell never change.
  std::vector<double> inverses_;
  Eigen::VectorXd greville_;
};

// Inline: Newton embedding evaluates the basis several times per point.
inline double AxisSpline::wrap(double t) const {
  if (!periodic_) return t;
  double w = t - std::floor(t);
  if (w >= 1.0) w = 0.0;
  return w;
}

inline int AxisSpline::cellOf(double t) const {
  t = wrap(t);
  const int cells = cellCount();
  if (!(t > breaks_[1])) return 0;  // also catches NaN
  if (t >= breaks_[cells - 1]) return cells - 1;
  const auto it = std::upper_bound(breaks_.begin() + 1, breaks_.end() - 1, t);
  return static_cast<int>(it - breaks_.begin()) - 1;
}

inline void AxisSpline::basis(int cell, double t, double* values, double* derivatives) const {
  // Cox-de Boor (The NURBS Book A2.2 / A2.3) with the cell's precomputed reciprocals.
  const int p = degree_;
  const int s = cellSpan_[cell];
  const double* U = knots_.data();
  const double* inv = inverses_.data() + static_cast<std::size_t>(cell) * p * (p + 1) / 2;
  t = wrap(t);
  double left[34];
  double right[34];
  double lower[34];
  values[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    if (j == p && derivatives != nullptr) {
      for (int r = 0; r < p; ++r) lower[r] = values[r];
    }
    left[j] = t - U[s + 1 - j];
    right[j] = U[s + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r, ++inv) {
      const double temp = values[r] * *inv;
      values[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    values[j] = saved;
  }
  if (derivatives == nullptr) return;
  // dN_(s-p+r) = p (lower[r-1] / (U[s+r] - U[s-p+r]) - lower[r] / (U[s+r+1] - U[s-p+r+1])); these are
  // the reciprocals of the last row (j = p), which `inv` has just walked past.
  const double* last = inv - p;
  for (int r = 0; r <= p; ++r) {
    double d = 0.0;
    if (r >= 1) d += lower[r - 1] * last[r - 1];
    if (r < p) d -= lower[r] * last[r];
    derivatives[r] = p * d;
  }
}

}  // namespace ffdkit::ffd
