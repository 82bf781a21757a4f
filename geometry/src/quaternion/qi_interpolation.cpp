#include "ffdkit/geometry/quaternion/qi_interpolation.h"

#include <cmath>
#include <sstream>

#include <Eigen/LU>

#include "ffdkit/geometry/quaternion/bernstein.h"
#include "ffdkit/geometry/quaternion/quaternion_error.h"
#include "ffdkit/geometry/quaternion/tangent_integration.h"

namespace ffdkit::geometry::quaternion {

Eigen::Vector3d circleTangentAtFirst(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d u = b - a;
  const Eigen::Vector3d v = c - a;
  return (v.squaredNorm() * u - u.squaredNorm() * v).normalized();
}

Eigen::MatrixX3d cubicSplineDerivatives(const Eigen::MatrixX3d& points, bool natural, const Eigen::Vector3d& d0,
                                        const Eigen::Vector3d& dn) {
  const int m = static_cast<int>(points.rows());
  if (m < 2) {
    std::ostringstream msg;
    msg << "cubicSplineDerivatives: expected at least 2 points, got " << m;
    throw QuaternionCurveError(msg.str());
  }
  // Tridiagonal system of the C2 conditions in the derivatives (uniform knots), Thomas algorithm.
  Eigen::VectorXd lower = Eigen::VectorXd::Zero(m);
  Eigen::VectorXd diag = Eigen::VectorXd::Zero(m);
  Eigen::VectorXd upper = Eigen::VectorXd::Zero(m);
  Eigen::MatrixX3d rhs(m, 3);
  for (int i = 1; i + 1 < m; ++i) {
    lower[i] = 1.0;
    diag[i] = 4.0;
    upper[i] = 1.0;
    rhs.row(i) = 3.0 * (points.row(i + 1) - points.row(i - 1));
  }
  if (natural) {
    diag[0] = 2.0;
    upper[0] = 1.0;
    rhs.row(0) = 3.0 * (points.row(1) - points.row(0));
    lower[m - 1] = 1.0;
    diag[m - 1] = 2.0;
    rhs.row(m - 1) = 3.0 * (points.row(m - 1) - points.row(m - 2));
  } else {
    diag[0] = 1.0;
    rhs.row(0) = d0.transpose();
    diag[m - 1] = 1.0;
    rhs.row(m - 1) = dn.transpose();
  }
  for (int i = 1; i < m; ++i) {
    const double w = lower[i] / diag[i - 1];
    diag[i] -= w * upper[i - 1];
    rhs.row(i) -= w * rhs.row(i - 1);
  }
  Eigen::MatrixX3d d(m, 3);
  d.row(m - 1) = rhs.row(m - 1) / diag[m - 1];
  for (int i = m - 2; i >= 0; --i) {
    d.row(i) = (rhs.row(i) - upper[i] * d.row(i + 1)) / diag[i];
  }
  return d;
}

namespace {

// Variable layout of Miura 1998, sec. 5: x = [a01, b01, (ai0, bi0, ai1, bi1)_{i=1..n-1},
// l_0..l_{n-1}].
struct Layout {
  int n;
  int size() const { return 5 * n - 2; }
  int alpha(int i, int j) const {
    if (j == 0) return i == 0 ? -1 : 2 + 4 * (i - 1);
    if (j == 1) return i == 0 ? 0 : 2 + 4 * (i - 1) + 2;
    return i == n - 1 ? -1 : alpha(i + 1, 0);
  }
  int beta(int i, int j) const {
    const int a = alpha(i, j);
    return a < 0 ? -1 : a + 1;
  }
  int length(int i) const { return 2 + 4 * (n - 1) + i; }
};

struct Unpacked {
  std::vector<std::array<double, 3>> a, b;
  std::vector<double> l;
};

Unpacked unpack(const Layout& lay, const Eigen::VectorXd& x, QiAngles start, QiAngles end) {
  Unpacked u;
  u.a.resize(lay.n);
  u.b.resize(lay.n);
  u.l.resize(lay.n);
  for (int i = 0; i < lay.n; ++i) {
    for (int j = 0; j < 3; ++j) {
      const int ia = lay.alpha(i, j);
      const bool atStart = (i == 0 && j == 0);
      u.a[i][j] = ia >= 0 ? x[ia] : (atStart ? start.alpha : end.alpha);
      u.b[i][j] = ia >= 0 ? x[lay.beta(i, j)] : (atStart ? start.beta : end.beta);
    }
    u.l[i] = x[lay.length(i)];
  }
  return u;
}

struct System {
  Eigen::VectorXd f;
  Eigen::MatrixXd jacobian;
};

// Residual of eqs. (60)-(62) and, when wanted, its Jacobian (Miura 1998, sec. 5) from one Simpson
// sweep.
System evaluate(const Layout& lay, const Eigen::VectorXd& x, QiAngles start, QiAngles end, const Eigen::MatrixX3d& q,
                int intervals, bool wantJacobian) {
  const Unpacked u = unpack(lay, x, start, end);
  const int n = lay.n;
  System sys;
  sys.f.resize(lay.size());
  if (wantJacobian) sys.jacobian = Eigen::MatrixXd::Zero(lay.size(), lay.size());
  const double h = 1.0 / intervals;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d integral = Eigen::Vector3d::Zero();
    Eigen::Matrix<double, 3, 3> dA = Eigen::Matrix3d::Zero();  // column j: int B_j dT/dalpha
    Eigen::Matrix<double, 3, 3> dB = Eigen::Matrix3d::Zero();
    for (int k = 0; k <= intervals; ++k) {
      const double t = k * h;
      const double w = (k == 0 || k == intervals) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
      const double s = 1.0 - t;
      const double basis[3] = {s * s, 2.0 * s * t, t * t};
      const double al = u.a[i][0] * basis[0] + u.a[i][1] * basis[1] + u.a[i][2] * basis[2];
      const double be = u.b[i][0] * basis[0] + u.b[i][1] * basis[1] + u.b[i][2] * basis[2];
      const double ca = std::cos(al), sa = std::sin(al), c2 = std::cos(2.0 * be), s2 = std::sin(2.0 * be);
      integral += w * Eigen::Vector3d(c2, sa * s2, -ca * s2);
      if (wantJacobian) {
        const Eigen::Vector3d ta(0.0, ca * s2, sa * s2);
        const Eigen::Vector3d tb(-2.0 * s2, 2.0 * sa * c2, -2.0 * ca * c2);
        for (int j = 0; j < 3; ++j) {
          dA.col(j) += (w * basis[j]) * ta;
          dB.col(j) += (w * basis[j]) * tb;
        }
      }
    }
    integral *= h / 3.0;
    sys.f.segment<3>(3 * i) = u.l[i] * integral - (q.row(i + 1) - q.row(i)).transpose();
    if (wantJacobian) {
      sys.jacobian.block<3, 1>(3 * i, lay.length(i)) = integral;
      for (int j = 0; j < 3; ++j) {
        const int ia = lay.alpha(i, j);
        if (ia < 0) continue;
        sys.jacobian.block<3, 1>(3 * i, ia) += (u.l[i] * h / 3.0) * dA.col(j);
        sys.jacobian.block<3, 1>(3 * i, lay.beta(i, j)) += (u.l[i] * h / 3.0) * dB.col(j);
      }
    }
  }
  for (int i = 0; i + 1 < n; ++i) {
    const double li = u.l[i], lj = u.l[i + 1];
    for (int c = 0; c < 2; ++c) {
      const auto& v = c == 0 ? u.a : u.b;
      const int row = 3 * n + 2 * i + c;
      sys.f[row] = (v[i + 1][1] - v[i + 1][0]) / lj - (v[i][2] - v[i][1]) / li;
      if (wantJacobian) {
        const auto var = [&](int seg, int j) { return c == 0 ? lay.alpha(seg, j) : lay.beta(seg, j); };
        sys.jacobian(row, var(i, 1)) += 1.0 / li;
        sys.jacobian(row, var(i + 1, 0)) += -1.0 / lj - 1.0 / li;
        sys.jacobian(row, var(i + 1, 1)) += 1.0 / lj;
        sys.jacobian(row, lay.length(i)) += (v[i][2] - v[i][1]) / (li * li);
        sys.jacobian(row, lay.length(i + 1)) += -(v[i + 1][1] - v[i + 1][0]) / (lj * lj);
      }
    }
  }
  return sys;
}

bool lengthsPositive(const Layout& lay, const Eigen::VectorXd& x) {
  for (int i = 0; i < lay.n; ++i) {
    if (!(x[lay.length(i)] > 0.0)) return false;
  }
  return x.allFinite();
}

}  // namespace

