#pragma once

#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/quaternion/cumulative_bezier_quaternion.h"

namespace ffdkit::geometry::quaternion {

/// How direction controls on S^2 make a tangent path (Sphere-tangent report, secs. 2.2, 4, sec. 4).
enum class SphereCurveKind {
  KimPure,        ///< Kim's cumulative Bezier quaternion on the pure controls (0, V_i), tangent
                  ///< = normalised vector part (normative; the paper's construction)
  ShoemakeSlerp,  ///< de Casteljau with great-circle slerp on S^2 (stays exactly on S^2)
};

/// A unit-tangent path T(t), t in [0, 1], on the unit sphere given by Bezier direction controls
/// V_0..V_n (n >= 1). T(0) = V_0 and T(1) = V_n. @see Sphere-tangent report, secs. 4, 5,
/// eqs. (13)-(15).
class SphereBezierTangent {
 public:
  /// directions: n + 1 >= 2 non-zero vectors (normalised here).
  /// @throws QuaternionCurveError for fewer than 2 controls, a zero control, or consecutive controls
  ///   closer than 1e-9 rad to antipodal (the arc / log is undefined; Sphere-tangent report,
  //sec. 4).
  explicit SphereBezierTangent(std::vector<Eigen::Vector3d> directions, SphereCurveKind kind = SphereCurveKind::KimPure);

  /// Degree n (one less than the number of directions).
  int degree() const { return static_cast<int>(directions_.size()) - 1; }
  /// How the curve on the sphere is built.
  SphereCurveKind kind() const { return kind_; }
  /// The control directions V_0..V_n (unit).
  const std::vector<Eigen::Vector3d>& directions() const { return directions_; }

  /// Unit tangent T(t).
  Eigen::Vector3d tangent(double t) const;
  /// dT/dt: analytic for KimPure (from q'), 5-point differences for ShoemakeSlerp.
  Eigen::Vector3d tangentDt(double t) const;
  /// d^2T/dt^2 by a 5-point difference of tangentDt (h = 1e-4, one-sided near the ends).
  Eigen::Vector3d tangentDtt(double t) const;
  /// |w(t)| of Kim's quaternion (0 on a great circle; 0 for ShoemakeSlerp). Diagnostic for A1.
  double realPart(double t) const;
  /// The underlying Kim quaternion curve (KimPure only).
  const CumulativeBezierQuaternion& quaternionCurve() const { return kim_; }

 private:
  std::vector<Eigen::Vector3d> directions_;
  SphereCurveKind kind_;
  CumulativeBezierQuaternion kim_;
};

}  // namespace ffdkit::geometry::quaternion
