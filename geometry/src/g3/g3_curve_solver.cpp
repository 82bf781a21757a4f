#include "ffdkit/geometry/g3/g3_curve_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>

#include "ffdkit/geometry/g3/bohm_conversion.h"
#include "ffdkit/geometry/g3/cubic_spline_initial_guess.h"
#include "ffdkit/geometry/g3/g3_error.h"
#include "points_validation.h"
#include "span_quadrature.h"

namespace ffdkit::geometry::g3 {

const char* toString(G3SolveStatus status) {
  switch (status) {
    case G3SolveStatus::Converged: return "converged";
    case G3SolveStatus::MaxIterations: return "maximum iterations reached";
    case G3SolveStatus::Stalled: return "stalled (residual stopped decreasing)";
    case G3SolveStatus::LineSearchFailed: return "line search failed";
    case G3SolveStatus::SingularJacobian: return "singular Jacobian";
    case G3SolveStatus::NonFinite: return "non-finite value";
    case G3SolveStatus::NonPositiveSpanLength: return "non-positive span length";
    case G3SolveStatus::LikelyInfeasible: return "likely infeasible (continuation failed)";
    case G3SolveStatus::WorkLimit: return "work limit reached (the curve turns too much between its points)";
  }
  return "unknown";
}

namespace {

// The interpolation system of eq. (3) plus the condition rows, with row scales that make
// every residual dimensionless.
class System {
 public:
  System(const Eigen::Ref<const Eigen::MatrixX2d>& points, std::vector<Condition> conditions,
         const G3SolverOptions& options)
      : n_(static_cast<int>(points.rows()) - 1),
        conditions_(std::move(conditions)),
        rule_(gaussLegendreRule(options.quadratureNodes)),
        maxTurn_(options.maxTurnPerPanel),
        nodesPerPanel_(options.quadratureNodes),
        maxTangentEvaluations_(options.maxTangentEvaluationsPerSpan * std::max(n_, 1)) {
    chords_.resize(n_, 2);
    for (int i = 0; i < n_; ++i) chords_.row(i) = points.row(i + 1) - points.row(i);
    h_ = chords_.rowwise().norm().maxCoeff();
    conditionRows_ = 0;
    for (auto& c : conditions_) {
      resolve(c);
      conditionRows_ += c.rowCount();
    }
    scales_.resize(rows());
    scales_.head(2 * n_).setConstant(h_);
    int r = 2 * n_;
    for (const auto& c : conditions_) {
      double scale = 1.0;
      if (c.kind == Condition::Kind::Curvature) scale = 1.0 / h_;
      if (c.kind == Condition::Kind::Length || c.kind == Condition::Kind::RadiusOfCurvature) scale = h_;
      for (int k = 0; k < c.rowCount(); ++k) scales_[r++] = scale;
    }
  }

  int n() const { return n_; }
  /// The tangent evaluations so far exceed the solve's budget.
  bool overBudget() const { return tangentEvaluations_ > maxTangentEvaluations_; }
  int rows() const { return 2 * n_ + conditionRows_; }
  int cols() const { return 2 * n_ + 3; }
  int conditionRows() const { return conditionRows_; }
  double h() const { return h_; }
  const Eigen::VectorXd& scales() const { return scales_; }

  // Tangent targets move to the 2 pi branch nearest the initial guess (Kuroda et al. 1997, sec. 4).
  void alignBranches(const Eigen::VectorXd& v) {
    const Eigen::VectorXd b = bezierOrdinatesFromDeBoor(v.head(n_), v.tail(n_ + 3));
    for (auto& c : conditions_) {
      if (c.kind != Condition::Kind::TangentAngle) continue;
      const double current = b[3 * c.index];
      c.value += 2.0 * std::numbers::pi * std::round((current - c.value) / (2.0 * std::numbers::pi));
    }
  }

  Eigen::VectorXi panels(const Eigen::VectorXd& v) const {
    const Eigen::VectorXd b = bezierOrdinatesFromDeBoor(v.head(n_), v.tail(n_ + 3));
    Eigen::VectorXi p(n_);
    for (int i = 0; i < n_; ++i) p[i] = detail::panelCount(detail::controlPolygonTurning(b.segment<4>(3 * i)), maxTurn_);
    return p;
  }

