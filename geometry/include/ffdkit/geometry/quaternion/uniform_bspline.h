#pragma once

#include <Eigen/Core>

#include "ffdkit/geometry/quaternion/arc_length_curve.h"

namespace ffdkit::geometry::quaternion {

/// Floating uniform cubic B-spline with knots at the integers, domain x in [0, spans], spans + 3
/// control points; span m uses controls m..m+3 with the uniform blending functions of Sakiyama
/// et al. 2001 eq. (13). The baseline of the paper's comparisons (sec. 3.7) and the target of the QI
/// -> B-spline conversion (Sakiyama et al. 2001, sec. 3.6).
class UniformCubicBSpline {
 public:
  /// control: (spans + 3) x 3. @throws QuaternionCurveError if fewer than 4 control points.
  explicit UniformCubicBSpline(Eigen::MatrixX3d control);

  /// Number of spans (control points - 3).
  int spans() const { return static_cast<int>(control_.rows()) - 3; }
  /// The control points, (spans + 3) x 3.
  const Eigen::MatrixX3d& control() const { return control_; }
  /// Position (order 0) or x-derivative of order 1..3 at x (clamped to the domain).
  Eigen::Vector3d derivative(double x, int order) const;
  /// Position at x (clamped to the domain).
  Eigen::Vector3d point(double x) const { return derivative(x, 0); }
  /// Unsigned curvature |C' x C''| / |C'|^3.
  double curvature(double x) const;
  /// Signed curvature (C' x C'').z / |C'|^3 for curves in a plane z = const.
  double signedPlanarCurvature(double x) const;
  /// Arc length, Gauss-Legendre 8 points on 4 panels per span.
  double length() const;

 private:
  Eigen::MatrixX3d control_;
};

/// Least-squares uniform cubic B-spline with `spans` spans through points P_i at parameters u_i in
/// [0, spans] (QR). points: #P x 3, u: #P. @see Sakiyama et al. 2001, sec. 3.7 (baseline: same
/// spans and u_i).
/// @throws QuaternionCurveError if sizes differ, spans < 1 or the system is rank deficient.
UniformCubicBSpline fitLeastSquaresCubicBSpline(const Eigen::MatrixX3d& points, const Eigen::VectorXd& u, int spans);

/// Converts any arc-length curve to a uniform cubic B-spline: `samples` arc-uniform samples at
/// x_i = s_i / L * spans, least squares. @see Sakiyama et al. 2001, sec. 3.6, eqs. (25)-(26).
UniformCubicBSpline convertToCubicBSpline(const ArcLengthCurve& curve, int spans, int samples);

}  // namespace ffdkit::geometry::quaternion
