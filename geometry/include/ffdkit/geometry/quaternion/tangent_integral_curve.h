#pragma once

#include <functional>

#include <Eigen/Core>

#include "ffdkit/geometry/quaternion/arc_length_curve.h"
#include "ffdkit/geometry/quaternion/cumulative_bezier_quaternion.h"
#include "ffdkit/geometry/quaternion/sphere_bezier_tangent.h"

namespace ffdkit::geometry::quaternion {

/// Composite Gauss-Legendre used for tangent integral curves (64 panels x 8; the report does not
/// say how it integrates).
struct TangentQuadrature {
  int panels = 64;  ///< Gauss-Legendre panels over [0, 1]
  int order = 8;  ///< nodes per panel
};

/// Tangent integral curve C(s) = P0 + int_0^s T(u / L) du, s in [0, L], from a unit-tangent path on
/// S^2 (Sphere-tangent report, sec. 4, eq. (17), with the denominator read as the total length L,
/// as in eq. (16) of sec. 3.3). kappa = |T_t| / L, tau = det(T, T_t, T_tt) / (L |T_t|^2)
/// (Sphere-tangent report, sec. 1).
class TangentIntegralCurve : public ArcLengthCurve {
 public:
  /// @throws QuaternionCurveError if length <= 0.
  TangentIntegralCurve(SphereBezierTangent tangentPath, double length, const Eigen::Vector3d& start = Eigen::Vector3d::Zero(),
                       TangentQuadrature quadrature = {});

  /// The unit-tangent path on the sphere.
  const SphereBezierTangent& tangentPath() const { return path_; }
  /// Start point P0.
  const Eigen::Vector3d& start() const { return start_; }

  double length() const override { return length_; }
  Eigen::Vector3d position(double s) const override;
  Eigen::Vector3d tangent(double s) const override;
  double curvature(double s) const override;
  double torsion(double s) const override;
  Eigen::Vector3d curvatureVector(double s) const override;
  Eigen::MatrixX3d samplePositions(int count) const override;
  /// C(L).
  Eigen::Vector3d endPoint() const { return position(length_); }

 private:
  SphereBezierTangent path_;
  double length_;
  Eigen::Vector3d start_;
  TangentQuadrature quadrature_;
};

/// Miura's unit quaternion integral curve, the baseline of Sphere-tangent report (eq. (16)
/// sec. 3.3): tangent R_{q(t)} v for a cumulative Bezier quaternion q with general controls and a fixed
/// unit v.
class QuaternionIntegralCurve : public ArcLengthCurve {
 public:
  /// @throws QuaternionCurveError if length <= 0 or v = 0.
  QuaternionIntegralCurve(CumulativeBezierQuaternion rotation, const Eigen::Vector3d& v, double length,
                          const Eigen::Vector3d& start = Eigen::Vector3d::Zero(), TangentQuadrature quadrature = {});

  double length() const override { return length_; }
  Eigen::Vector3d position(double s) const override;
  Eigen::Vector3d tangent(double s) const override;
  double curvature(double s) const override;
  double torsion(double s) const override;
  Eigen::Vector3d curvatureVector(double s) const override;

 private:
  Eigen::Vector3d tangentAt(double t) const;
  Eigen::Vector3d tangentDtAt(double t) const;
  CumulativeBezierQuaternion rotation_;
  Eigen::Vector3d v_;
  double length_;
  Eigen::Vector3d start_;
  TangentQuadrature quadrature_;
};

}  // namespace ffdkit::geometry::quaternion