  // Unscaled residual f(v) (and Jacobian when jac != nullptr) minus `offset` on each row.
  void evaluate(const Eigen::VectorXd& v, const Eigen::VectorXi& panels, const Eigen::VectorXd& offset,
                Eigen::VectorXd& f, Eigen::MatrixXd* jac) const {
    const auto ds = v.head(n_);
    const Eigen::VectorXd b = bezierOrdinatesFromDeBoor(ds, v.tail(n_ + 3));
    Eigen::MatrixXd db;
    if (jac) {
      db = bezierOrdinateJacobian(ds, v.tail(n_ + 3));
      jac->setZero(rows(), cols());
    }
    f.resize(rows());
    tangentEvaluations_ += double(panels.sum()) * nodesPerPanel_;
    for (int i = 0; i < n_; ++i) {
      const Eigen::Vector4d eta = b.segment<4>(3 * i);
      if (jac) {
        const detail::SpanMoments m = detail::cubicSpanMoments(rule_, eta, panels[i]);
        f[2 * i] = ds[i] * m[0] - chords_(i, 0);
        f[2 * i + 1] = ds[i] * m[1] - chords_(i, 1);
        // d f / d v = [v = Delta s_i] I - / + Delta s_i sum_k M_k d eta_k / d v
        auto rx = jac->row(2 * i);
        auto ry = jac->row(2 * i + 1);
        for (int k = 0; k < 4; ++k) {
          rx -= ds[i] * m[3 + 2 * k] * db.row(3 * i + k);
          ry += ds[i] * m[2 + 2 * k] * db.row(3 * i + k);
        }
        rx[i] += m[0];
        ry[i] += m[1];
      } else {
        const Eigen::Vector2d integral = detail::integrateTangent(
            rule_, [&](double t) { return detail::cubicBezier(eta, t); }, 0.0, 1.0, panels[i]);
        f[2 * i] = ds[i] * integral[0] - chords_(i, 0);
        f[2 * i + 1] = ds[i] * integral[1] - chords_(i, 1);
      }
    }
    int r = 2 * n_;
    Eigen::RowVectorXd grad(cols());
    for (const auto& c : conditions_) {
      for (int k = 0; k < c.rowCount(); ++k, ++r) {
        grad.setZero();
        f[r] = conditionRow(c, k, v, b, jac ? &db : nullptr, grad);
        if (jac) jac->row(r) = grad;
      }
    }
    f -= offset;
  }

 private:
  void resolve(Condition& c) const {
    using Kind = Condition::Kind;
    auto fail = [&](const char* what, int got, int hi) {
      std::ostringstream msg;
      msg << "condition " << what << ": index must be in 0.." << hi << " (or kLast) for " << n_ + 1
          << " points, got " << got;
      throw G3InputError(msg.str());
    };
    switch (c.kind) {
      case Kind::TangentAngle:
      case Kind::Curvature:
      case Kind::RadiusOfCurvature:
        if (c.index == kLast) c.index = n_;
        if (c.index < 0 || c.index > n_) fail("at a point", c.index, n_);
        break;
      case Kind::ClothoidSpan:
      case Kind::CircularArcSpan:
        if (c.index == kLast) c.index = n_ - 1;
        if (c.index < 0 || c.index >= n_) fail("on a span", c.index, n_ - 1);
        break;
      case Kind::Length:
        if (c.index == kLast) c.index = n_ - 1;
        if (c.lastIndex == kLast) c.lastIndex = n_ - 1;
        if (c.index < 0 || c.index >= n_) fail("length (first span)", c.index, n_ - 1);
        if (c.lastIndex < c.index || c.lastIndex >= n_) fail("length (last span)", c.lastIndex, n_ - 1);
        if (!(c.value > 0.0)) {
          std::ostringstream msg;
          msg << "length condition needs a positive length, got " << c.value;
          throw G3InputError(msg.str());
        }
        break;
      case Kind::NaturalEnds:
        break;
      case Kind::Custom:
        if (!c.custom) throw G3InputError("custom condition '" + c.name + "' has no function");
        break;
    }
    if (!std::isfinite(c.value)) throw G3InputError("condition target must be finite");
  }

