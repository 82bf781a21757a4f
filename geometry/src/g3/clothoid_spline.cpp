#include "ffdkit/geometry/g3/clothoid_spline.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/QR>

#include "ffdkit/geometry/g3/cubic_spline_initial_guess.h"
#include "ffdkit/geometry/g3/g3_error.h"
#include "points_validation.h"
#include "span_quadrature.h"

namespace ffdkit::geometry::g3 {
namespace {

inline double quadraticBezier(const Eigen::Vector3d& b, double t) {
  const double u = 1.0 - t;
  return b[0] * u * u + 2.0 * b[1] * u * t + b[2] * t * t;
}

inline double turning(const Eigen::Vector3d& b) { return std::abs(b[1] - b[0]) + std::abs(b[2] - b[1]); }

// b_0..b_{2n} from (Delta s, e) (Kuroda et al. 1997, sec. 2).
Eigen::VectorXd quadraticOrdinates(const Eigen::Ref<const Eigen::VectorXd>& ds, const Eigen::Ref<const Eigen::VectorXd>& e) {
  const Eigen::Index n = ds.size();
  Eigen::VectorXd b(2 * n + 1);
  for (Eigen::Index i = 0; i < n; ++i) b[2 * i + 1] = e[i + 1];
  b[0] = e[0];
  b[2 * n] = e[n + 1];
  for (Eigen::Index i = 1; i < n; ++i) b[2 * i] = (ds[i] * e[i] + ds[i - 1] * e[i + 1]) / (ds[i - 1] + ds[i]);
  return b;
}

// d b / d v, (2n+1) x (2n+2), v = (Delta s, e).
Eigen::MatrixXd quadraticOrdinateJacobian(const Eigen::Ref<const Eigen::VectorXd>& ds, const Eigen::Ref<const Eigen::VectorXd>& e) {
  const Eigen::Index n = ds.size();
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(2 * n + 1, 2 * n + 2);
  for (Eigen::Index i = 0; i < n; ++i) j(2 * i + 1, n + i + 1) = 1.0;
  j(0, n) = 1.0;
  j(2 * n, 2 * n + 1) = 1.0;
  for (Eigen::Index i = 1; i < n; ++i) {
    const double sum = ds[i - 1] + ds[i];
    const double gamma = ds[i - 1] / sum;  // b_{2i} = (1 - gamma) e_{i-1} + gamma e_i
    j(2 * i, n + i) = 1.0 - gamma;
    j(2 * i, n + i + 1) = gamma;
    const double gap = e[i + 1] - e[i];
    j(2 * i, i - 1) = gap * ds[i] / (sum * sum);
    j(2 * i, i) = -gap * ds[i - 1] / (sum * sum);
  }
  return j;
}

using QuadMoments = Eigen::Matrix<double, 8, 1>;  // I (2), then int B^2_k (cos, sin) for k = 0..2

QuadMoments quadraticSpanMoments(const GaussLegendreRule& rule, const Eigen::Vector3d& b, int panels) {
  QuadMoments sum = QuadMoments::Zero();
  for (int p = 0; p < panels; ++p) {
    sum += integrateGaussLegendre(rule, static_cast<double>(p) / panels, static_cast<double>(p + 1) / panels, [&](double t) {
      const double u = 1.0 - t;
      const double bern[3] = {u * u, 2.0 * u * t, t * t};
      const double angle = b[0] * bern[0] + b[1] * bern[1] + b[2] * bern[2];
      const double c = std::cos(angle), s = std::sin(angle);
      QuadMoments m;
      m << c, s, bern[0] * c, bern[0] * s, bern[1] * c, bern[1] * s, bern[2] * c, bern[2] * s;
      return m;
    });
  }
  return sum;
}

}  // namespace

ClothoidSpline ClothoidSpline::fromSpanStarts(const Eigen::Ref<const Eigen::MatrixX2d>& spanStarts,
                                              const Eigen::Ref<const Eigen::VectorXd>& spanLengths,
                                              const Eigen::Ref<const Eigen::VectorXd>& deBoor) {
  const Eigen::Index n = spanLengths.size();
  if (n < 1 || deBoor.size() != n + 2 || spanStarts.rows() != n + 1) {
    std::ostringstream msg;
    msg << "ClothoidSpline needs n >= 1 span lengths, n+2 de Boor ordinates and n+1 span starts, got " << n << ", "
        << deBoor.size() << ", " << spanStarts.rows();
    throw G3InputError(msg.str());
  }
  if (!((spanLengths.array() > 0.0).all() && spanLengths.allFinite() && deBoor.allFinite() && spanStarts.allFinite())) {
    throw G3InputError("ClothoidSpline needs finite values and every span length > 0");
  }
  ClothoidSpline c;
  c.spanLengths_ = spanLengths;
  c.deBoor_ = deBoor;
  c.spanStarts_ = spanStarts;
  c.bezier_ = quadraticOrdinates(spanLengths, deBoor);
  c.knots_.resize(n + 1);
  c.knots_[0] = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) c.knots_[i + 1] = c.knots_[i] + spanLengths[i];
  return c;
}

