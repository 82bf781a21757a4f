#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ffdkit::geometry::curvenet {

/// Thrown for curve input that cannot make a curve (too few points, bad knots, ...).
class CurveInputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A plane through `origin` with unit `normal`: the plane a network curve was drawn in.
struct Plane {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< a point of the plane
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit normal
};

/// Knot spacing for interpolating a polyline. @see Kuriyama 1996, secs. 5.3.1, 5.3.3.
enum class KnotSpacing {
  ChordLength,     ///< dt_k proportional to |P_{k+1} - P_k| (sec. 5.3.3)
  Centripetal,     ///< dt_k proportional to |P_{k+1} - P_k|^(1/2) (sec. 5.3.3)
  AffineInvariant  ///< Nielson-Foley: dt_k = sqrt(d^T S^-1 d), S the in-plane covariance (sec. 5.3.3)
};

/// One segment of a piecewise polynomial: K(t) = sum_j coefficients.row(j) (t - t0)^j on [t0, t1].
struct CurveSegment {
  double t0 = 0.0;  ///< start parameter
  double t1 = 1.0;  ///< end parameter
  Eigen::MatrixX3d coefficients;  ///< (degree + 1) x 3, power basis in (t - t0)
};

/// A C^n parametric space curve of the network, stored as a piecewise polynomial (every
/// B-spline and every interpolating spline converts to this exactly).
///
/// Evaluation is defined for every real t: a closed curve is periodic, an open curve is
/// continued by the polynomial of its end segment (sec. 5.2.1: the transversal sweeps reach past a
/// segment's far vertex and must not be clamped).
class NetworkCurve {
 public:
  NetworkCurve() = default;
  /// @throws CurveInputError if segments is empty or not contiguous.
  NetworkCurve(std::vector<CurveSegment> segments, bool closed);

  /// Start of the parameter range.
  double tMin() const { return segments_.front().t0; }
  /// End of the parameter range.
  double tMax() const { return segments_.back().t1; }
  /// Parameter length, tMax() - tMin() (the period of a closed curve).
  double period() const { return tMax() - tMin(); }
  /// True for a closed (periodic) curve.
  bool closed() const { return closed_; }
  /// The polynomial pieces, in order.
  const std::vector<CurveSegment>& segments() const { return segments_; }

  /// d^k K / dt^k at t, k = 0..3.
  Eigen::Vector3d evaluate(double t, int derivative = 0) const;
  /// t mapped into [tMin, tMax) for a closed curve; unchanged for an open one.
  double wrap(double t) const;

  /// The curve plus a displacement defined on the same breakpoints (curve correction).
  NetworkCurve plus(const NetworkCurve& displacement) const;

  /// n samples per segment (closed: no repeated end point), with their parameters.
  void sample(int perSegment, Eigen::MatrixX3d& points, Eigen::VectorXd& parameters) const;

 private:
  int segmentIndex(double t) const;
  std::vector<CurveSegment> segments_;
  bool closed_ = false;
};

/// C^2 cubic spline through the rows of points (the ch. 2 tangent system (2.3),
/// Kuriyama 1996 sec. 2.3.2; Hermite segments sec. 2.3.2). Open curves use natural end conditions, closed curves
/// the periodic system (the last point must not repeat the first). Parameters start at 0.
/// @param points #P x 3, #P >= 2 (open) or >= 3 (closed); consecutive points distinct.
/// @throws CurveInputError on too few or repeated points.
NetworkCurve interpolateCubicSpline(const Eigen::MatrixX3d& points, bool closed,
                                    KnotSpacing spacing = KnotSpacing::ChordLength);

/// A polynomial B-spline converted to piecewise polynomial form.
/// Open: #knots = #controlPoints + degree + 1, nondecreasing; domain [knots[p], knots[n]].
/// Closed (periodic): knots holds the #controlPoints + 1 breakpoints t_0 < ... < t_n of one
/// period and the control polygon wraps around.
/// @throws CurveInputError on inconsistent sizes or knots.
NetworkCurve bsplineCurve(const Eigen::MatrixX3d& controlPoints, int degree,
                          const std::vector<double>& knots, bool closed);

/// Least-squares plane of the curve if it is planar within tolerance (relative to its extent);
/// nullopt for a straight or a non-planar curve.
std::optional<Plane> fitCurvePlane(const NetworkCurve& curve, double relativeTolerance = 1e-9);

/// Displacement spline for curve correction (Kuriyama 1996, sec. 5.3.3): a cubic spline on the
/// curve's breakpoints (C^2; periodic for a closed curve) whose coefficients are the minimum-norm
/// ones with D(parameters[k]) = displacements.row(k).
NetworkCurve correctionSpline(const NetworkCurve& curve, const std::vector<double>& parameters,
                              const Eigen::MatrixX3d& displacements);

}  // namespace ffdkit::geometry::curvenet