  // Row k of condition c at v, gradient into grad when db is given.
  double conditionRow(const Condition& c, int k, const Eigen::VectorXd& v, const Eigen::VectorXd& b,
                      const Eigen::MatrixXd* db, Eigen::Ref<Eigen::RowVectorXd> grad) const {
    using Kind = Condition::Kind;
    switch (c.kind) {
      case Kind::TangentAngle:
        if (db) grad = db->row(3 * c.index);
        return b[3 * c.index] - c.value;
      case Kind::Curvature:
      case Kind::RadiusOfCurvature: {
        // kappa at p_i from the span on its right (left at the end): 3 (b_hi - b_lo) / Delta s.
        const int span = c.index < n_ ? c.index : n_ - 1;
        const int lo = c.index < n_ ? 3 * c.index : 3 * n_ - 1;
        const double ds = v[span];
        const double jump = b[lo + 1] - b[lo];
        if (c.kind == Kind::Curvature) {
          const double kappa = 3.0 * jump / ds;
          if (db) {
            grad = 3.0 * (db->row(lo + 1) - db->row(lo)) / ds;
            grad[span] -= kappa / ds;
          }
          return kappa - c.value;
        }
        if (db) {
          grad = -3.0 * c.value * (db->row(lo + 1) - db->row(lo));
          grad[span] += 1.0;
        }
        return ds - 3.0 * c.value * jump;
      }
      case Kind::ClothoidSpan:
      case Kind::CircularArcSpan: {
        const int o = 3 * c.index;
        if (k == 0) {  // a_3 = b3 - 3 b2 + 3 b1 - b0
          if (db) grad = db->row(o + 3) - 3.0 * db->row(o + 2) + 3.0 * db->row(o + 1) - db->row(o);
          return b[o + 3] - 3.0 * b[o + 2] + 3.0 * b[o + 1] - b[o];
        }
        // a_2 / 3 = b2 - 2 b1 + b0
        if (db) grad = db->row(o + 2) - 2.0 * db->row(o + 1) + db->row(o);
        return b[o + 2] - 2.0 * b[o + 1] + b[o];
      }
      case Kind::Length: {
        if (db) grad.segment(c.index, c.lastIndex - c.index + 1).setOnes();
        return v.segment(c.index, c.lastIndex - c.index + 1).sum() - c.value;
      }
      case Kind::NaturalEnds: {
        // d_0 - d_{-1} (columns n, n+1) or d_{n+1} - d_n (columns 2n+1, 2n+2)
        const int first = k == 0 ? n_ : 2 * n_ + 1;
        if (db) {
          grad[first] = -1.0;
          grad[first + 1] = 1.0;
        }
        return v[first + 1] - v[first];
      }
      case Kind::Custom: {
        Eigen::RowVectorXd g = Eigen::RowVectorXd::Zero(cols());
        const double value = c.custom(v, g);
        if (db) grad = g;
        return value;
      }
    }
    return 0.0;
  }