int ClothoidSpline::locate(double s, double& t) const {
  const double len = length();
  if (!(s >= -1e-12 * len && s <= len * (1.0 + 1e-12))) {
    std::ostringstream msg;
    msg << "arc length s must be in [0, " << len << "], got " << s;
    throw G3InputError(msg.str());
  }
  s = std::clamp(s, 0.0, len);
  const int n = spanCount();
  const int span = static_cast<int>(std::upper_bound(knots_.data() + 1, knots_.data() + n, s) - (knots_.data() + 1));
  t = std::clamp((s - knots_[span]) / spanLengths_[span], 0.0, 1.0);
  return span;
}

double ClothoidSpline::tangentAngle(double s) const {
  double t = 0.0;
  const int i = locate(s, t);
  return quadraticBezier(bezier_.segment<3>(2 * i), t);
}

double ClothoidSpline::curvature(double s) const {
  double t = 0.0;
  const int i = locate(s, t);
  const Eigen::Vector3d b = bezier_.segment<3>(2 * i);
  return 2.0 * ((b[1] - b[0]) * (1.0 - t) + (b[2] - b[1]) * t) / spanLengths_[i];
}

double ClothoidSpline::sharpness(int span) const {
  if (span < 0 || span >= spanCount()) throw G3InputError("ClothoidSpline::sharpness: span index out of range");
  const Eigen::Vector3d b = bezier_.segment<3>(2 * span);
  return 2.0 * (b[2] - 2.0 * b[1] + b[0]) / (spanLengths_[span] * spanLengths_[span]);
}

double ClothoidSpline::curvatureDerivative(double s) const {
  double t = 0.0;
  return sharpness(locate(s, t));
}

Eigen::Vector2d ClothoidSpline::position(double s) const {
  double t = 0.0;
  const int i = locate(s, t);
  const Eigen::Vector3d b = bezier_.segment<3>(2 * i);
  return spanStarts_.row(i).transpose() +
         spanLengths_[i] * detail::integrateTangent(detail::defaultRule(), [&](double u) { return quadraticBezier(b, u); },
                                                    0.0, t, detail::panelCount(turning(b) * t, 1.0));
}

Eigen::Vector2d ClothoidSpline::spanDisplacement(int span, int panelMultiplier) const {
  if (span < 0 || span >= spanCount() || panelMultiplier < 1) {
    throw G3InputError("ClothoidSpline::spanDisplacement: span index out of range or panelMultiplier < 1");
  }
  const Eigen::Vector3d b = bezier_.segment<3>(2 * span);
  return spanLengths_[span] * detail::integrateTangent(detail::defaultRule(), [&](double u) { return quadraticBezier(b, u); },
                                                       0.0, 1.0, panelMultiplier * detail::panelCount(turning(b), 1.0));
}

