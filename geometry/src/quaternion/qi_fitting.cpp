#include "ffdkit/geometry/quaternion/qi_fitting.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Cholesky>

#include "ffdkit/geometry/gauss_legendre.h"
#include "ffdkit/geometry/quaternion/quaternion_error.h"
#include "ffdkit/geometry/quaternion/unit_quaternion.h"
#include "qi_fit_problem.h"

namespace ffdkit::geometry::quaternion {

Eigen::VectorXd chordLengthParameters(const Eigen::MatrixX3d& points, const std::vector<int>& breaks) {
  const int last = static_cast<int>(points.rows()) - 1;
  if (breaks.size() < 2 || breaks.front() != 0 || breaks.back() != last) {
    std::ostringstream msg;
    msg << "chordLengthParameters: expected breaks from 0 to " << last << " (#points - 1), got "
        << (breaks.empty() ? std::string("none") : std::to_string(breaks.front()) + ".." + std::to_string(breaks.back()));
    throw QuaternionCurveError(msg.str());
  }
  for (std::size_t j = 1; j < breaks.size(); ++j) {
    if (breaks[j] <= breaks[j - 1]) {
      std::ostringstream msg;
      msg << "chordLengthParameters: expected strictly increasing breaks, got " << breaks[j - 1] << " then "
          << breaks[j] << " at position " << j;
      throw QuaternionCurveError(msg.str());
    }
  }
  Eigen::VectorXd u(points.rows());
  for (std::size_t j = 0; j + 1 < breaks.size(); ++j) {
    double total = 0.0;
    for (int m = breaks[j] + 1; m <= breaks[j + 1]; ++m) total += (points.row(m) - points.row(m - 1)).norm();
    if (!(total > 0.0) || !std::isfinite(total)) {
      std::ostringstream msg;
      msg << "chordLengthParameters: segment " << j << " (points " << breaks[j] << ".." << breaks[j + 1] << ") has "
          << (total > 0.0 ? "a chord length beyond the range of doubles (points too far apart)" : "zero chord length");
      throw QuaternionCurveError(msg.str());
    }
    double acc = 0.0;
    u[breaks[j]] = static_cast<double>(j);
    for (int m = breaks[j] + 1; m <= breaks[j + 1]; ++m) {
      acc += (points.row(m) - points.row(m - 1)).norm();
      u[m] = static_cast<double>(j) + acc / total;
    }
  }
  return u;
}

namespace {

// omega taking direction a to b by the minimal rotation, in the exp convention (half angle).
Eigen::Vector3d halfAngleOmega(const Eigen::Vector3d& a, const Eigen::Vector3d& b, bool planar) {
  const Eigen::Vector3d c = a.cross(b);
  const double theta = angleBetween(a, b);
  Eigen::Vector3d w;
  if (c.norm() > 1e-14) {
    w = 0.5 * theta * c.normalized();
  } else if (a.dot(b) > 0.0) {
    w.setZero();
  } else {
    const Eigen::Vector3d axis = planar ? Eigen::Vector3d::UnitZ() : a.unitOrthogonal();
    w = 0.5 * M_PI * axis;
  }
  if (planar) w = Eigen::Vector3d(0.0, 0.0, w.z());
  return w;
}

// Uniform cubic B-spline interpolating the points at x = 0..N-1 with the paper's end condition
// Q_0 = Q_1, Q_{N+1} = Q_N (Sakiyama et al. 2001, eqs. (11)-(12)), solved directly instead of by
// Gauss-Seidel (eqs. (14)-(16) converge to the same controls; Sakiyama et al. 2001, sec. 3.4.1).
UniformCubicBSpline interpolatingCubicBSpline(const Eigen::MatrixX3d& points) {
  const int n = static_cast<int>(points.rows());
  Eigen::VectorXd lower = Eigen::VectorXd::Constant(n, 1.0), diag = Eigen::VectorXd::Constant(n, 4.0),
                  upper = Eigen::VectorXd::Constant(n, 1.0);
  Eigen::MatrixX3d rhs = 6.0 * points;
  diag[0] += 1.0;         // Q_0 = Q_1
  diag[n - 1] += 1.0;     // Q_{N+1} = Q_N
  for (int i = 1; i < n; ++i) {
    const double w = lower[i] / diag[i - 1];
    diag[i] -= w * upper[i - 1];
    rhs.row(i) -= w * rhs.row(i - 1);
  }
  Eigen::MatrixX3d q(n + 2, 3);
  q.row(n) = rhs.row(n - 1) / diag[n - 1];
  for (int i = n - 2; i >= 0; --i) q.row(i + 1) = (rhs.row(i) - upper[i] * q.row(i + 2)) / diag[i];
  q.row(0) = q.row(1);
  q.row(n + 1) = q.row(n);
  return UniformCubicBSpline(q);
}

QiChain buildChain(const detail::QiFitProblem& pb, const Eigen::VectorXd& x) {
  QiChain chain(pb.start(), pb.q00(x), pb.form(), Eigen::Vector3d::UnitX(), pb.quadrature());
  for (int seg = 0; seg < pb.layout().segments; ++seg) chain.appendSegment(pb.omegas(x, seg), pb.length(x, seg));
  return chain;
}

}  // namespace

namespace {

// The data parameters u_i: chord length per segment, or the user's (each break at its integer).
Eigen::VectorXd fitParameters(const Eigen::MatrixX3d& points, const std::vector<int>& breaks, const FitOptions& options,
                              const Eigen::VectorXd* userParameters) {
  if (options.degree < 1) {
    std::ostringstream msg;
    msg << "fitQiChain: expected degree >= 1, got " << options.degree;
    throw QuaternionCurveError(msg.str());
  }
  if (!points.allFinite()) throw QuaternionCurveError("fitQiChain: expected finite point coordinates");
  Eigen::VectorXd u = chordLengthParameters(points, breaks);
  if (userParameters == nullptr) return u;
  const int segments = static_cast<int>(breaks.size()) - 1;
  if (userParameters->size() != points.rows()) {
    std::ostringstream msg;
    msg << "fitQiChain: expected " << points.rows() << " user parameters, got " << userParameters->size();
    throw QuaternionCurveError(msg.str());
  }
  u = *userParameters;
  for (int j = 0; j <= segments; ++j) {
    if (std::abs(u[breaks[j]] - j) > 1e-12) {
      std::ostringstream msg;
      msg << "fitQiChain: expected user parameter " << j << " at break point " << breaks[j] << ", got " << u[breaks[j]];
      throw QuaternionCurveError(msg.str());
    }
  }
  return u;
}

// Whether the fit is planar (in z = const): asked for (the points must be flat), or Auto and flat.
bool fitIsPlanar(const Eigen::MatrixX3d& points, const FitOptions& options) {
  const double zSpread = points.col(2).maxCoeff() - points.col(2).minCoeff();
  const double extent = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
  const bool flat = zSpread <= 1e-12 * std::max(extent, 1e-300);
  if (options.dimension == FitDimension::Planar && !flat) {
    std::ostringstream msg;
    msg << "fitQiChain: Planar fitting expects all points at one z, got a z spread of " << zSpread;
    throw QuaternionCurveError(msg.str());
  }
  return options.dimension == FitDimension::Planar || (options.dimension == FitDimension::Auto && flat);
}

// The initial curve the fit starts from (Sakiyama et al. 2001, sec. 3.4): the least-squares cubic
// (the baseline), or the interpolating cubic of the paper's preset (sec. 3.4.1), and the map from
// the QI global parameter g to its own parameter.
class InitialCurve {
 public:
  InitialCurve(const Eigen::MatrixX3d& points, const Eigen::VectorXd& u, const UniformCubicBSpline& baseline,
               const FitOptions& options, bool planar)
      : u_(u),
        interpolating_(options.initialCurve == FitInitialCurve::InterpolatingCubic),
        planar_(planar),
        curve_(interpolating_ ? interpolatingCubicBSpline(points) : baseline) {}

