#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/g3/condition.h"
#include "ffdkit/geometry/g3/quadratic_curvature_spline.h"

namespace ffdkit::geometry::g3 {

/// What to do when fewer than 3 condition rows leave a one-parameter family of solutions.
enum class UnderdeterminedPolicy {
  MinimumNormFromInitialGuess,  ///< the paper's pseudo-inverse Newton (sec. 4): nearest member
  Reject,                       ///< throw G3InputError
};

/// When to use continuation on the condition targets (not in the paper, which runs a fixed 4
/// steps).
enum class ContinuationMode {
  Off,        ///< plain damped Newton only
  OnFailure,  ///< plain damped Newton first; continuation if it fails
  Always,     ///< continuation from the start
};

/// How a Newton step is safeguarded far from the solution (our addition to the iteration of Kuroda
/// et al. 1997, sec. 4).
enum class Globalization {
  None,                ///< full steps (paper mode always uses full steps)
  LineSearch,          ///< Armijo backtracking on the scaled residual 2-norm, step halving
  LevenbergMarquardt,  ///< J^T (J J^T + mu I)^{-1} f, adaptive mu; -> min-norm step as mu -> 0
};

/// Options of the G3 curve solver (Kuroda et al. 1997).
struct G3SolverOptions {
  int maxIterations = 30;          ///< Newton iterations per solve (per continuation stage)
  double tolerance = 1e-12;        ///< max scaled residual: interpolation rows and lengths / h,
                                   ///< curvatures * h, angles in rad
  Globalization globalization = Globalization::LineSearch;  ///< how Newton steps are kept from diverging
  double lineSearchFloor = 1e-6;   ///< smallest step fraction before reporting failure
  bool paperMode = false;          ///< exactly 4 undamped pseudo-inverse steps (app. 1)
  ContinuationMode continuation = ContinuationMode::OnFailure;  ///< when to solve by continuation from an easier problem
  double minContinuationStep = 1e-4;  ///< below this lambda step: "likely infeasible"
  int quadratureNodes = 16;        ///< Gauss-Legendre nodes per panel (the paper integrates with Mathematica, app. 1)
  double maxTurnPerPanel = 1.0;    ///< rad of turning per quadrature panel
  UnderdeterminedPolicy underdetermined = UnderdeterminedPolicy::MinimumNormFromInitialGuess;  ///< how a system with fewer than 3 condition rows is solved
  bool allowOverdetermined = false;  ///< > 3 condition rows: least squares if true, else throw
  double singularThreshold = 1e-13;  ///< reciprocal condition estimate below this: singular (failure)
  /// Tangent evaluations (quadrature nodes: a sin/cos pair each) per span for the whole solve,
  /// continuation included. Each span's panels follow its turning (maxTurnPerPanel, at most
  /// 4096 of 16 nodes), so points far apart with steep curvature targets cost seconds per
  /// solve: fuzz_generator found 4-point curves taking 5 s. A curve that turns a few radians
  /// per span needs at most ~60,000 per span (30 continuation stages of 15 evaluations at 8
  /// panels); past the budget the solve stops with WorkLimit, so a solve costs at most ~4 ms
  /// per span.
  double maxTangentEvaluationsPerSpan = 1e5;
};

enum class G3SolveStatus {
  Converged,
  MaxIterations,         ///< tolerance not reached within maxIterations (or the 4 paper steps)
  Stalled,               ///< residual did not drop by 0.9 over 5 iterations (infeasible?)
  LineSearchFailed,      ///< no acceptable step (line search floor / LM damping exhausted)
  SingularJacobian,      ///< rank-deficient Jacobian at the last iterate
  NonFinite,             ///< a NaN or infinity appeared
  NonPositiveSpanLength, ///< an undamped step made some Delta s_i <= 0 (paper mode)
  LikelyInfeasible,      ///< continuation step fell below minContinuationStep
  WorkLimit,             ///< more than maxTangentEvaluationsPerSpan x spans were needed
};

/// Text for a status ("converged", "stalled", ...).
const char* toString(G3SolveStatus status);

/// How a G3 solve went.
struct G3SolveResult {
  G3SolveStatus status = G3SolveStatus::MaxIterations;  ///< how the solve ended
  bool converged = false;  ///< status == Converged
  int iterations = 0;             ///< Newton iterations, summed over continuation stages
  int continuationStages = 0;     ///< 0 when no continuation was used
  double residualNorm = 0.0;      ///< ||f||_2, unscaled, at the last iterate
  double scaledResidualInf = 0.0; ///< max scaled residual at the last iterate (vs tolerance)
  std::vector<double> residualHistory;  ///< ||f||_2 unscaled, from the initial guess on
  double jacobianConditionNumber = 0.0; ///< 1-norm condition estimate of the row-scaled Jacobian
                                        ///< at the last iterate (via J J^T when not square)
  int conditionRows = 0;          ///< rows the conditions added (3 makes the system square)
  bool underdetermined = false;   ///< fewer than 3 rows: the answer depends on the guess (sec. 3.8)
  std::string message;            ///< what happened, in words
  std::vector<std::string> warnings;  ///< e.g. underdetermined (guess-dependent) or least-squares fits
  Eigen::VectorXd unknowns;       ///< last iterate v (2n+3), also on failure (diagnostics only)
  std::optional<QuadraticCurvatureSpline> curve;  ///< set only when converged
};

/// Solves for the G3 curve with piecewise quadratic curvature through points p_0..p_n:
/// 2n interpolation equations (eq. (3), sec. 3) plus the condition rows, by Newton /
/// Gauss-Newton with the analytic Jacobian (sec. 4, Kuroda et al. 1997), minimum-norm steps
/// when underdetermined (sec. 4), Armijo line search and optional continuation (our additions).
///   points        (n+1) x 2, n >= 1, consecutive points distinct
///   conditions    see Condition; tangent targets are moved to the 2 pi branch nearest the guess
///   initialGuess  optional 2n+3 vector v^(0); default initialGuessFromCubicSpline
/// Never returns a curve from a failed solve: check `converged` / `status`.
/// @throws G3InputError for invalid points, out-of-range condition indices, a guess of the
///   wrong size or with Delta s <= 0, too many rows without allowOverdetermined, or fewer
///   than 3 rows under UnderdeterminedPolicy::Reject.
/// @see Kuroda et al. 1997, secs. 3, 4, eq. (3)-(5).
G3SolveResult solveG3Curve(const Eigen::Ref<const Eigen::MatrixX2d>& points,
                           const std::vector<Condition>& conditions,
                           const G3SolverOptions& options = {},
                           const std::optional<Eigen::VectorXd>& initialGuess = std::nullopt);

/// The residual f(v) of eq. (3) plus the condition rows and its analytic Jacobian, exactly as
/// the solver builds them (unscaled; tangent targets are taken literally, without branch
/// alignment). For diagnostics and for checking the Jacobian against finite differences.
struct G3SystemEvaluation {
  Eigen::VectorXd residual;  ///< 2n + condition rows: (f_0..f_{2n-1}, g_0, ...)
  Eigen::MatrixXd jacobian;  ///< rows x (2n+3), columns (Delta s_0..Delta s_{n-1}, d_{-1}..d_{n+1})
  Eigen::VectorXd rowScales; ///< divide residual rows by these to get the dimensionless residual
};

/// @throws G3InputError as solveG3Curve, or when v has not 2n+3 entries with Delta s_i > 0.
G3SystemEvaluation evaluateG3System(const Eigen::Ref<const Eigen::MatrixX2d>& points,
                                    const std::vector<Condition>& conditions,
                                    const Eigen::Ref<const Eigen::VectorXd>& unknowns,
                                    const G3SolverOptions& options = {});

}  // namespace ffdkit::geometry::g3