CurveSamples ClothoidSpline::sample(int perSpan) const {
  if (perSpan < 1) throw G3InputError("ClothoidSpline::sample needs >= 1 sample per span");
  const int n = spanCount();
  CurveSamples out;
  const int count = n * perSpan + 1;
  out.arcLength.resize(count);
  out.points.resize(count, 2);
  out.tangentAngle.resize(count);
  out.curvature.resize(count);
  out.curvatureDerivative.resize(count);
  int k = 0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d b = bezier_.segment<3>(2 * i);
    const int panels = detail::panelCount(turning(b) / perSpan, 1.0);
    Eigen::Vector2d p = spanStarts_.row(i).transpose();
    for (int j = 0; j < perSpan; ++j, ++k) {
      const double t = static_cast<double>(j) / perSpan;
      if (j > 0) {
        p += spanLengths_[i] * detail::integrateTangent(detail::defaultRule(), [&](double u) { return quadraticBezier(b, u); },
                                                        static_cast<double>(j - 1) / perSpan, t, panels);
      }
      out.arcLength[k] = knots_[i] + t * spanLengths_[i];
      out.points.row(k) = p.transpose();
      out.tangentAngle[k] = quadraticBezier(b, t);
      out.curvature[k] = 2.0 * ((b[1] - b[0]) * (1.0 - t) + (b[2] - b[1]) * t) / spanLengths_[i];
      out.curvatureDerivative[k] = sharpness(i);
    }
  }
  out.arcLength[k] = length();
  out.points.row(k) = spanStarts_.row(n);
  out.tangentAngle[k] = bezier_[2 * n];
  out.curvature[k] = 2.0 * (bezier_[2 * n] - bezier_[2 * n - 1]) / spanLengths_[n - 1];
  out.curvatureDerivative[k] = sharpness(n - 1);
  return out;
}

