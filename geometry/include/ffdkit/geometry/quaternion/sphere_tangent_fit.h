#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/quaternion/tangent_integral_curve.h"

namespace ffdkit::geometry::quaternion {

/// End conditions of one tangent-integral segment (Sphere-tangent report, sec. 5), world frame.
struct SphereTangentSegmentSpec {
  Eigen::Vector3d startPoint = Eigen::Vector3d::Zero();      ///< P_a
  Eigen::Vector3d startTangent = Eigen::Vector3d::UnitX();   ///< V_a, any non-zero length
  Eigen::Vector3d endPoint = Eigen::Vector3d(1.0, 1.0, 0.0); ///< P_c != P_a
  Eigen::Vector3d endTangent = Eigen::Vector3d::UnitY();     ///< V_c, any non-zero length
  int degree = 2;                                            ///< 2 (paper default) or 3 (Fig. 17)
  std::optional<Eigen::Vector3d> fixedSecondControl;         ///< cubic: V_2 in the world frame
                                                             ///< (default slerp(V_a, V_c; 2/3))
  SphereCurveKind kind = SphereCurveKind::KimPure;  ///< how the curve on the sphere is built
};

/// Downhill simplex settings (Sphere-tangent report, sec. 5; ours: absolute tolerances, NOT NR's
/// relative one).
struct NelderMeadOptions {
  double initialStep = 0.2;         ///< simplex edge in (theta, phi), radians
  double functionTolerance = 1e-24; ///< on f_max - f_min
  double simplexTolerance = 1e-12;  ///< on the simplex diameter
  double successThreshold = 1e-20;  ///< f <= this counts as solved (angle error ~1.4e-10 rad)
  int maxIterations = 5000;  ///< simplex iterations at most
  int stallIterations = 300;        ///< stop when the best f has not decreased for this many iterations
  std::optional<Eigen::Vector2d> initialThetaPhi;  ///< default: the great-arc midpoint of V_a, V_c
  int multiStarts = 1;              ///< 1..7 starts (the guess, arc points at 1/4 and 3/4, +-0.5 rad
                                    ///< offsets); stops at the first success, else keeps the lowest f
  TangentQuadrature quadrature;     ///< fixed rule so f stays smooth for the simplex
};

/// The fitted tangent path and how the simplex search went.
struct SphereTangentFitResult {
  bool converged = false;      ///< f <= successThreshold
  double objective = 2.0;      ///< f = 1/2 |P_e/|P_e| - V_s|^2 at the best vertex
  int iterations = 0;  ///< simplex iterations taken
  int evaluations = 0;  ///< objective evaluations
  Eigen::Vector2d thetaPhi = Eigen::Vector2d::Zero();  ///< chart coordinates of V_1 (canonical frame, eq. (18))
  std::vector<Eigen::Vector3d> controlsWorld;          ///< V_0..V_n, world frame
  double length = 0.0;                                 ///< L* = |P_c| / |P_e| (canonical frame)
  double endPositionError = 0.0;                       ///< |C(L*) - P_c|
  double endTangentAngle = 0.0;                        ///< angle(T(1), V_c), radians
  std::optional<TangentIntegralCurve> curve;           ///< only when converged
  std::string message;                                 ///< why it failed, empty on success
};

/// The chart p(theta, phi) = (cos theta cos phi, sin theta, cos theta sin phi), p(0, 0) = e_x
/// (Sphere-tangent report, sec. 5, eq. (18), its Greek letters, lost in print, rebuilt from the
/// text).
Eigen::Vector3d polarPoint(double theta, double phi);

/// Finds the free middle control V_1 (chart angles) so that the segment from P_a with tangent V_a
/// ends at P_c with tangent V_c: canonical frame (P_a = 0, V_a = e_x), f(theta, phi) =
/// 1/2 |P_e/|P_e| - P_c/|P_c||^2 minimised by Nelder-Mead, then uniform scaling to L* = |P_c|/|P_e|.
/// @return converged = false with a message (and no curve) when no solution was found, e.g. when
///   the simplex is pulled to antipodal controls; never a silently wrong curve.
/// @throws QuaternionCurveError on invalid input: P_c = P_a, zero tangents, degree not 2 or 3.
/// @see Sphere-tangent report, sec. 5.
SphereTangentFitResult fitSphereTangentSegment(const SphereTangentSegmentSpec& spec, const NelderMeadOptions& options = {});

}  // namespace ffdkit::geometry::quaternion