  // Initial-curve parameter x of the QI global parameter: x = u for the LSQ cubic; piecewise
  // linear in the data parameters for the interpolating cubic, whose data point m sits at x = m.
  double toInit(double g) const {
    if (!interpolating_) return g;
    const Eigen::Index n = u_.size();
    Eigen::Index m = std::upper_bound(u_.data(), u_.data() + n, g) - u_.data() - 1;
    m = std::clamp<Eigen::Index>(m, 0, n - 2);
    return static_cast<double>(m) + (g - u_[m]) / (u_[m + 1] - u_[m]);
  }

  // The unit tangent at g (in the plane when planar).
  Eigen::Vector3d direction(double g) const {
    Eigen::Vector3d d = curve_.derivative(toInit(g), 1);
    if (planar_) d.z() = 0.0;
    return d.normalized();
  }

  // Eq. (18) read as the arc length of the initial curve over segment seg (Sakiyama et al. 2001,
  // sec. 3.4.2).
  double segmentLength(int seg, const GaussLegendreRule& rule) const {
    double l = 0.0;
    const double a = toInit(seg), b = toInit(seg + 1.0);
    const int panels = std::max(4, static_cast<int>(std::ceil(b - a)) * 2);
    for (int p = 0; p < panels; ++p) {
      l += integrateGaussLegendre(rule, a + (b - a) * p / panels, a + (b - a) * (p + 1) / panels,
                                  [&](double xx) { return curve_.derivative(xx, 1).norm(); });
    }
    return l;
  }