ClothoidSplineResult solveClothoidSpline(const Eigen::Ref<const Eigen::MatrixX2d>& points, double startCurvature,
                                         double endCurvature, const G3SolverOptions& options) {
  detail::validatePoints(points, "solveClothoidSpline");
  if (!std::isfinite(startCurvature) || !std::isfinite(endCurvature)) {
    throw G3InputError("solveClothoidSpline: end curvatures must be finite");
  }
  const int n = static_cast<int>(points.rows()) - 1;
  const GaussLegendreRule rule = gaussLegendreRule(options.quadratureNodes);
  Eigen::MatrixX2d chords(n, 2);
  for (int i = 0; i < n; ++i) chords.row(i) = points.row(i + 1) - points.row(i);
  const double h = chords.rowwise().norm().maxCoeff();
  Eigen::VectorXd scales = Eigen::VectorXd::Constant(2 * n + 2, h);
  scales.tail(2).setConstant(1.0 / h);

  // Guess: the cubic-spline guess's spans, its G3 angle function sampled at the quadratic
  // Greville abscissae (s_k + s_{k+1}) / 2.
  const CubicSplineInitialGuess cubic = initialGuessFromCubicSpline(points);
  const QuadraticCurvatureSpline guessCurve =
      QuadraticCurvatureSpline::fromStartPoint(points.row(0).transpose(), cubic.spanLengths, cubic.deBoor);
  Eigen::VectorXd v(2 * n + 2);
  v.head(n) = cubic.spanLengths;
  for (int k = -1; k <= n; ++k) {
    const double a = guessCurve.knots()[std::clamp(k, 0, n)];
    const double b = guessCurve.knots()[std::clamp(k + 1, 0, n)];
    v[n + 1 + k] = guessCurve.tangentAngle(0.5 * (a + b));
  }

  auto evaluate = [&](const Eigen::VectorXd& x, Eigen::VectorXd& f, Eigen::MatrixXd* jac) {
    const auto ds = x.head(n);
    const auto e = x.tail(n + 2);
    const Eigen::VectorXd b = quadraticOrdinates(ds, e);
    Eigen::MatrixXd db;
    if (jac) {
      db = quadraticOrdinateJacobian(ds, e);
      jac->setZero(2 * n + 2, 2 * n + 2);
    }
    f.resize(2 * n + 2);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d eta = b.segment<3>(2 * i);
      const QuadMoments m = quadraticSpanMoments(rule, eta, detail::panelCount(turning(eta), options.maxTurnPerPanel));
      f[2 * i] = ds[i] * m[0] - chords(i, 0);
      f[2 * i + 1] = ds[i] * m[1] - chords(i, 1);
      if (jac) {
        auto rx = jac->row(2 * i);
        auto ry = jac->row(2 * i + 1);
        for (int k = 0; k < 3; ++k) {
          rx -= ds[i] * m[3 + 2 * k] * db.row(2 * i + k);
          ry += ds[i] * m[2 + 2 * k] * db.row(2 * i + k);
        }
        rx[i] += m[0];
        ry[i] += m[1];
      }
    }
    // End curvatures 2 (e_0 - e_{-1}) / Delta s_0 and 2 (e_n - e_{n-1}) / Delta s_{n-1}.
    const double k0 = 2.0 * (e[1] - e[0]) / ds[0];
    const double kn = 2.0 * (e[n + 1] - e[n]) / ds[n - 1];
    f[2 * n] = k0 - startCurvature;
    f[2 * n + 1] = kn - endCurvature;
    if (jac) {
      (*jac)(2 * n, n) = -2.0 / ds[0];
      (*jac)(2 * n, n + 1) = 2.0 / ds[0];
      (*jac)(2 * n, 0) = -k0 / ds[0];
      (*jac)(2 * n + 1, 2 * n) = -2.0 / ds[n - 1];
      (*jac)(2 * n + 1, 2 * n + 1) = 2.0 / ds[n - 1];
      (*jac)(2 * n + 1, n - 1) += -kn / ds[n - 1];
    }
  };

  ClothoidSplineResult result;
  Eigen::VectorXd f;
  Eigen::MatrixXd jac;
  evaluate(v, f, nullptr);
  result.residualHistory.push_back(f.norm());
  result.status = G3SolveStatus::MaxIterations;
  for (int it = 1; it <= options.maxIterations; ++it) {
    Eigen::VectorXd scaled = f.cwiseQuotient(scales);
    if (scaled.cwiseAbs().maxCoeff() <= options.tolerance) {
      result.status = G3SolveStatus::Converged;
      break;
    }
    result.iterations = it;
    evaluate(v, f, &jac);
    const Eigen::MatrixXd scaledJac = scales.cwiseInverse().asDiagonal() * jac;
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaledJac);
    if (qr.rank() < 2 * n + 2) {
      result.status = G3SolveStatus::SingularJacobian;
      break;
    }
    const Eigen::VectorXd step = -qr.solve(scaled);
    const double merit2 = scaled.squaredNorm();
    double lambda = 1.0;
    bool accepted = false;
    Eigen::VectorXd trial, trialF;
    while (lambda >= options.lineSearchFloor) {
      trial = v + lambda * step;
      if (trial.allFinite() && (trial.head(n).array() > 0.0).all()) {
        evaluate(trial, trialF, nullptr);
        if (trialF.allFinite() && trialF.cwiseQuotient(scales).squaredNorm() <= (1.0 - 2e-4 * lambda) * merit2) {
          accepted = true;
          break;
        }
      }
      lambda *= 0.5;
    }
    if (!accepted) {
      result.status = scaled.cwiseAbs().maxCoeff() <= 1e2 * options.tolerance ? G3SolveStatus::Converged
                                                                               : G3SolveStatus::LineSearchFailed;
      break;
    }
    v = trial;
    f = trialF;
    result.residualHistory.push_back(f.norm());
  }
  if (result.status == G3SolveStatus::MaxIterations && f.cwiseQuotient(scales).cwiseAbs().maxCoeff() <= options.tolerance) {
    result.status = G3SolveStatus::Converged;
  }
  result.converged = result.status == G3SolveStatus::Converged;
  result.unknowns = v;
  result.residualNorm = f.norm();
  result.scaledResidualInf = f.cwiseQuotient(scales).cwiseAbs().maxCoeff();
  std::ostringstream msg;
  msg << toString(result.status) << " after " << result.iterations << " iterations, scaled residual "
      << result.scaledResidualInf;
  result.message = msg.str();
  if (result.converged) result.curve = ClothoidSpline::fromSpanStarts(points, v.head(n), v.tail(n + 2));
  return result;
}

}  // namespace ffdkit::geometry::g3
