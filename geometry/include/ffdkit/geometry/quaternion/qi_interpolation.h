#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/quaternion/bezier_qi_segment.h"
#include "ffdkit/geometry/quaternion/qi_spline.h"

namespace ffdkit::geometry::quaternion {

/// End-tangent rules of Miura 1998 (secs. 5.2, 5.3).
enum class EndTangentRule {
  NaturalSpline,  ///< end directions of the natural cubic spline through the points (Ex. 1)
  Circle3,        ///< tangents of the circles through the first / last three points (Ex. 2, 3)
  User,           ///< InterpolationOptions::startTangent / endTangent
};

/// Stopping rule (Miura 1998, sec. 5.2).
enum class StopMode {
  Strict,  ///< |f|_inf < strictTolerance on data normalised to mean chord 1 (default)
  Paper,   ///< |f|^2 < paperEpsilon = 5e-4 on normalised data, as in Miura 1998, sec. 5.2
};

/// Options of interpolateQi.
struct InterpolationOptions {
  EndTangentRule endRule = EndTangentRule::Circle3;       ///< Circle3 also works for collinear points
  Eigen::Vector3d startTangent = Eigen::Vector3d::Zero();  ///< User rule only: non-zero, any length
  Eigen::Vector3d endTangent = Eigen::Vector3d::Zero();    ///< User rule only: non-zero, any length
  int simpsonIntervals = 100;         ///< even; the paper's "100 equal parts" (sec. 5.1)
  StopMode stopMode = StopMode::Strict;  ///< Strict (tolerance on |f|) or Paper (the paper's epsilon)
  double paperEpsilon = 5e-4;         ///< on |f|^2, Paper mode
  double strictTolerance = 1e-12;     ///< on |f|_inf, Strict mode (normalised units)
  int maxIterations = 50;  ///< Newton steps at most
  bool pureNewton = false;            ///< true: undamped Newton as in the paper; false: step halving
  AngleEquivalence equivalence = AngleEquivalence::Full;  ///< which control angles count as equivalent
};

/// The interpolating curve and how the solve went.
struct InterpolationResult {
  /// A result holding curve `c`.
  explicit InterpolationResult(QiSpline c) : curve(std::move(c)) {}
  QiSpline curve;                        ///< anchored at the data points, in world units
  bool converged = false;  ///< the stopping test was met
  int iterations = 0;                    ///< Newton steps taken
  double residual = 0.0;                 ///< final |f|^2 (normalised units, as the paper reports)
  std::vector<double> residualHistory;   ///< |f|^2 before the first step and after each step
  Eigen::Vector3d startTangent = Eigen::Vector3d::UnitX();  ///< the unit end tangents that were imposed
  Eigen::Vector3d endTangent = Eigen::Vector3d::UnitX();  ///< see startTangent
  double meanChord = 1.0;                ///< the normalisation scale c
  std::string message;                   ///< why it failed, empty on success
};

/// G2 interpolation of n+1 points by n quadratic Bezier QI segments with Newton-Raphson on the
/// 5n-2 unknowns (alpha_{0,1}, beta_{0,1}, (alpha_{i,0}, beta_{i,0}, alpha_{i,1}, beta_{i,1})_{i>=1},
/// l_0..l_{n-1}). Points are normalised (P_0 -> origin, mean chord -> 1) for the solve and mapped
/// back. The initial guess comes from a uniform-knot cubic spline (Miura 1998, sec. 5.2).
/// points: #P x 3, #P >= 2 (>= 3 for Circle3).
/// @return the curve and convergence record; a failed solve has converged = false and the last
///   iterate (never NaN) and a message.
/// @throws QuaternionCurveError on invalid input: too few points, coincident consecutive points,
///   a zero user tangent, odd Simpson count.
/// @see Miura 1998, secs. 4, 5.2, eqs. (40)-(62).
InterpolationResult interpolateQi(const Eigen::MatrixX3d& points, const InterpolationOptions& options = {});

/// The Newton system of interpolateQi (Miura 1998, eqs. (60)-(62)) at an arbitrary unknown vector,
/// for tests and diagnostics. points: #P x 3 (n = #P - 1 segments); unknowns: 5n - 2 values in the
/// order [a01, b01, (ai0, bi0, ai1, bi1)_{i=1..n-1}, l_0..l_{n-1}]; start / end: the fixed end
/// angles.
/// @return f (3n position rows, then G_i, H_i interleaved) and its analytic Jacobian (5n-2 square).
/// @throws QuaternionCurveError if the sizes do not match or simpsonIntervals is not positive and even.
struct QiInterpolationSystem {
  Eigen::VectorXd residual;  ///< f
  Eigen::MatrixXd jacobian;  ///< df/d(unknowns), square
};
QiInterpolationSystem qiInterpolationSystem(const Eigen::MatrixX3d& points, const Eigen::VectorXd& unknowns,
                                            QiAngles start, QiAngles end, int simpsonIntervals = 100);

/// Unit tangent at P_0 of the circle through a, b, c (the line direction when collinear):
/// proportional to |c-a|^2 (b-a) - |b-a|^2 (c-a). @see Miura 1998, sec. 5.2.
Eigen::Vector3d circleTangentAtFirst(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// First derivatives D_i (#P x 3) of the uniform-knot (u = i) cubic spline through the points:
/// natural (zero second derivative at both ends) or clamped with end derivatives d0, dn.
Eigen::MatrixX3d cubicSplineDerivatives(const Eigen::MatrixX3d& points, bool natural,
                                        const Eigen::Vector3d& d0 = Eigen::Vector3d::Zero(),
                                        const Eigen::Vector3d& dn = Eigen::Vector3d::Zero());

}  // namespace ffdkit::geometry::quaternion