  int n_;
  std::vector<Condition> conditions_;
  GaussLegendreRule rule_;
  double maxTurn_;
  int nodesPerPanel_;
  double maxTangentEvaluations_;
  mutable double tangentEvaluations_ = 0.0;  // the work done, summed over every evaluate()
  Eigen::MatrixX2d chords_;
  double h_ = 1.0;
  int conditionRows_ = 0;
  Eigen::VectorXd scales_;
};

struct NewtonOutcome {
  G3SolveStatus status = G3SolveStatus::MaxIterations;
  int iterations = 0;
  Eigen::VectorXd v;
  double scaledInf = 0.0;
  double norm = 0.0;
  std::vector<double> history;
};

bool spanLengthsPositive(const Eigen::VectorXd& v, int n) {
  return v.allFinite() && (v.head(n).array() > 0.0).all();
}

NewtonOutcome newton(const System& sys, Eigen::VectorXd v, const Eigen::VectorXd& offset,
                     const G3SolverOptions& opt) {
  NewtonOutcome out;
  const int n = sys.n();
  const bool square = sys.rows() == sys.cols();
  const bool over = sys.rows() > sys.cols();
  const Eigen::VectorXd& scales = sys.scales();
  Eigen::VectorXd f;
  Eigen::MatrixXd jac;
  Eigen::VectorXi panels = sys.panels(v);
  sys.evaluate(v, panels, offset, f, nullptr);
  Eigen::VectorXd scaled = f.cwiseQuotient(scales);
  std::vector<double> merits{scaled.norm()};
  out.history.push_back(f.norm());
  auto finish = [&](G3SolveStatus status) {
    out.status = status;
    out.v = v;
    out.scaledInf = scaled.cwiseAbs().maxCoeff();
    out.norm = f.norm();
    return out;
  };
  if (!f.allFinite()) return finish(G3SolveStatus::NonFinite);
  const int maxIt = opt.paperMode ? 4 : opt.maxIterations;
  if (!opt.paperMode && scaled.cwiseAbs().maxCoeff() <= opt.tolerance) return finish(G3SolveStatus::Converged);
  double mu = -1.0;  // Levenberg-Marquardt damping, set from the first Jacobian
  double nu = 2.0;
  for (int it = 1; it <= maxIt; ++it) {
    if (sys.overBudget()) return finish(G3SolveStatus::WorkLimit);
    out.iterations = it;
    sys.evaluate(v, panels, offset, f, &jac);
    const Eigen::MatrixXd scaledJac = scales.cwiseInverse().asDiagonal() * jac;
    const bool levenbergMarquardt = !opt.paperMode && opt.globalization == Globalization::LevenbergMarquardt;
    Eigen::VectorXd step;
    if (levenbergMarquardt) {
      // computed below, per damping value
    } else if (square && !opt.paperMode) {
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaledJac);
      if (qr.rank() < sys.cols()) return finish(G3SolveStatus::SingularJacobian);
      step = -qr.solve(scaled);
    } else {
      // Minimum-norm Gauss-Newton step J^+ f (sec. 4); least squares when overdetermined.
      Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(scaledJac);
      if (cod.rank() < std::min(sys.rows(), sys.cols())) return finish(G3SolveStatus::SingularJacobian);
      step = -cod.solve(scaled);
    }
    if (!levenbergMarquardt && !step.allFinite()) return finish(G3SolveStatus::NonFinite);
    // Least squares: stationary when the Gauss-Newton step vanishes (the residual need not).
    if (over && !levenbergMarquardt && step.cwiseAbs().maxCoeff() <= 1e-11 * (1.0 + v.cwiseAbs().maxCoeff())) {
      return finish(G3SolveStatus::Converged);
    }

    Eigen::VectorXd trial;
    Eigen::VectorXd trialF;
    const double merit2 = scaled.squaredNorm();
    if (opt.paperMode || opt.globalization == Globalization::None) {
      trial = v + step;
      if (!trial.allFinite()) return finish(G3SolveStatus::NonFinite);
      if ((trial.head(n).array() <= 0.0).any()) {
        v = trial;
        return finish(G3SolveStatus::NonPositiveSpanLength);
      }
      sys.evaluate(trial, panels, offset, trialF, nullptr);
    } else {
      bool accepted = false;
      if (levenbergMarquardt) {
        // Nielsen's damping update; the m x m form keeps the step minimum-norm when m < n.
        const Eigen::MatrixXd normal =
            over ? Eigen::MatrixXd(scaledJac.transpose() * scaledJac) : Eigen::MatrixXd(scaledJac * scaledJac.transpose());
        if (mu < 0.0) mu = 1e-8 * normal.diagonal().maxCoeff();
        for (int attempt = 0; attempt < 60 && !accepted && !sys.overBudget(); ++attempt) {
          Eigen::MatrixXd damped = normal;
          damped.diagonal().array() += mu;
          const Eigen::LDLT<Eigen::MatrixXd> ldlt(damped);
          const Eigen::VectorXd lmStep = over ? Eigen::VectorXd(-ldlt.solve(scaledJac.transpose() * scaled))
                                              : Eigen::VectorXd(-scaledJac.transpose() * ldlt.solve(scaled));
          trial = v + lmStep;
          if (lmStep.allFinite() && spanLengthsPositive(trial, n)) {
            sys.evaluate(trial, panels, offset, trialF, nullptr);
            const double actual = merit2 - trialF.cwiseQuotient(scales).squaredNorm();
            const double predicted = merit2 - (scaled + scaledJac * lmStep).squaredNorm();
            if (trialF.allFinite() && predicted > 0.0 && actual > 1e-4 * predicted) {
              const double rho = actual / predicted;
              mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
              nu = 2.0;
              accepted = true;
              break;
            }
          }
          mu *= nu;
          nu *= 2.0;
        }
      } else {
        // Armijo backtracking on ||scaled f||^2.
        double lambda = 1.0;
        while (lambda >= opt.lineSearchFloor && !sys.overBudget()) {
          trial = v + lambda * step;
          if (spanLengthsPositive(trial, n)) {
            sys.evaluate(trial, panels, offset, trialF, nullptr);
            if (trialF.allFinite() &&
                trialF.cwiseQuotient(scales).squaredNorm() <= (1.0 - 2e-4 * lambda) * merit2) {
              accepted = true;
              break;
            }
          }
          lambda *= 0.5;
        }
      }
      if (!accepted && sys.overBudget()) return finish(G3SolveStatus::WorkLimit);
      if (!accepted) {
        // At the rounding floor no step can decrease the residual any more.
        if (scaled.cwiseAbs().maxCoeff() <= 1e2 * opt.tolerance) return finish(G3SolveStatus::Converged);
        return finish(G3SolveStatus::LineSearchFailed);
      }
    }
    if (!trialF.allFinite()) return finish(G3SolveStatus::NonFinite);
    const double stepInf = (trial - v).cwiseAbs().maxCoeff();
    v = trial;
    const Eigen::VectorXi newPanels = sys.panels(v);
    if (newPanels != panels) {
      panels = newPanels;
      sys.evaluate(v, panels, offset, trialF, nullptr);
    }
    f = trialF;
    scaled = f.cwiseQuotient(scales);
    out.history.push_back(f.norm());
    merits.push_back(scaled.norm());
    if (!f.allFinite()) return finish(G3SolveStatus::NonFinite);
    if (opt.paperMode) continue;
    const double scaledInf = scaled.cwiseAbs().maxCoeff();
    const bool tinyStep = stepInf <= 1e-13 * (1.0 + v.cwiseAbs().maxCoeff());
    if (scaledInf <= opt.tolerance && !over) return finish(G3SolveStatus::Converged);
    if (tinyStep && (over || scaledInf <= 1e2 * opt.tolerance)) return finish(G3SolveStatus::Converged);
    const size_t k = merits.size();
    if (k > 5 && merits[k - 1] > 0.9 * merits[k - 6]) return finish(G3SolveStatus::Stalled);
  }
  if (opt.paperMode && scaled.cwiseAbs().maxCoeff() <= opt.tolerance) return finish(G3SolveStatus::Converged);
  return finish(G3SolveStatus::MaxIterations);
}

}  // namespace

