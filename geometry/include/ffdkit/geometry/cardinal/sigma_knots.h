#pragma once

#include <optional>

#include <Eigen/Core>

namespace ffdkit::geometry::cardinal {

/// Options of SigmaKnots.
struct SigmaKnotsOptions {
  bool closed = false;  ///< periodic knots: t_n is the period end, beta2 has n entries
  /// Open ends only: widths of the phantom intervals Delta_{-1} and Delta_n, which the
  /// thesis leaves undefined (Kuriyama 1996, sec. 3.2.2). Unset: Delta_{-1} = Delta_0, Delta_n =
  /// Delta_{n-1}.
  std::optional<double> phantomBefore;
  std::optional<double> phantomAfter;  ///< Delta_n; see phantomBefore
};

/// Simple knots t_0 < ... < t_n of a sigma-spline (each a triple knot of the underlying
/// quartic B-splines) with a tension beta2_i >= 0 per knot, and the basis coefficients of
/// eq. (3.18)-(3.23) (D_i, C_{i,0}, C_{i,1}, Chat_{i,0,1,3,4}). Indices may run one past the
/// ends: open knots use the phantom widths, closed knots wrap modulo n.
/// @see Kuriyama 1996, sec. 3.3.2.
class SigmaKnots {
 public:
  /// knots: n+1 strictly increasing values (n >= 1 open, n >= 3 closed), gaps
  /// > 1e-12 * range. beta2: n+1 values (open) or n values (closed), all >= 0; empty = all 0.
  /// @throws CardinalSplineError naming the offending index.
  SigmaKnots(const Eigen::VectorXd& knots, const Eigen::VectorXd& beta2 = {},
             const SigmaKnotsOptions& options = {});

  /// Uniform knots 0, 1, ..., n with zero tension.
  static SigmaKnots uniform(int n, bool closed = false);

  int last() const { return n_; }  ///< n
  /// True for periodic knots.
  bool closed() const { return options_.closed; }
  /// The knots t_0 .. t_n.
  const Eigen::VectorXd& knots() const { return t_; }
  /// beta2 per knot: n+1 (open) or n (closed) values.
  const Eigen::VectorXd& beta2Values() const { return beta2_; }
  /// The options the knots were built with.
  const SigmaKnotsOptions& options() const { return options_; }
  /// First knot t_0.
  double start() const { return t_[0]; }
  /// Last knot t_n.
  double end() const { return t_[n_]; }

  double knot(int i) const;   ///< t_i, wrapping by the period for closed knots
  double delta(int i) const;  ///< Delta_i = t_{i+1} - t_i, i in -1..n (phantom / periodic)
  double beta2(int i) const;  ///< beta2_i, i in 0..n (open) or any i (closed, periodic)
  double D(int i) const;      ///< 2/Delta_{i-1} + 2/Delta_i + beta2_i / 3
  double C0(int i) const;     ///< C_{i,0}
  double C1(int i) const;     ///< C_{i,1}
  double Chat0(int i) const;  ///< Chat_{i,0} = -Delta_{i-1} / (Delta_i^2 D_i)
  double Chat1(int i) const;  ///< Chat_{i,1} = 1 / (Delta_i D_i)
  double Chat3(int i) const;  ///< Chat_{i,3} = 1 / (Delta_i D_{i+1})
  double Chat4(int i) const;  ///< Chat_{i,4} = -Delta_{i+1} / (Delta_i^2 D_{i+1})

  int pointCount() const { return closed() ? n_ : n_ + 1; }  ///< interpolation points
  int shapeCount() const { return closed() ? n_ : n_ + 2; }  ///< shape points
  int shapeFirst() const { return closed() ? 0 : -1; }       ///< index of shape row 0
  /// Number of knot intervals n.
  int intervalCount() const { return n_; }

  /// Interval index i with x in [t_i, t_{i+1}) and the local parameter s = (x - t_i)/Delta_i.
  /// Closed knots wrap x into [t_0, t_n); open knots clamp x to [t_0, t_n] (t_n -> last
  /// interval, s = 1).
  int locate(double x, double& s) const;

 private:
  Eigen::VectorXd t_;
  Eigen::VectorXd beta2_;
  SigmaKnotsOptions options_;
  int n_ = 0;
};

}  // namespace ffdkit::geometry::cardinal