 private:
  const Eigen::VectorXd& u_;
  bool interpolating_;
  bool planar_;
  UniformCubicBSpline curve_;
};

// The start tangent: the initial curve's, or the one given.
Eigen::Vector3d startTangent(const InitialCurve& init, const FitOptions& options) {
  if (options.startTangent != StartTangentMode::Given) return init.direction(0.0);
  if (!(options.givenStartTangent.norm() > 0.0))
    throw QuaternionCurveError("fitQiChain: Given start tangent mode expects a non-zero givenStartTangent");
  return options.givenStartTangent.normalized();
}

// The unknowns' starting values from the initial curve: the minimal rotations between its
// tangents at the k sub-knots of each segment (half-angle omegas), and each segment's log length.
Eigen::VectorXd initialUnknowns(const detail::QiFitProblem& pb, const detail::QiFitLayout& layout,
                                const InitialCurve& init, const Eigen::Vector3d& t0) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(pb.size());
  const GaussLegendreRule rule = gaussLegendreRule(8);
  const int k = layout.degree;
  for (int seg = 0; seg < layout.segments; ++seg) {
    Eigen::Vector3d prev = seg == 0 ? t0 : init.direction(seg);
    for (int j = 1; j <= k; ++j) {
      const Eigen::Vector3d next = init.direction(seg + static_cast<double>(j) / k);
      const Eigen::Vector3d w = halfAngleOmega(prev, next, layout.planar);
      if (layout.planar) {
        x[layout.offset(seg) + j - 1] = w.z();
      } else {
        x.segment<3>(layout.offset(seg) + 3 * (j - 1)) = w;
      }
      prev = next;
    }
    x[layout.offset(seg + 1) - 1] = std::log(init.segmentLength(seg, rule));
  }
  return x;
}

// Levenberg-Marquardt with Marquardt scaling (Sakiyama et al. 2001, sec. 3.5.1 [rec]); analytic or
// forward-difference Jacobian; optionally NL2SOL's secant tail (FitOptions::secantTail).
class QiLevenbergMarquardt {
 public:
  QiLevenbergMarquardt(const detail::QiFitProblem& pb, const FitOptions& options, Eigen::VectorXd x)
      : pb_(pb), options_(options), x_(std::move(x)) {
    pb_.evaluate(x_, ev_);
    objective_ = ev_.r.squaredNorm();
    initialObjective_ = objective_;
    history_.push_back(objective_);
  }

  void run() {
    updateJacobian();
    while (!gradientConverged()) {
      Eigen::VectorXd taken;    // the accepted step
      bool secantPair = false;  // it updates S
      if (takeStep(taken, secantPair)) break;
      const Eigen::VectorXd gBefore = g_;
      updateJacobian();
      if (secantPair) updateSecant(taken, gBefore);
    }
  }

  const Eigen::VectorXd& x() const { return x_; }
  const Eigen::VectorXd& residuals() const { return ev_.r; }
  double initialObjective() const { return initialObjective_; }
  bool converged() const { return converged_; }
  int iterations() const { return iterations_; }
  int evaluations() const { return evaluations_; }
  std::vector<double> takeHistory() { return std::move(history_); }
  const std::string& message() const { return message_; }

