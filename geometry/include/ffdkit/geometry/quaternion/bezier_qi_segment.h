#pragma once

#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ffdkit::geometry::quaternion {

/// Polar coordinates (alpha = angle, beta = radius) of a control quaternion in the jk-plane.
struct QiAngles {
  double alpha = 0.0;  ///< angle in the jk-plane
  double beta = 0.0;  ///< radius in the jk-plane
};

/// Closed-form unit tangent T(alpha, beta) = (cos 2b, sin a sin 2b, -cos a sin 2b), equal to
/// q e_x q^-1 for q = (cos b, 0, cos a sin b, sin a sin b). @see Miura 1998, sec. 3.3, eq. (36).
Eigen::Vector3d qiTangentFromAngles(double alpha, double beta);

/// q(alpha, beta) = (cos b, 0, cos a sin b, sin a sin b) = exp(b (0, 0, cos a, sin a)).
/// @see Miura 1998, sec. 3.3, eqs. (31)-(36).
Eigen::Quaterniond qiQuaternionFromAngles(double alpha, double beta);

/// Principal (alpha, beta) of a unit tangent: beta = acos(T_x)/2 in [0, pi/2],
/// alpha = atan2(T_y, -T_z) (alpha = 0 at T = +-e_x, where it is arbitrary).
QiAngles qiAnglesFromTangent(const Eigen::Vector3d& unitTangent);

/// Which equivalent (alpha, beta) pairs the initial guess searches (Miura 1998, sec. 5.2).
enum class AngleEquivalence {
  Full,       ///< (alpha + k pi, (-1)^k beta + m pi): every pair with the same tangent (default)
  PaperOnly,  ///< (alpha + (2k+1) pi, -beta) and the trivial alpha + 2k pi, as printed in the paper
};

/// Among the pairs equivalent to `raw`, the one nearest to `previous` in
/// (d alpha)^2 + (d beta)^2. At the singular tangent +-e_x (|sin 2 beta| < 1e-9) alpha takes the
/// predecessor's value. @see Miura 1998, sec. 5.2.
QiAngles nearestEquivalentAngles(QiAngles raw, QiAngles previous, AngleEquivalence equivalence = AngleEquivalence::Full);

/// One quadratic Bezier QI segment of Miura 1998: arc length l, start point P, and quadratic
/// alpha(t), beta(t) in Bernstein form, t = s / l in [0, 1]; the tangent is T(alpha(t), beta(t)).
/// Positions are integrated with composite Simpson (the paper's rule) with `simpsonIntervals`.
/// @see Miura 1998, sec. 3.3, eqs. (30)-(39) and app. A.1, app. A.2.
class BezierQiSegment {
 public:
  /// @throws QuaternionCurveError if length <= 0 or simpsonIntervals is not positive and even.
  BezierQiSegment(const Eigen::Vector3d& start, double length, const std::array<double, 3>& alpha,
                  const std::array<double, 3>& beta, int simpsonIntervals = 100);

  /// Start point of the segment.
  const Eigen::Vector3d& start() const { return start_; }
  /// Arc length of the segment.
  double length() const { return length_; }
  /// The three alpha control values.
  const std::array<double, 3>& alphaControls() const { return alpha_; }
  /// The three beta control values.
  const std::array<double, 3>& betaControls() const { return beta_; }
  /// Simpson intervals of the position integral.
  int simpsonIntervals() const { return simpsonIntervals_; }

  /// alpha(t), beta(t) and their t-derivatives (first, second).
  QiAngles angles(double t) const;
  /// First t-derivatives of alpha and beta.
  QiAngles anglesDot(double t) const;
  /// Second t-derivatives of alpha and beta.
  QiAngles anglesDDot(double t) const;

  /// The unit quaternion q(t) of the segment.
  Eigen::Quaterniond quaternion(double t) const;
  /// Angular velocity omega(t) (t-rate, pure quaternion as a 3-vector) with q' = q omega, the
  /// corrected i-component -sin^2(beta) alpha' (the paper's eq. (68) in app. A.1 is misprinted).
  Eigen::Vector3d omega(double t) const;
  /// Unit tangent at t (closed form).
  Eigen::Vector3d tangent(double t) const;
  /// Position C(t) = P + l int_0^t T dt (Simpson on [0, t]).
  Eigen::Vector3d point(double t) const;
  /// int_0^1 T(t) dt with the segment's Simpson rule (Miura 1998, eq. (60) without l).
  Eigen::Vector3d chordIntegral() const;
  /// Curvature vector d^2C/ds^2 = (2/l) q [omega, e_x] q^-1. @see Miura 1998, sec. 4, eq. (49).
  Eigen::Vector3d curvatureVector(double t) const;
  /// kappa = sqrt(a'^2 sin^2 2b + 4 b'^2) / l: Miura 1998, sec. 3.3, eq. (39) with the missing 1/l.
  double curvature(double t) const;
  /// d kappa / ds (derived; Miura 1998, sec. 3.3). 0 where kappa = 0.
  double curvatureDerivative(double t) const;
  /// Torsion (derived; Miura 1998, sec. 3.3). 0 where kappa = 0, where it is undefined.
  double torsion(double t) const;

 private:
  Eigen::Vector3d start_;
  double length_;
  std::array<double, 3> alpha_;
  std::array<double, 3> beta_;
  int simpsonIntervals_;
};

}  // namespace ffdkit::geometry::quaternion
