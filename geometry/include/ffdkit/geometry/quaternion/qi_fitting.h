#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/quaternion/qi_chain.h"
#include "ffdkit/geometry/quaternion/uniform_bspline.h"

namespace ffdkit::geometry::quaternion {

/// Which initial curve seeds the QI fit (Sakiyama et al. 2001, sec. 3.4).
enum class FitInitialCurve {
  LeastSquaresCubic,   ///< LSQ uniform cubic at the same breaks and u_i (default; our choice)
  InterpolatingCubic,  ///< the paper's interpolating uniform cubic with Q_0 = Q_1 (eqs. (11)-(16));
                       ///< with StartTangentMode::FromInitialCurve this is the "paper" preset
};

/// How the chain's start tangent (q_00) is chosen (Sakiyama et al. 2001, sec. 3.4; the paper leaves
/// it open).
enum class StartTangentMode {
  FromInitialCurve,  ///< fixed to the initial curve's tangent at u = 0 (the paper's implicit choice)
  Given,             ///< fixed to FitOptions::givenStartTangent
  Free,              ///< optimised (+2 variables, planar +1), starting from the initial curve
};

/// Planar or spatial parameterisation (Sakiyama et al. 2001, sec. 3.1).
enum class FitDimension {
  Auto,     ///< Planar when all points share one z, Spatial otherwise
  Planar,   ///< w_ij = phi_ij e_z: planar result, exactly linear curvature per segment for k = 2
  Spatial,  ///< full 3-vectors w_ij
};

/// How the LM Jacobian is computed.
enum class FitJacobian {
  Analytic,           ///< exact derivatives through the frame rotations, one sweep (default)
  ForwardDifference,  ///< sqrt(eps) forward differences, recomputing segments >= the perturbed one
};

/// Options of fitQiChain.
struct FitOptions {
  int degree = 2;                                        ///< k, degree of each segment's quaternion curve
  FitDimension dimension = FitDimension::Auto;  ///< planar or spatial fit; Auto: planar when the points are
  ProductForm form = ProductForm::Global;                ///< form A (Sakiyama et al. 2001, sec. 2.2)
  StartTangentMode startTangent = StartTangentMode::FromInitialCurve;  ///< how the start tangent is chosen
  Eigen::Vector3d givenStartTangent = Eigen::Vector3d::UnitX();  ///< Given mode only
  FitInitialCurve initialCurve = FitInitialCurve::LeastSquaresCubic;  ///< where Levenberg-Marquardt starts
  /// GL-5 per panel; the data parameters are the breakpoints, and gaps wider than 1/8 of a segment are
  /// split evenly (so >= 8 panels per segment, none wider than a uniform grid of GL-8 panels). The
  /// paper is silent on quadrature; GL-8 is our choice; its own accuracy table gives 1e-13 of l for
  /// GL-5 on 8 panels of a strongly twisted segment, and the fit's panels are narrower: the
  /// objective agrees with GL-24 on 64 panels to 1e-14 and the fitted curves with GL-8 fits to 3e-9
  /// of the length (test), at 0.7 x the instructions.
  QiQuadrature quadrature{5, 8};
  FitJacobian jacobian = FitJacobian::Analytic;  ///< analytic or forward-difference Jacobian
  double functionTolerance = 1e-12;                      ///< relative reduction of R
  double stepTolerance = 1e-12;                          ///< relative step size
  double gradientTolerance = 1e-12;                      ///< |J^T r|_inf relative to R
  int maxIterations = 500;                               ///< LM iterations
  int maxFunctionEvaluations = 50000;  ///< cap on residual evaluations
  /// Near the minimum, add a structured secant estimate S of the second-order term sum r_i Hess r_i
  /// to J^T J, as NL2SOL does (Dennis, Gay & Welsch 1981): the fit's residuals are large, so
  /// Gauss-Newton alone ends linearly. S learns from accepted steps that lower R by less than 1e-7 of
  /// R, and a step uses it when it predicted the last change of R better than J^T J alone. The
  /// spiral's fit takes 81 trial steps instead of 106 and ends at the minimum of R (1.6e-12 lower).
  /// false: plain Levenberg-Marquardt.
  bool secantTail = true;
  /// Sweep the segments on the OpenMP threads (fits of >= 512 quadrature nodes). The result is the
  /// same bits with any thread count or with false: segments are computed alone and chained in order.
  bool parallel = true;
};

/// The fitted chain and the fit's record.
struct FitResult {
  /// A result holding the fitted chain and the baseline B-spline.
  FitResult(QiChain c, UniformCubicBSpline b) : curve(std::move(c)), baseline(std::move(b)) {}
  QiChain curve;                       ///< the fitted G1 chain, world units
  Eigen::VectorXd parameters;          ///< u_i used, in [0, M]
  Eigen::VectorXd pointErrors;         ///< e_i = |C(u_i) - P_i|
  double rms = 0.0;  ///< root mean square of the point errors
  double maxError = 0.0;  ///< largest point error
  double rmsPercent = 0.0;             ///< 100 rms / L (Sakiyama et al. 2001, Table 1)
  double maxPercent = 0.0;  ///< 100 maxError / L
  double initialRms = 0.0;             ///< rms of the initial guess
  bool converged = false;              ///< an LM stopping test was met (not the evaluation cap)
  int iterations = 0;  ///< LM iterations taken
  int functionEvaluations = 0;         ///< residual evaluations (forward-difference columns included)
  std::vector<double> objectiveHistory;  ///< accepted R = sum e_i^2, non-increasing
  UniformCubicBSpline baseline;        ///< LSQ cubic B-spline, same spans and u_i (Sakiyama et al. 2001's comparison)
  std::string message;                 ///< which stopping test fired, or why it failed
};

/// Chord-length parameters within segments: u_{b_j} = j, linear in cumulative chord between
/// breaks. @see Sakiyama et al. 2001, eqs. (9)-(10), (sec. 3.3), with the misprinted indices
/// corrected.
/// @throws QuaternionCurveError if breaks are not 0 = b_0 < ... < b_M = #P - 1.
Eigen::VectorXd chordLengthParameters(const Eigen::MatrixX3d& points, const std::vector<int>& breaks);

/// Fits a G1 chain of M = breaks.size() - 1 Bezier-type QI segments to the points by
/// Levenberg-Marquardt on R = sum |C(u_i) - P_i|^2 with fixed u_i (chord length or `userParameters`).
/// The start point is fixed to P_0; lengths are l = exp(lambda) so they stay positive.
/// points: #P x 3; breaks: data indices 0 = b_0 < b_1 < ... < b_M = #P - 1 (a break point belongs to
/// both segments; at least 2 points per segment). userParameters: optional #P sorted values with
/// u_{b_j} = j.
/// @return the chain and the fit record; an LM run stopped by the evaluation cap has converged = false.
/// @throws QuaternionCurveError on invalid input (breaks, sizes, degree < 1, Planar with non-planar data).
/// @see Sakiyama et al. 2001, secs. 2.2, 3.5.1, eqs. (4)-(19).
FitResult fitQiChain(const Eigen::MatrixX3d& points, const std::vector<int>& breaks, const FitOptions& options = {},
                     const Eigen::VectorXd* userParameters = nullptr);

/// Curvature fairness of a sampled curvature profile made of pieces of `samplesPerPiece` samples
/// each (segments or spans, both ends included): total variation sum |d kappa| over all consecutive
/// samples, the same within pieces only, and the number of interior local extrema within pieces.
struct CurvatureFairness {
  double totalVariation = 0.0;  ///< sum of |d kappa| over all consecutive samples
  double intraVariation = 0.0;  ///< the same within pieces only
  int interiorExtrema = 0;  ///< interior local extrema within pieces
};
CurvatureFairness curvatureFairness(const Eigen::VectorXd& kappa, int samplesPerPiece);

/// Curvature of a fitted chain sampled per segment (samplesPerSegment each, ends included), signed
/// for planar data (z constant) and unsigned otherwise; and the same per span for a B-spline.
Eigen::VectorXd sampledChainCurvature(const QiChain& chain, int samplesPerSegment, bool signedPlanar);
Eigen::VectorXd sampledBSplineCurvature(const UniformCubicBSpline& spline, int samplesPerSpan, bool signedPlanar);

}  // namespace ffdkit::geometry::quaternion