 private:
  // The secant tail (FitOptions::secantTail): S estimates sum r_i Hess r_i, the part of the Hessian
  // of R / 2 that J^T J leaves out, from the steps s and the changes y of g = J^T r: S s ~ y - J^T J s
  // (Dennis, Gay & Welsch 1981, NL2SOL's update with its sizing and its model switch). Far from the
  // minimum the steps are too long for a secant to hold (S learnt from every step: 296 trials on the
  // spiral instead of 106; from every step after the first short one: the 12-segment 328-point
  // spiral ran into the 500 cap), so S learns only from accepted steps that lower R by less than
  // kSecantTailStart of R. Trials on the 6-segment spiral for 1e-4 / 1e-5 / 1e-6 / 1e-7 / 1e-8: 88 /
  // 86 / 90 / 81 / 81; below 1e-7 the overfitting 82-point 6-segment spiral stays at the 500 cap.
  static constexpr double kSecantTailStart = 1e-7;

  void stopWith(const char* why, bool converged) {
    message_ = why;
    converged_ = converged;
  }

  // Gauss-Newton normal equations a = J^T J, g = J^T r at the current x.
  void updateJacobian() {
    if (options_.jacobian == FitJacobian::Analytic) {
      pb_.analyticNormalEquations(x_, ev_, a_, g_);
    } else {
      evaluations_ += pb_.finiteDifferenceJacobian(x_, ev_, jac_);
      a_.setZero(jac_.cols(), jac_.cols());
      a_.selfadjointView<Eigen::Lower>().rankUpdate(jac_.transpose());
      a_.triangularView<Eigen::StrictlyUpper>() = a_.transpose();
      g_ = jac_.transpose() * ev_.r;
    }
  }

  // An exact fit, or the gradient's largest cosine with a column of J within the tolerance.
  bool gradientConverged() {
    if (objective_ <= 1e-300) {
      stopWith("exact fit", true);
      return true;
    }
    double cosine = 0.0;
    const double rn = std::sqrt(objective_);
    for (int c = 0; c < a_.cols(); ++c) {
      const double cn = std::sqrt(a_(c, c));
      if (cn > 0.0) cosine = std::max(cosine, std::abs(g_[c]) / (cn * rn));
    }
    if (!(cosine <= options_.gradientTolerance)) return false;
    stopWith("gradient tolerance", true);
    return true;
  }

  // Damped steps until one lowers R (then x moves, `taken` is it); true when the fit stops.
  bool takeStep(Eigen::VectorXd& taken, bool& secantPair) {
    // Marquardt scaling by the current diagonal (the MINPACK running maximum doubled the
    // iterations on the spiral and D-CHAIN3D-N).
    Eigen::VectorXd diag = a_.diagonal();
    const double dmax = diag.maxCoeff();
    diag = diag.cwiseMax(1e-12 * std::max(dmax, 1e-300));
    if (mu_ < 0.0) mu_ = 1e-3;
    while (true) {
      if (iterations_ >= options_.maxIterations || evaluations_ >= options_.maxFunctionEvaluations) {
        stopWith("iteration or evaluation cap reached", false);
        return true;
      }
      bool withSecant = false;
      const Eigen::VectorXd step = dampedStep(diag, withSecant);
      if (!step.allFinite()) {
        mu_ *= nu_;
        nu_ *= 2.0;
        continue;
      }
      if (step.norm() <= options_.stepTolerance * (x_.norm() + options_.stepTolerance)) {
        stopWith("step tolerance", true);
        return true;
      }
      const Eigen::VectorXd xn = x_ + step;
      pb_.evaluate(xn, trial_);
      const Eigen::VectorXd& rn2 = trial_.r;
      ++evaluations_;
      ++iterations_;
      const double objn = rn2.allFinite() ? rn2.squaredNorm() : INFINITY;
      const double predictedGN = -(step.dot(g_) * 2.0 + step.dot(a_ * step));
      const double predictedSecant = haveSecant_ ? predictedGN - step.dot(secant_ * step) : predictedGN;
      const double predicted = withSecant ? predictedSecant : predictedGN;
      const double actual = objective_ - objn;
      // NL2SOL's model switch: the next step uses the model that predicted this one's change better.
      if (haveSecant_) preferSecant_ = std::abs(predictedSecant - actual) < std::abs(predictedGN - actual);
      const double rho = predicted > 0.0 ? actual / predicted : -1.0;
      if (actual > 0.0 && rho > 0.0) {
        taken = step;
        secantPair = options_.secantTail && actual < kSecantTailStart * objn;
        x_ = xn;
        std::swap(ev_, trial_);
        history_.push_back(objn);
        objective_ = objn;
        mu_ *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
        nu_ = 2.0;
        if (actual <= options_.functionTolerance * (objective_ + actual) &&
            predicted <= options_.functionTolerance * (objective_ + actual)) {
          stopWith("function tolerance", true);
          return true;
        }
        return false;
      }
      mu_ *= nu_;
      nu_ *= 2.0;
      if (mu_ > 1e20) {
        stopWith("no further decrease (damping limit)", true);
        return true;
      }
    }
  }