QiInterpolationSystem qiInterpolationSystem(const Eigen::MatrixX3d& points, const Eigen::VectorXd& unknowns,
                                            QiAngles start, QiAngles end, int simpsonIntervals) {
  const int n = static_cast<int>(points.rows()) - 1;
  if (n < 1 || unknowns.size() != 5 * n - 2 || simpsonIntervals <= 0 || simpsonIntervals % 2 != 0) {
    std::ostringstream msg;
    msg << "qiInterpolationSystem: expected >= 2 points, 5n-2 = " << 5 * n - 2 << " unknowns and an even Simpson count, got "
        << points.rows() << " points, " << unknowns.size() << " unknowns, " << simpsonIntervals << " intervals";
    throw QuaternionCurveError(msg.str());
  }
  System sys = evaluate(Layout{n}, unknowns, start, end, points, simpsonIntervals, true);
  return {std::move(sys.f), std::move(sys.jacobian)};
}

InterpolationResult interpolateQi(const Eigen::MatrixX3d& points, const InterpolationOptions& options) {
  const int count = static_cast<int>(points.rows());
  const int n = count - 1;
  if (count < 2) {
    std::ostringstream msg;
    msg << "interpolateQi: expected at least 2 points, got " << count;
    throw QuaternionCurveError(msg.str());
  }
  if (options.endRule == EndTangentRule::Circle3 && count < 3) {
    std::ostringstream msg;
    msg << "interpolateQi: the Circle3 end rule needs at least 3 points, got " << count << " (use the User rule)";
    throw QuaternionCurveError(msg.str());
  }
  if (!points.allFinite()) {
    throw QuaternionCurveError("interpolateQi: expected finite point coordinates, got NaN or infinity");
  }
  if (options.simpsonIntervals <= 0 || options.simpsonIntervals % 2 != 0) {
    std::ostringstream msg;
    msg << "interpolateQi: expected a positive even simpsonIntervals, got " << options.simpsonIntervals;
    throw QuaternionCurveError(msg.str());
  }
  double chordSum = 0.0;
  for (int i = 0; i < n; ++i) chordSum += (points.row(i + 1) - points.row(i)).norm();
  const double meanChord = chordSum / n;
  for (int i = 0; i < n; ++i) {
    if ((points.row(i + 1) - points.row(i)).norm() <= 1e-12 * meanChord) {
      std::ostringstream msg;
      msg << "interpolateQi: expected distinct consecutive points, got points " << i << " and " << i + 1
          << " coinciding at (" << points.row(i) << ")";
      throw QuaternionCurveError(msg.str());
    }
  }
  // Normalised data: P_0 at the origin, mean chord 1 (the method is scale-invariant,
  // Miura 1998, sec. 5.1).
  Eigen::MatrixX3d q = (points.rowwise() - points.row(0)) / meanChord;

  Eigen::Vector3d ts = Eigen::Vector3d::UnitX();
  Eigen::Vector3d te = Eigen::Vector3d::UnitX();
  switch (options.endRule) {
    case EndTangentRule::NaturalSpline: {
      const Eigen::MatrixX3d d = cubicSplineDerivatives(q, true);
      ts = d.row(0).transpose().normalized();
      te = d.row(n).transpose().normalized();
      break;
    }
    case EndTangentRule::Circle3:
      ts = circleTangentAtFirst(q.row(0), q.row(1), q.row(2));
      te = -circleTangentAtFirst(q.row(n), q.row(n - 1), q.row(n - 2));
      break;
    case EndTangentRule::User:
      if (!(options.startTangent.norm() > 0.0) || !(options.endTangent.norm() > 0.0) ||
          !options.startTangent.allFinite() || !options.endTangent.allFinite()) {
        std::ostringstream msg;
        msg << "interpolateQi: the User end rule expects non-zero finite tangents, got start ("
            << options.startTangent.transpose() << ") and end (" << options.endTangent.transpose() << ")";
        throw QuaternionCurveError(msg.str());
      }
      ts = options.startTangent.normalized();
      te = options.endTangent.normalized();
      break;
  }

  // Initial guess from the uniform-knot cubic spline (Miura 1998, sec. 5.2).
  const bool natural = options.endRule == EndTangentRule::NaturalSpline;
  const Eigen::MatrixX3d d = cubicSplineDerivatives(q, natural, ts * (q.row(1) - q.row(0)).norm(),
                                                    te * (q.row(n) - q.row(n - 1)).norm());
  std::vector<Eigen::Vector3d> chain;  // joint 0, mid 0, joint 1, ..., joint n
  for (int i = 0; i <= n; ++i) {
    Eigen::Vector3d joint = d.row(i).transpose();
    if (i == 0) joint = ts;
    if (i == n) joint = te;
    if (joint.norm() < 1e-14) joint = (q.row(std::min(i + 1, n)) - q.row(std::max(i - 1, 0))).transpose();
    chain.push_back(joint.normalized());
    if (i < n) {
      Eigen::Vector3d mid = (1.5 * (q.row(i + 1) - q.row(i)) - 0.25 * (d.row(i) + d.row(i + 1))).transpose();
      if (mid.norm() < 1e-14) mid = (q.row(i + 1) - q.row(i)).transpose();
      chain.push_back(mid.normalized());
    }
  }
  std::vector<QiAngles> ang;
  for (std::size_t k = 0; k < chain.size(); ++k) {
    const QiAngles raw = qiAnglesFromTangent(chain[k]);
    ang.push_back(k == 0 ? raw : nearestEquivalentAngles(raw, ang.back(), options.equivalence));
  }
  const QiAngles startAngles = ang.front();
  const QiAngles endAngles = ang.back();
  const Layout lay{n};
  Eigen::VectorXd x(lay.size());
  for (int i = 0; i < n; ++i) {
    const QiAngles a0 = ang[2 * i], am = ang[2 * i + 1], a2 = ang[2 * i + 2];
    const double a1 = 2.0 * am.alpha - 0.5 * (a0.alpha + a2.alpha);
    const double b1 = 2.0 * am.beta - 0.5 * (a0.beta + a2.beta);
    x[lay.alpha(i, 1)] = a1;
    x[lay.beta(i, 1)] = b1;
    if (i > 0) {
      x[lay.alpha(i, 0)] = a0.alpha;
      x[lay.beta(i, 0)] = a0.beta;
    }
    const Eigen::Vector3d pi = q.row(i).transpose(), pj = q.row(i + 1).transpose();
    const Eigen::Vector3d di = d.row(i).transpose(), dj = d.row(i + 1).transpose();
    const auto speed = [&](double t) {
      const double h00 = 6 * t * t - 6 * t, h10 = 3 * t * t - 4 * t + 1, h11 = 3 * t * t - 2 * t;
      return Eigen::Vector3d::Constant(((h00 * pi - h00 * pj) + h10 * di + h11 * dj).norm());
    };
    x[lay.length(i)] = integrateSimpson(speed, 0.0, 1.0, 100)[0];
  }

  std::vector<double> history;
  bool converged = false;
  std::string message;
  int iterations = 0;
  System sys = evaluate(lay, x, startAngles, endAngles, q, options.simpsonIntervals, true);
  double r2 = sys.f.squaredNorm();
  history.push_back(r2);
  const auto done = [&](const Eigen::VectorXd& f) {
    return options.stopMode == StopMode::Paper ? f.squaredNorm() < options.paperEpsilon
                                               : f.lpNorm<Eigen::Infinity>() < options.strictTolerance;
  };
  converged = done(sys.f);
  while (!converged && iterations < options.maxIterations) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(sys.jacobian);
    const Eigen::VectorXd step = lu.solve(-sys.f);
    if (!step.allFinite()) {
      message = "singular Jacobian at iteration " + std::to_string(iterations);
      break;
    }
    double scale = 1.0;
    bool accepted = false;
    Eigen::VectorXd trial;
    System trialSys;
    for (int halving = 0; halving <= (options.pureNewton ? 0 : 30); ++halving, scale *= 0.5) {
      trial = x + scale * step;
      if (!lengthsPositive(lay, trial)) continue;
      trialSys = evaluate(lay, trial, startAngles, endAngles, q, options.simpsonIntervals, true);
      if (!trialSys.f.allFinite()) continue;
      if (options.pureNewton || trialSys.f.squaredNorm() < r2) {
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      // At the round-off floor no step can decrease |f| any more; that is convergence, not failure.
      if (options.stopMode == StopMode::Strict && sys.f.lpNorm<Eigen::Infinity>() < 1e3 * options.strictTolerance) {
        converged = true;
      } else {
        message = options.pureNewton ? "Newton step made a segment length non-positive (pure Newton, no safeguard)"
                                     : "no step decreased the residual after 30 halvings";
      }
      break;
    }
    x = trial;
    sys = std::move(trialSys);
    r2 = sys.f.squaredNorm();
    history.push_back(r2);
    ++iterations;
    converged = done(sys.f);
  }
  if (!converged && message.empty()) {
    message = "no convergence in " + std::to_string(options.maxIterations) + " iterations, |f|^2 = " +
              std::to_string(r2);
  }

  const Unpacked u = unpack(lay, x, startAngles, endAngles);
  std::vector<BezierQiSegment> segments;
  for (int i = 0; i < n; ++i) {
    segments.emplace_back(points.row(i).transpose(), u.l[i] * meanChord, u.a[i], u.b[i], options.simpsonIntervals);
  }
  InterpolationResult result(QiSpline(std::move(segments), SegmentPlacement::Anchored));
  result.converged = converged;
  result.iterations = iterations;
  result.residual = r2;
  result.residualHistory = std::move(history);
  result.startTangent = ts;
  result.endTangent = te;
  result.meanChord = meanChord;
  result.message = message;
  return result;
}

}  // namespace ffdkit::geometry::quaternion
