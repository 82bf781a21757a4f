#include "ffdkit/geometry/quaternion/qi_fitting.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include <Eigen/Cholesky>

#include "ffdkit/geometry/gauss_legendre.h"
#include "ffdkit/geometry/quaternion/bernstein.h"
#include "ffdkit/geometry/quaternion/quaternion_error.h"
#include "ffdkit/geometry/quaternion/tangent_integration.h"
#include "ffdkit/geometry/quaternion/unit_quaternion.h"

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
    if (!(total > 0.0)) {
      std::ostringstream msg;
      msg << "chordLengthParameters: segment " << j << " (points " << breaks[j] << ".." << breaks[j + 1]
          << ") has zero chord length";
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

// Left Jacobian of SO(3) at the rotation vector theta: Exp(theta + d) = Exp(J_l d) Exp(theta).
Eigen::Matrix3d leftJacobian(const Eigen::Vector3d& theta) {
  const double a = theta.norm();
  Eigen::Matrix3d k;
  k << 0, -theta.z(), theta.y(), theta.z(), 0, -theta.x(), -theta.y(), theta.x(), 0;
  if (a < 1e-6) return Eigen::Matrix3d::Identity() + 0.5 * k + (1.0 / 6.0) * k * k;
  return Eigen::Matrix3d::Identity() + ((1.0 - std::cos(a)) / (a * a)) * k + ((a - std::sin(a)) / (a * a * a)) * k * k;
}

// Cumulative composite Gauss-Legendre of a 3 x cols matrix function, with the same panels as
// cumulativeGaussLegendre (union of the parameters and a uniform grid).
template <class F>
std::vector<Eigen::MatrixXd> cumulativeMatrixIntegral(F&& f, const Eigen::VectorXd& params, int cols, int order,
                                                      int minPanels) {
  // Grown on demand: a fixed 65-slot table was indexed past its end for orders above 64.
  thread_local std::vector<GaussLegendreRule> rules;
  if (order < 1) throw QuaternionCurveError("fitQiChain: quadrature order must be >= 1, got " + std::to_string(order));
  if (static_cast<std::size_t>(order) >= rules.size()) rules.resize(static_cast<std::size_t>(order) + 1);
  if (rules[order].nodes.size() != order) rules[order] = gaussLegendreRule(order);
  const GaussLegendreRule& rule = rules[order];
  std::vector<double> breaks(params.data(), params.data() + params.size());
  for (int p = 0; p <= minPanels; ++p) breaks.push_back(static_cast<double>(p) / minPanels);
  std::sort(breaks.begin(), breaks.end());
  std::vector<Eigen::MatrixXd> out;
  out.reserve(params.size());
  Eigen::MatrixXd running = Eigen::MatrixXd::Zero(3, cols);
  Eigen::Matrix<double, 3, Eigen::Dynamic> m(3, cols);
  double at = 0.0;
  std::size_t b = 0;
  for (Eigen::Index k = 0; k < params.size(); ++k) {
    while (b < breaks.size() && breaks[b] <= params[k]) {
      if (breaks[b] > at) {
        const double half = 0.5 * (breaks[b] - at), mid = 0.5 * (breaks[b] + at);
        for (Eigen::Index g = 0; g < rule.nodes.size(); ++g) {
          f(mid + half * rule.nodes[g], m);
          running += (rule.weights[g] * half) * m;
        }
        at = breaks[b];
      }
      ++b;
    }
    out.push_back(running);
  }
  return out;
}

// Uniform cubic B-spline interpolating the points at x = 0..N-1 with the paper's end condition
// Q_0 = Q_1, Q_{N+1} = Q_N (seed 003 eqs. (11)-(12)), solved directly instead of by Gauss-Seidel
// (eqs. (14)-(16) converge to the same controls; spec §7 A14).
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

// The optimisation problem: design vector layout, residual with per-segment restart.
struct Problem {
  const Eigen::MatrixX3d& points;
  std::vector<int> breaks;
  Eigen::VectorXd u;
  int segments;
  int degree;
  bool planar;
  ProductForm form;
  QiQuadrature quadrature;
  Eigen::Vector3d start;
  Eigen::Quaterniond baseQ00;
  Eigen::Vector3d freeAxis1, freeAxis2;  // start-tangent directions (Free mode)
  int startVars;                         // 0, 1 (planar Free) or 2 (spatial Free)
  int omegaDim() const { return planar ? 1 : 3; }
  int segmentVars() const { return degree * omegaDim() + 1; }
  int offset(int seg) const { return startVars + seg * segmentVars(); }
  int size() const { return offset(segments); }
  int firstPoint(int seg) const { return breaks[seg]; }
  int lastPoint(int seg) const { return seg + 1 == segments ? breaks[seg + 1] : breaks[seg + 1] - 1; }

  std::vector<Eigen::Vector3d> omegas(const Eigen::VectorXd& x, int seg) const {
    std::vector<Eigen::Vector3d> w(degree);
    for (int j = 0; j < degree; ++j) {
      w[j] = planar ? Eigen::Vector3d(0.0, 0.0, x[offset(seg) + j])
                    : Eigen::Vector3d(x.segment<3>(offset(seg) + 3 * j));
    }
    return w;
  }
  double length(const Eigen::VectorXd& x, int seg) const { return std::exp(x[offset(seg + 1) - 1]); }
  Eigen::Quaterniond q00(const Eigen::VectorXd& x) const {
    if (startVars == 0) return baseQ00;
    const Eigen::Vector3d eta = startVars == 1 ? Eigen::Vector3d(x[0] * freeAxis1) : Eigen::Vector3d(x[0] * freeAxis1 + x[1] * freeAxis2);
    return (quaternionExp(eta) * baseQ00).normalized();
  }

  // Segment start states (position, orientation), size segments + 1.
  struct State {
    std::vector<Eigen::Vector3d> p;
    std::vector<Eigen::Quaterniond> q;
  };

  // Residual rows of points from segment `from` on, starting from the given state; fills the state
  // for later segments. r: 3 #P (rows of earlier segments are left untouched).
  void evaluateFrom(const Eigen::VectorXd& x, int from, State& st, Eigen::VectorXd& r) const {
    for (int seg = from; seg < segments; ++seg) {
      const CumulativeBezierQuaternion rot(st.q[seg], omegas(x, seg), form);
      const double l = length(x, seg);
      const int lo = firstPoint(seg), hi = lastPoint(seg);
      Eigen::VectorXd params(hi - lo + 2);
      for (int i = lo; i <= hi; ++i) params[i - lo] = std::clamp(u[i] - seg, 0.0, 1.0);
      params[hi - lo + 1] = 1.0;
      const Eigen::MatrixX3d integral = cumulativeGaussLegendre(
          [&rot](double t) { return rotateFixedVector(rot.value(t).normalized(), Eigen::Vector3d::UnitX()); }, params,
          quadrature.order, quadrature.minPanels);
      for (int i = lo; i <= hi; ++i) {
        r.segment<3>(3 * i) = st.p[seg] + l * integral.row(i - lo).transpose() - points.row(i).transpose();
      }
      st.p[seg + 1] = st.p[seg] + l * integral.row(hi - lo + 1).transpose();
      st.q[seg + 1] = rot.value(1.0).normalized();
    }
  }

  Eigen::VectorXd residual(const Eigen::VectorXd& x, State& st) const {
    st.p.assign(segments + 1, start);
    st.q.assign(segments + 1, q00(x));
    Eigen::VectorXd r(3 * points.rows());
    evaluateFrom(x, 0, st, r);
    return r;
  }


  // Analytic Jacobian from one sweep per segment. A perturbation of w_j is a world rotation
  // dPhi = W_j J_l(2 b_j w_j) 2 b_j dw of the frame (W_j = R(E_k..E_{j+1}) in form A,
  // R(q_0 E_1..E_{j-1}) in form B), so dt = dPhi x t; upstream variables reach a segment as a
  // start translation dP and a start rotation dPhi that the segment turns by R(E_k..E_1) (form A)
  // or carries unchanged (form B). Integrals use the residual's quadrature nodes.
  void analyticJacobian(const Eigen::VectorXd& x, const State& st, Eigen::MatrixXd& j) const {
    const int nv = size();
    j.setZero(3 * points.rows(), nv);
    Eigen::MatrixXd dp = Eigen::MatrixXd::Zero(3, nv);
    Eigen::MatrixXd dphi = Eigen::MatrixXd::Zero(3, nv);
    if (startVars > 0) {
      const Eigen::Vector3d eta = startVars == 1 ? Eigen::Vector3d(x[0] * freeAxis1)
                                                 : Eigen::Vector3d(x[0] * freeAxis1 + x[1] * freeAxis2);
      const Eigen::Matrix3d jl = leftJacobian(2.0 * eta);
      dphi.col(0) = 2.0 * jl * freeAxis1;
      if (startVars == 2) dphi.col(1) = 2.0 * jl * freeAxis2;
    }
    const int cols = 3 * degree + 4;  // [A_1 .. A_k | G | t]
    for (int seg = 0; seg < segments; ++seg) {
      const std::vector<Eigen::Vector3d> w = omegas(x, seg);
      const double l = length(x, seg);
      const Eigen::Quaterniond q0 = st.q[seg];
      // Scratch reused by every quadrature node.
      std::vector<Eigen::Quaterniond> e(degree + 1), frame(degree + 1);
      std::vector<double> b(degree + 1);
      const auto integrand = [&](double t, Eigen::Matrix<double, 3, Eigen::Dynamic>& m) {
        for (int jj = 1; jj <= degree; ++jj) {
          b[jj] = cumulativeBernstein(degree, jj, t);
          e[jj] = quaternionExp(w[jj - 1] * b[jj]);
        }
        Eigen::Quaterniond full = Eigen::Quaterniond::Identity();  // E_k..E_1 (A) or E_1..E_k (B); W_j in frame
        if (form == ProductForm::Global) {
          Eigen::Quaterniond suffix = Eigen::Quaterniond::Identity();
          for (int jj = degree; jj >= 1; --jj) {
            frame[jj] = suffix;
            suffix = suffix * e[jj];
          }
          full = suffix;
        } else {
          Eigen::Quaterniond prefix = q0;
          for (int jj = 1; jj <= degree; ++jj) {
            frame[jj] = prefix;
            prefix = prefix * e[jj];
          }
          full = q0.conjugate() * prefix;
        }
        const Eigen::Quaterniond q = form == ProductForm::Global ? Eigen::Quaterniond(full * q0) : Eigen::Quaterniond(q0 * full);
        const Eigen::Vector3d tan = rotateFixedVector(q.normalized(), Eigen::Vector3d::UnitX());
        Eigen::Matrix3d cross;
        cross << 0, tan.z(), -tan.y(), -tan.z(), 0, tan.x(), tan.y(), -tan.x(), 0;  // -[t]x
        for (int jj = 1; jj <= degree; ++jj) {
          m.block<3, 3>(0, 3 * (jj - 1)) =
              cross * frame[jj].normalized().toRotationMatrix() * leftJacobian(2.0 * b[jj] * w[jj - 1]) * (2.0 * b[jj]);
        }
        m.block<3, 3>(0, 3 * degree) =
            form == ProductForm::Global ? Eigen::Matrix3d(cross * full.normalized().toRotationMatrix()) : cross;
        m.col(3 * degree + 3) = tan;
      };
      const int lo = firstPoint(seg), hi = lastPoint(seg);
      Eigen::VectorXd params(hi - lo + 2);
      for (int i = lo; i <= hi; ++i) params[i - lo] = std::clamp(u[i] - seg, 0.0, 1.0);
      params[hi - lo + 1] = 1.0;
      const std::vector<Eigen::MatrixXd> cum = cumulativeMatrixIntegral(integrand, params, cols, quadrature.order,
                                                                        quadrature.minPanels);
      const int off = offset(seg);
      const auto own = [&](const Eigen::MatrixXd& c, Eigen::Block<Eigen::MatrixXd> target) {
        for (int jj = 0; jj < degree; ++jj) {
          const Eigen::Matrix3d a = l * c.block(0, 3 * jj, 3, 3);
          if (planar) {
            target.col(off + jj) = a.col(2);
          } else {
            target.block(0, off + 3 * jj, 3, 3) = a;
          }
        }
        target.col(off + segmentVars() - 1) = l * c.col(3 * degree + 3);
      };
      for (int i = lo; i <= hi; ++i) {
        const Eigen::MatrixXd& c = cum[i - lo];
        auto rows = j.middleRows(3 * i, 3);
        const Eigen::Matrix3d g = l * c.block<3, 3>(0, 3 * degree);
        rows = dp + g.lazyProduct(dphi);  // 3 x 3 times 3 x nv: a plain loop beats GEMM here
        own(c, rows);
      }
      const Eigen::MatrixXd& end = cum.back();
      const Eigen::Matrix3d gEnd = l * end.block<3, 3>(0, 3 * degree);
      dp += gEnd.lazyProduct(dphi);
      auto dpBlock = dp.middleRows(0, 3);
      own(end, dpBlock);
      if (form == ProductForm::Global) {
        Eigen::Quaterniond f1 = Eigen::Quaterniond::Identity();
        for (int jj = 1; jj <= degree; ++jj) f1 = quaternionExp(w[jj - 1]) * f1;
        dphi = f1.normalized().toRotationMatrix() * dphi;
        Eigen::Quaterniond suffix = Eigen::Quaterniond::Identity();
        for (int jj = degree; jj >= 1; --jj) {
          const Eigen::Matrix3d d = suffix.normalized().toRotationMatrix() * leftJacobian(2.0 * w[jj - 1]) * 2.0;
          if (planar) {
            dphi.col(off + jj - 1) = d.col(2);
          } else {
            dphi.block(0, off + 3 * (jj - 1), 3, 3) = d;
          }
          suffix = suffix * quaternionExp(w[jj - 1]);
        }
      } else {
        Eigen::Quaterniond prefix = q0;
        for (int jj = 1; jj <= degree; ++jj) {
          const Eigen::Matrix3d d = prefix.normalized().toRotationMatrix() * leftJacobian(2.0 * w[jj - 1]) * 2.0;
          if (planar) {
            dphi.col(off + jj - 1) = d.col(2);
          } else {
            dphi.block(0, off + 3 * (jj - 1), 3, 3) = d;
          }
          prefix = prefix * quaternionExp(w[jj - 1]);
        }
      }
    }
  }

  // Forward-difference Jacobian; a column of segment seg only recomputes segments >= seg
  // (block lower-triangular structure, spec §3.5). Returns the number of partial evaluations.
  int jacobian(const Eigen::VectorXd& x, const Eigen::VectorXd& r, const State& st, Eigen::MatrixXd& j) const {
    const int nv = size();
    j.setZero(r.size(), nv);
    const double eps = std::sqrt(std::numeric_limits<double>::epsilon());
    State work = st;
    Eigen::VectorXd rp = r;
    for (int c = 0; c < nv; ++c) {
      const int seg = c < startVars ? 0 : (c - startVars) / segmentVars();
      Eigen::VectorXd xp = x;
      const double h = eps * std::max(std::abs(x[c]), 1.0);
      xp[c] += h;
      work = st;
      if (c < startVars) work.q[0] = q00(xp);
      evaluateFrom(xp, seg, work, rp);
      const int row0 = 3 * firstPoint(seg);
      j.col(c).tail(r.size() - row0) = (rp.tail(r.size() - row0) - r.tail(r.size() - row0)) / h;
    }
    return nv;
  }
};

QiChain buildChain(const Problem& pb, const Eigen::VectorXd& x) {
  QiChain chain(pb.start, pb.q00(x), pb.form, Eigen::Vector3d::UnitX(), pb.quadrature);
  for (int seg = 0; seg < pb.segments; ++seg) chain.appendSegment(pb.omegas(x, seg), pb.length(x, seg));
  return chain;
}

}  // namespace