  // The step of the damped model: J^T J (+ S when the secant model is preferred and keeps it
  // positive definite; `withSecant` says whether it did) + mu D.
  Eigen::VectorXd dampedStep(const Eigen::VectorXd& diag, bool& withSecant) const {
    Eigen::MatrixXd damped = a_;
    const bool trySecant = haveSecant_ && preferSecant_;
    if (trySecant) damped += secant_;
    damped.diagonal() += mu_ * diag;
    Eigen::LDLT<Eigen::MatrixXd> ldlt(damped);
    withSecant = trySecant;
    if (withSecant && !(ldlt.info() == Eigen::Success && (ldlt.vectorD().array() > 0.0).all())) {
      // J^T J + S + mu D is not positive definite: this step uses the Gauss-Newton model.
      withSecant = false;
      damped = a_;
      damped.diagonal() += mu_ * diag;
      ldlt.compute(damped);
    }
    return ldlt.solve(-g_);
  }

  // The symmetric secant update of Dennis, Gay & Welsch from step s and the change of g.
  void updateSecant(const Eigen::VectorXd& s, const Eigen::VectorXd& gBefore) {
    const Eigen::VectorXd y = g_ - gBefore;
    const double ys = y.dot(s);
    if (!(ys > 0.0)) return;
    if (!haveSecant_) secant_.setZero(s.size(), s.size());
    const Eigen::VectorXd yh = y - a_ * s;  // the change of g that J^T J does not explain
    // Sizing: shrink S where it overstates the curvature along s (NL2SOL).
    const double sss = s.dot(secant_ * s);
    if (haveSecant_ && sss != 0.0) secant_ *= std::min(1.0, std::abs(s.dot(yh)) / std::abs(sss));
    // S+ s = yh, S+ - S of rank two.
    const Eigen::VectorXd z = yh - secant_ * s;
    secant_ += (z * y.transpose() + y * z.transpose()) / ys - (z.dot(s) / (ys * ys)) * (y * y.transpose());
    haveSecant_ = true;
  }

  const detail::QiFitProblem& pb_;
  const FitOptions& options_;
  Eigen::VectorXd x_;
  detail::QiFitEvaluation ev_, trial_;
  double objective_ = 0.0, initialObjective_ = 0.0;
  std::vector<double> history_;
  int evaluations_ = 1;
  int iterations_ = 0;
  bool converged_ = false;
  std::string message_;
  Eigen::MatrixXd a_, jac_;
  Eigen::VectorXd g_;
  double mu_ = -1.0;
  double nu_ = 2.0;
  bool haveSecant_ = false;
  bool preferSecant_ = true;
  Eigen::MatrixXd secant_;
};

}  // namespace

