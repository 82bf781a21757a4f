#pragma once

#include <vector>

#include <Eigen/Core>

namespace ffdkit::ffd {

/// What basis one lattice axis uses (seed 001 eq. (6.1), l.2351: Bernstein or B-spline).
/// A description, independent of the number of control points; a Lattice resolves it into an
/// AxisSpline for its count. Value type; cheap to copy.
struct AxisBasis {
  enum class Kind {
    Bernstein,      ///< degree count-1, parameter domain [0, 1] (Sederberg & Parry 1986).
    BSpline,        ///< clamped; uniform knots unless `knots` is given.
    PeriodicBSpline ///< closed axis (the angle of a cylindrical lattice), uniform knots, domain [0, 1).
  };

  Kind kind = Kind::BSpline;
  int degree = 3;          ///< B-spline degree, 1 <= degree <= count-1 (ignored for Bernstein).
  Eigen::VectorXd knots;   ///< BSpline only: explicit non-decreasing knots of length count+degree+1,
                           ///< empty = clamped uniform on [0, 1]. The domain is [knots[degree], knots[count]].

  static AxisBasis bernstein() { return AxisBasis{Kind::Bernstein, 0, {}}; }
  /// Clamped uniform B-spline (the default basis) of the given degree.
  static AxisBasis bspline(int degree = 3) { return AxisBasis{Kind::BSpline, degree, {}}; }
  /// Clamped or unclamped B-spline with explicit non-uniform knots (size count+degree+1).
  static AxisBasis bsplineWithKnots(int degree, Eigen::VectorXd knots) {
    return AxisBasis{Kind::BSpline, degree, std::move(knots)};
  }
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

  const AxisBasis& basis() const { return basis_; }
  int count() const { return count_; }
  int degree() const { return degree_; }
  bool periodic() const { return periodic_; }
  double domainMin() const { return lo_; }
  double domainMax() const { return hi_; }
  int cellCount() const { return static_cast<int>(cellSpan_.size()); }
  const std::vector<double>& knots() const { return knots_; }
  /// Knot index of the span of cell c.
  int cellSpan(int cell) const { return cellSpan_[cell]; }
  double cellMin(int cell) const { return knots_[cellSpan_[cell]]; }
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

}  // namespace ffdkit::ffd