G3SolveResult solveG3Curve(const Eigen::Ref<const Eigen::MatrixX2d>& points, const std::vector<Condition>& conditions,
                           const G3SolverOptions& options, const std::optional<Eigen::VectorXd>& initialGuess) {
  detail::validatePoints(points, "solveG3Curve");
  if (options.maxIterations < 1 || options.quadratureNodes < 2 || !(options.maxTurnPerPanel > 0.0) ||
      !(options.tolerance > 0.0) || !(options.lineSearchFloor > 0.0) || !(options.minContinuationStep > 0.0) ||
      !(options.maxTangentEvaluationsPerSpan > 0.0)) {
    throw G3InputError(
        "solveG3Curve options: need maxIterations >= 1, quadratureNodes >= 2 and positive "
        "maxTurnPerPanel, tolerance, lineSearchFloor, minContinuationStep, maxTangentEvaluationsPerSpan");
  }
  System sys(points, conditions, options);
  const int n = sys.n();
  if (sys.conditionRows() > 3 && !options.allowOverdetermined) {
    std::ostringstream msg;
    msg << "solveG3Curve: at most 3 condition rows make a square system, got " << sys.conditionRows()
        << " (set allowOverdetermined for a least-squares fit)";
    throw G3InputError(msg.str());
  }
  if (sys.conditionRows() < 3 && options.underdetermined == UnderdeterminedPolicy::Reject) {
    std::ostringstream msg;
    msg << "solveG3Curve: 3 condition rows are needed for a unique curve, got " << sys.conditionRows()
        << " (UnderdeterminedPolicy::Reject)";
    throw G3InputError(msg.str());
  }

  Eigen::VectorXd v0;
  if (initialGuess) {
    if (initialGuess->size() != 2 * n + 3) {
      std::ostringstream msg;
      msg << "solveG3Curve: initial guess needs 2n+3 = " << 2 * n + 3 << " values, got " << initialGuess->size();
      throw G3InputError(msg.str());
    }
    if (!spanLengthsPositive(*initialGuess, n)) {
      throw G3InputError("solveG3Curve: initial guess needs finite values and every Delta s_i > 0");
    }
    v0 = *initialGuess;
  } else {
    v0 = initialGuessFromCubicSpline(points).unknowns;
  }
  sys.alignBranches(v0);

  G3SolveResult result;
  result.conditionRows = sys.conditionRows();
  result.underdetermined = sys.conditionRows() < 3;
  if (result.underdetermined) {
    std::ostringstream msg;
    msg << sys.conditionRows() << " condition row(s) < 3: the curve is the minimum-norm member of a "
        << 3 - sys.conditionRows() << "-parameter family and depends on the initial guess";
    result.warnings.push_back(msg.str());
  }
  if (sys.conditionRows() > 3) {
    std::ostringstream msg;
    msg << sys.conditionRows() << " condition rows > 3: solved as least squares; conditions hold only as "
        << "well as scaledResidualInf says";
    result.warnings.push_back(msg.str());
  }
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(sys.rows());

  NewtonOutcome outcome;
  const bool direct = options.paperMode || options.continuation != ContinuationMode::Always;
  if (direct) {
    outcome = newton(sys, v0, zero, options);
    result.iterations = outcome.iterations;
    result.residualHistory = outcome.history;
  }
  const bool continuation = !options.paperMode && (options.continuation == ContinuationMode::Always ||
                                                   (options.continuation == ContinuationMode::OnFailure &&
                                                    outcome.status != G3SolveStatus::Converged &&
                                                    outcome.status != G3SolveStatus::WorkLimit &&
                                                    // a rank-deficient system stays so along any path
                                                    outcome.status != G3SolveStatus::SingularJacobian));
  if (continuation) {
    // Start from a curve that interpolates (min-norm Newton on the interpolation rows alone),
    // so that the lambda = 0 problem is feasible; the guess itself may carry targets no
    // interpolating curve reaches (e.g. the cubic's length, shorter than any G3 curve's).
    // Targets then move from their values there to the requested ones:
    // g(v) - (1 - lambda) g(v_start).
    const System bare(points, {}, options);
    G3SolverOptions bareOptions = options;
    bareOptions.globalization = Globalization::LineSearch;
    const NewtonOutcome start = newton(bare, v0, Eigen::VectorXd::Zero(bare.rows()), bareOptions);
    result.iterations += start.iterations;
    const Eigen::VectorXd vStart = start.status == G3SolveStatus::Converged ? start.v : v0;
    Eigen::VectorXd f0;
    sys.evaluate(vStart, sys.panels(vStart), zero, f0, nullptr);
    Eigen::VectorXd g0 = f0;
    g0.head(2 * n).setZero();
    const G3SolveStatus directStatus = outcome.status;
    Eigen::VectorXd v = vStart;
    double lambda = 0.0;
    double step = 0.25;
    int successes = 0;
    bool first = true;
    G3SolveStatus status = G3SolveStatus::Converged;
    while (true) {
      const double target = first ? 0.0 : std::min(1.0, lambda + step);
      NewtonOutcome stage = newton(sys, v, (1.0 - target) * g0, options);
      ++result.continuationStages;
      result.iterations += stage.iterations;
      if (stage.status == G3SolveStatus::Converged) {
        v = stage.v;
        lambda = target;
        outcome = stage;
        if (!first && ++successes >= 2) {
          step *= 2.0;
          successes = 0;
        }
        first = false;
        if (lambda >= 1.0) break;
      } else {
        if (first || stage.status == G3SolveStatus::WorkLimit) {  // the relaxed start fails, or no work is left
          outcome = stage;
          status = stage.status;
          break;
        }
        step *= 0.5;
        successes = 0;
        if (step < options.minContinuationStep) {
          outcome = stage;
          status = G3SolveStatus::LikelyInfeasible;
          break;
        }
      }
    }
    outcome.status = status == G3SolveStatus::Converged ? outcome.status : status;
    if (outcome.status != G3SolveStatus::Converged) {
      std::ostringstream msg;
      msg << "continuation stopped at lambda = " << lambda << " after direct Newton: " << toString(directStatus);
      result.message = msg.str();
    }
    if (result.residualHistory.empty()) result.residualHistory = outcome.history;
  }

  result.status = outcome.status;
  result.unknowns = outcome.v;
  result.residualNorm = outcome.norm;
  result.scaledResidualInf = outcome.scaledInf;
  if (outcome.v.allFinite() && spanLengthsPositive(outcome.v, n)) {
    Eigen::VectorXd f;
    Eigen::MatrixXd jac;
    sys.evaluate(outcome.v, sys.panels(outcome.v), zero, f, &jac);
    // Report the residual of the requested problem, not of a continuation stage.
    result.residualNorm = f.norm();
    result.scaledResidualInf = f.cwiseQuotient(sys.scales()).cwiseAbs().maxCoeff();
    const Eigen::MatrixXd scaledJac = sys.scales().cwiseInverse().asDiagonal() * jac;
    // 1-norm reciprocal condition estimates: an SVD would cost more than the whole solve.
    double rcond = 0.0;
    if (scaledJac.rows() == scaledJac.cols()) {
      rcond = Eigen::PartialPivLU<Eigen::MatrixXd>(scaledJac).rcond();
    } else {
      const Eigen::MatrixXd normal = scaledJac.rows() < scaledJac.cols()
                                         ? Eigen::MatrixXd(scaledJac * scaledJac.transpose())
                                         : Eigen::MatrixXd(scaledJac.transpose() * scaledJac);
      const Eigen::LLT<Eigen::MatrixXd> llt(normal);
      rcond = llt.info() == Eigen::Success ? std::sqrt(std::max(0.0, llt.rcond())) : 0.0;
    }
    result.jacobianConditionNumber = rcond > 0.0 ? 1.0 / rcond : std::numeric_limits<double>::infinity();
    if (result.status == G3SolveStatus::Converged && !(rcond >= options.singularThreshold)) {
      result.status = G3SolveStatus::SingularJacobian;
    }
  }
  result.converged = result.status == G3SolveStatus::Converged;
  if (result.message.empty()) {
    std::ostringstream msg;
    msg << toString(result.status) << " after " << result.iterations << " iterations, scaled residual "
        << result.scaledResidualInf;
    result.message = msg.str();
  }
  if (result.converged) {
    result.curve = QuadraticCurvatureSpline::fromSpanStarts(points, outcome.v.head(n), outcome.v.tail(n + 3));
  }
  return result;
}

G3SystemEvaluation evaluateG3System(const Eigen::Ref<const Eigen::MatrixX2d>& points,
                                    const std::vector<Condition>& conditions,
                                    const Eigen::Ref<const Eigen::VectorXd>& unknowns,
                                    const G3SolverOptions& options) {
  detail::validatePoints(points, "evaluateG3System");
  const System sys(points, conditions, options);
  const Eigen::VectorXd v = unknowns;
  if (v.size() != sys.cols() || !spanLengthsPositive(v, sys.n())) {
    std::ostringstream msg;
    msg << "evaluateG3System: unknowns need 2n+3 = " << sys.cols() << " finite values with Delta s_i > 0, got "
        << v.size() << " values";
    throw G3InputError(msg.str());
  }
  G3SystemEvaluation out;
  sys.evaluate(v, sys.panels(v), Eigen::VectorXd::Zero(sys.rows()), out.residual, &out.jacobian);
  out.rowScales = sys.scales();
  return out;
}

}  // namespace ffdkit::geometry::g3