FitResult fitQiChain(const Eigen::MatrixX3d& points, const std::vector<int>& breaks, const FitOptions& options,
                     const Eigen::VectorXd* userParameters) {
  if (options.degree < 1) {
    std::ostringstream msg;
    msg << "fitQiChain: expected degree >= 1, got " << options.degree;
    throw QuaternionCurveError(msg.str());
  }
  if (!points.allFinite()) throw QuaternionCurveError("fitQiChain: expected finite point coordinates");
  Eigen::VectorXd u = chordLengthParameters(points, breaks);
  const int segments = static_cast<int>(breaks.size()) - 1;
  if (userParameters != nullptr) {
    if (userParameters->size() != points.rows()) {
      std::ostringstream msg;
      msg << "fitQiChain: expected " << points.rows() << " user parameters, got " << userParameters->size();
      throw QuaternionCurveError(msg.str());
    }
    u = *userParameters;
    for (int j = 0; j <= segments; ++j) {
      if (std::abs(u[breaks[j]] - j) > 1e-12) {
        std::ostringstream msg;
        msg << "fitQiChain: expected user parameter " << j << " at break point " << breaks[j] << ", got "
            << u[breaks[j]];
        throw QuaternionCurveError(msg.str());
      }
    }
  }
  const double zSpread = points.col(2).maxCoeff() - points.col(2).minCoeff();
  const double extent = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
  const bool flat = zSpread <= 1e-12 * std::max(extent, 1e-300);
  if (options.dimension == FitDimension::Planar && !flat) {
    std::ostringstream msg;
    msg << "fitQiChain: Planar fitting expects all points at one z, got a z spread of " << zSpread;
    throw QuaternionCurveError(msg.str());
  }
  const bool planar = options.dimension == FitDimension::Planar || (options.dimension == FitDimension::Auto && flat);

  // The baseline: least-squares cubic at the same breaks and u_i (spec §3.7). It is also the default
  // initial curve (spec §3.6 (b)); the paper preset interpolates instead (§3.6 (a)).
  UniformCubicBSpline baseline = fitLeastSquaresCubicBSpline(points, u, segments);
  const bool interpolating = options.initialCurve == FitInitialCurve::InterpolatingCubic;
  const UniformCubicBSpline init = interpolating ? interpolatingCubicBSpline(points) : baseline;
  // Initial-curve parameter x of the QI global parameter: x = u for the LSQ cubic; piecewise linear
  // in the data parameters for the interpolating cubic, whose data point m sits at x = m.
  const auto toInit = [&](double g) {
    if (!interpolating) return g;
    const Eigen::Index n = u.size();
    Eigen::Index m = std::upper_bound(u.data(), u.data() + n, g) - u.data() - 1;
    m = std::clamp<Eigen::Index>(m, 0, n - 2);
    return static_cast<double>(m) + (g - u[m]) / (u[m + 1] - u[m]);
  };
  const int k = options.degree;
  const auto direction = [&](double g) {
    Eigen::Vector3d d = init.derivative(toInit(g), 1);
    if (planar) d.z() = 0.0;
    return d.normalized();
  };
  Eigen::Vector3d t0 = direction(0.0);
  if (options.startTangent == StartTangentMode::Given) {
    if (!(options.givenStartTangent.norm() > 0.0)) {
      throw QuaternionCurveError("fitQiChain: Given start tangent mode expects a non-zero givenStartTangent");
    }
    t0 = options.givenStartTangent.normalized();
  }

  Problem pb{points, breaks, u, segments, k, planar, options.form, options.quadrature,
             points.row(0).transpose(), minimalRotation(Eigen::Vector3d::UnitX(), t0, Eigen::Vector3d::UnitZ()),
             Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY(), 0};
  if (options.startTangent == StartTangentMode::Free) {
    pb.startVars = planar ? 1 : 2;
    pb.freeAxis1 = planar ? Eigen::Vector3d::UnitZ() : t0.unitOrthogonal();
    pb.freeAxis2 = t0.cross(pb.freeAxis1).normalized();
  }
  Eigen::VectorXd x = Eigen::VectorXd::Zero(pb.size());
  const GaussLegendreRule rule = gaussLegendreRule(8);
  for (int seg = 0; seg < segments; ++seg) {
    Eigen::Vector3d prev = seg == 0 ? t0 : direction(seg);
    for (int j = 1; j <= k; ++j) {
      const Eigen::Vector3d next = direction(seg + static_cast<double>(j) / k);
      const Eigen::Vector3d w = halfAngleOmega(prev, next, planar);
      if (planar) {
        x[pb.offset(seg) + j - 1] = w.z();
      } else {
        x.segment<3>(pb.offset(seg) + 3 * (j - 1)) = w;
      }
      prev = next;
    }
    // Eq. (18) read as the arc length of the initial curve over the segment (spec §7 A12).
    double l = 0.0;
    const double a = toInit(seg), b = toInit(seg + 1.0);
    const int panels = std::max(4, static_cast<int>(std::ceil(b - a)) * 2);
    for (int p = 0; p < panels; ++p) {
      l += integrateGaussLegendre(rule, a + (b - a) * p / panels, a + (b - a) * (p + 1) / panels,
                                  [&](double xx) { return init.derivative(xx, 1).norm(); });
    }
    x[pb.offset(seg + 1) - 1] = std::log(l);
  }

  // Levenberg-Marquardt with Marquardt scaling and forward differences (spec §3.5 [rec]).
  Problem::State st;
  Eigen::VectorXd r = pb.residual(x, st);
  double objective = r.squaredNorm();
  const double initialObjective = objective;
  std::vector<double> history{objective};
  int evaluations = 1;
  int iterations = 0;
  bool converged = false;
  std::string message;
  Eigen::MatrixXd jac;
  const auto updateJacobian = [&] {
    if (options.jacobian == FitJacobian::Analytic) {
      pb.analyticJacobian(x, st, jac);
    } else {
      evaluations += pb.jacobian(x, r, st, jac);
    }
  };
  updateJacobian();
  double mu = -1.0;
  double nu = 2.0;
  while (true) {
    if (objective <= 1e-300) {
      converged = true;
      message = "exact fit";
      break;
    }
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(jac.cols(), jac.cols());
    a.selfadjointView<Eigen::Lower>().rankUpdate(jac.transpose());
    a.triangularView<Eigen::StrictlyUpper>() = a.transpose();
    const Eigen::VectorXd g = jac.transpose() * r;
    double cosine = 0.0;
    const double rn = std::sqrt(objective);
    for (int c = 0; c < a.cols(); ++c) {
      const double cn = std::sqrt(a(c, c));
      if (cn > 0.0) cosine = std::max(cosine, std::abs(g[c]) / (cn * rn));
    }
    if (cosine <= options.gradientTolerance) {
      converged = true;
      message = "gradient tolerance";
      break;
    }
    // Marquardt scaling by the current diagonal (the MINPACK running maximum doubled the
    // iterations on the spiral and D-CHAIN3D-N).
    Eigen::VectorXd diag = a.diagonal();
    const double dmax = diag.maxCoeff();
    diag = diag.cwiseMax(1e-12 * std::max(dmax, 1e-300));
    if (mu < 0.0) mu = 1e-3;
    bool accepted = false;
    bool stop = false;
    while (!accepted) {
      if (iterations >= options.maxIterations || evaluations >= options.maxFunctionEvaluations) {
        message = "iteration or evaluation cap reached";
        stop = true;
        break;
      }
      Eigen::MatrixXd damped = a;
      damped.diagonal() += mu * diag;
      const Eigen::VectorXd step = damped.ldlt().solve(-g);
      if (!step.allFinite()) {
        mu *= nu;
        nu *= 2.0;
        continue;
      }
      if (step.norm() <= options.stepTolerance * (x.norm() + options.stepTolerance)) {
        converged = true;
        message = "step tolerance";
        stop = true;
        break;
      }
      const Eigen::VectorXd xn = x + step;
      Problem::State stn;
      const Eigen::VectorXd rn2 = pb.residual(xn, stn);
      ++evaluations;
      ++iterations;
      const double objn = rn2.allFinite() ? rn2.squaredNorm() : INFINITY;
      const double predicted = -(step.dot(g) * 2.0 + step.dot(a * step));
      const double actual = objective - objn;
      const double rho = predicted > 0.0 ? actual / predicted : -1.0;
      if (actual > 0.0 && rho > 0.0) {
        accepted = true;
        x = xn;
        r = rn2;
        st = std::move(stn);
        history.push_back(objn);
        objective = objn;
        mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
        nu = 2.0;
        if (actual <= options.functionTolerance * (objective + actual) &&
            predicted <= options.functionTolerance * (objective + actual)) {
          converged = true;
          message = "function tolerance";
          stop = true;
        }
      } else {
        mu *= nu;
        nu *= 2.0;
        if (mu > 1e20) {
          converged = true;
          message = "no further decrease (damping limit)";
          stop = true;
          break;
        }
      }
    }
    if (stop) break;
    updateJacobian();
  }

  QiChain chain = buildChain(pb, x);
  FitResult result(std::move(chain), std::move(baseline));
  result.parameters = u;
  result.pointErrors.resize(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) result.pointErrors[i] = r.segment<3>(3 * i).norm();
  result.rms = std::sqrt(result.pointErrors.squaredNorm() / static_cast<double>(points.rows()));
  result.maxError = result.pointErrors.maxCoeff();
  const double total = result.curve.length();
  result.rmsPercent = 100.0 * result.rms / total;
  result.maxPercent = 100.0 * result.maxError / total;
  result.initialRms = std::sqrt(initialObjective / static_cast<double>(points.rows()));
  result.converged = converged;
  result.iterations = iterations;
  result.functionEvaluations = evaluations;
  result.objectiveHistory = std::move(history);
  result.message = message;
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