FitResult fitQiChain(const Eigen::MatrixX3d& points, const std::vector<int>& breaks, const FitOptions& options,
                     const Eigen::VectorXd* userParameters) {
  const Eigen::VectorXd u = fitParameters(points, breaks, options, userParameters);
  const int segments = static_cast<int>(breaks.size()) - 1;
  const bool planar = fitIsPlanar(points, options);
  // The baseline: least-squares cubic at the same breaks and u_i (Sakiyama et al. 2001, sec. 3.7).
  UniformCubicBSpline baseline = fitLeastSquaresCubicBSpline(points, u, segments);
  const InitialCurve init(points, u, baseline, options, planar);
  const Eigen::Vector3d t0 = startTangent(init, options);

  detail::QiFitLayout layout{segments, options.degree, planar, 0};
  Eigen::Vector3d freeAxis1 = Eigen::Vector3d::UnitZ(), freeAxis2 = Eigen::Vector3d::UnitY();
  if (options.startTangent == StartTangentMode::Free) {
    layout.startVars = planar ? 1 : 2;
    freeAxis1 = planar ? Eigen::Vector3d::UnitZ() : t0.unitOrthogonal();
    freeAxis2 = t0.cross(freeAxis1).normalized();
  }
  detail::QiFitProblem pb(points, breaks, u, layout, options.form, options.quadrature, points.row(0).transpose(),
                          minimalRotation(Eigen::Vector3d::UnitX(), t0, Eigen::Vector3d::UnitZ()), freeAxis1, freeAxis2);
  pb.setParallel(options.parallel);
  QiLevenbergMarquardt solver(pb, options, initialUnknowns(pb, layout, init, t0));
  solver.run();

  FitResult result(buildChain(pb, solver.x()), std::move(baseline));
  result.parameters = u;
  result.pointErrors.resize(points.rows());
  const Eigen::VectorXd& r = solver.residuals();
  for (Eigen::Index i = 0; i < points.rows(); ++i) result.pointErrors[i] = r.segment<3>(3 * i).norm();
  result.rms = std::sqrt(result.pointErrors.squaredNorm() / static_cast<double>(points.rows()));
  result.maxError = result.pointErrors.maxCoeff();
  const double total = result.curve.length();
  result.rmsPercent = 100.0 * result.rms / total;
  result.maxPercent = 100.0 * result.maxError / total;
  result.initialRms = std::sqrt(solver.initialObjective() / static_cast<double>(points.rows()));
  result.converged = solver.converged();
  result.iterations = solver.iterations();
  result.functionEvaluations = solver.evaluations();
  result.objectiveHistory = solver.takeHistory();
  result.message = solver.message();
  return result;
}

CurvatureFairness curvatureFairness(const Eigen::VectorXd& kappa, int samplesPerPiece) {
  CurvatureFairness f;
  for (Eigen::Index i = 1; i < kappa.size(); ++i) {
    const double d = std::abs(kappa[i] - kappa[i - 1]);
    f.totalVariation += d;
    if (i % samplesPerPiece != 0) f.intraVariation += d;
  }
  for (Eigen::Index i = 0; i < kappa.size(); ++i) {
    const Eigen::Index local = i % samplesPerPiece;
    if (local == 0 || local == samplesPerPiece - 1) continue;
    const double a = kappa[i] - kappa[i - 1];
    const double b = kappa[i + 1] - kappa[i];
    // A sign change of the slope with a non-negligible turn (round-off plateaus are ignored).
    const double tiny = 1e-12 * (std::abs(kappa[i]) + 1e-300);
    if ((a > tiny && b < -tiny) || (a < -tiny && b > tiny)) ++f.interiorExtrema;
  }
  return f;
}

Eigen::VectorXd sampledChainCurvature(const QiChain& chain, int samplesPerSegment, bool signedPlanar) {
  Eigen::VectorXd k(chain.segmentCount() * samplesPerSegment);
  for (int seg = 0; seg < chain.segmentCount(); ++seg) {
    for (int i = 0; i < samplesPerSegment; ++i) {
      const double u = static_cast<double>(i) / (samplesPerSegment - 1);
      const QiChainSegment& s = chain.segment(seg);
      k[seg * samplesPerSegment + i] = signedPlanar ? s.signedPlanarCurvature(u) : s.curvature(u);
    }
  }
  return k;
}

Eigen::VectorXd sampledBSplineCurvature(const UniformCubicBSpline& spline, int samplesPerSpan, bool signedPlanar) {
  Eigen::VectorXd k(spline.spans() * samplesPerSpan);
  for (int m = 0; m < spline.spans(); ++m) {
    for (int i = 0; i < samplesPerSpan; ++i) {
      const double x = m + static_cast<double>(i) / (samplesPerSpan - 1);
      k[m * samplesPerSpan + i] = signedPlanar ? spline.signedPlanarCurvature(x) : spline.curvature(x);
    }
  }
  return k;
}

}  // namespace ffdkit::geometry::quaternion
