#include "qi_fit_problem.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "ffdkit/geometry/gauss_legendre.h"
#include "ffdkit/geometry/quaternion/bernstein.h"
#include "ffdkit/geometry/quaternion/quaternion_error.h"
#include "ffdkit/geometry/quaternion/unit_quaternion.h"

namespace ffdkit::geometry::quaternion::detail {

namespace {

// exp(b w) in the spec's convention (cos|v|, sin|v| v/|v|), v = b w, b >= 0, with |w| given.
Eigen::Quaterniond scaledExp(const Eigen::Vector3d& w, double norm, double b) {
  const double theta = b * norm;
  const double s = (theta < 1e-8 ? 1.0 - theta * theta / 6.0 : std::sin(theta) / theta) * b;
  return Eigen::Quaterniond(std::cos(theta), s * w.x(), s * w.y(), s * w.z());
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d k;
  k << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return k;
}

// Left Jacobian of SO(3) at the rotation vector phi: Exp(phi + d) = Exp(J_l d) Exp(phi).
Eigen::Matrix3d leftJacobian(const Eigen::Vector3d& phi) {
  const double a = phi.norm();
  const Eigen::Matrix3d k = skew(phi);
  if (a < 1e-6) return Eigen::Matrix3d::Identity() + 0.5 * k + (1.0 / 6.0) * k * k;
  return Eigen::Matrix3d::Identity() + ((1.0 - std::cos(a)) / (a * a)) * k + ((a - std::sin(a)) / (a * a * a)) * k * k;
}

// The same at phi = 2 theta w/|w| from e = exp(theta w/|w|) = (cos theta, sin theta w/|w|), whose
// sine and cosine are already known: 1 - cos 2theta = 2 sin^2 theta, sin 2theta = 2 sin cos.
Eigen::Matrix3d leftJacobianOfExp(const Eigen::Quaterniond& e, const Eigen::Vector3d& w, double norm, double b) {
  const double theta = b * norm;
  const Eigen::Matrix3d k = skew((2.0 * b) * w);
  const double a = 2.0 * theta;
  if (a < 1e-3) {
    // Series: (1 - cos a)/a^2 = 1/2 - a^2/24 + ..., (a - sin a)/a^3 = 1/6 - a^2/120 + ...
    const double a2 = a * a;
    return Eigen::Matrix3d::Identity() + (0.5 - a2 / 24.0) * k + (1.0 / 6.0 - a2 / 120.0) * k * k;
  }
  const double s = e.vec().dot(w) / norm;  // sin theta, signed
  const double c = e.w();
  const double alpha = 2.0 * s * s / (a * a);
  const double beta = (a - 2.0 * s * c) / (a * a * a);
  return Eigen::Matrix3d::Identity() + alpha * k + beta * k * k;
}

// -[t]x: -[t]x v = v x t.
Eigen::Matrix3d minusCross(const Eigen::Vector3d& t) { return -skew(t); }

}  // namespace

QiFitProblem::QiFitProblem(const Eigen::MatrixX3d& points, const std::vector<int>& breaks, const Eigen::VectorXd& u,
                           QiFitLayout layout, ProductForm form, QiQuadrature quadrature, const Eigen::Vector3d& start,
                           const Eigen::Quaterniond& baseQ00, const Eigen::Vector3d& freeAxis1,
                           const Eigen::Vector3d& freeAxis2)
    : points_(points),
      breaks_(breaks),
      layout_(layout),
      form_(form),
      quadrature_(quadrature),
      start_(start),
      baseQ00_(baseQ00),
      freeAxis1_(freeAxis1),
      freeAxis2_(freeAxis2) {
  if (quadrature.order < 1 || quadrature.minPanels < 1) {
    std::ostringstream msg;
    msg << "fitQiChain: expected quadrature order >= 1 and minPanels >= 1, got " << quadrature.order << " and "
        << quadrature.minPanels;
    throw QuaternionCurveError(msg.str());
  }
  const GaussLegendreRule rule = gaussLegendreRule(quadrature.order);
  const int k = layout_.degree;
  plans_.resize(layout_.segments);
  for (int seg = 0; seg < layout_.segments; ++seg) {
    SegmentPlan& plan = plans_[seg];
    plan.firstNode = nodes_;
    const int lo = firstPoint(seg), hi = lastPoint(seg);
    // Panels: the union of the data parameters and a uniform grid (spec §4), as cumulativeGaussLegendre.
    std::vector<double> params;
    for (int i = lo; i <= hi; ++i) {
      params.push_back(std::clamp(u[i] - seg, 0.0, 1.0));
      if (params.size() > 1 && params.back() < params[params.size() - 2]) {
        std::ostringstream msg;
        msg << "fitQiChain: expected parameters increasing within segment " << seg << ", got " << u[i - 1]
            << " then " << u[i] << " at points " << i - 1 << " and " << i;
        throw QuaternionCurveError(msg.str());
      }
    }
    params.push_back(1.0);
    std::vector<double> cuts = params;
    for (int p = 0; p <= quadrature.minPanels; ++p) cuts.push_back(static_cast<double>(p) / quadrature.minPanels);
    std::sort(cuts.begin(), cuts.end());
    double at = 0.0;
    std::size_t b = 0;
    for (const double target : params) {
      while (b < cuts.size() && cuts[b] <= target) {
        if (cuts[b] > at) {
          const double half = 0.5 * (cuts[b] - at), mid = 0.5 * (cuts[b] + at);
          for (Eigen::Index g = 0; g < rule.nodes.size(); ++g) {
            const double t = mid + half * rule.nodes[g];
            plan.weight.push_back(rule.weights[g] * half);
            for (int j = 1; j <= k; ++j) plan.basis.push_back(cumulativeBernstein(k, j, t));
          }
          at = cuts[b];
        }
        ++b;
      }
      plan.closeAfter.push_back(static_cast<int>(plan.weight.size()));
    }
    nodes_ += static_cast<int>(plan.weight.size());
  }
}

std::vector<Eigen::Vector3d> QiFitProblem::omegas(const Eigen::VectorXd& x, int seg) const {
  std::vector<Eigen::Vector3d> w(layout_.degree);
  const int off = layout_.offset(seg);
  for (int j = 0; j < layout_.degree; ++j) {
    w[j] = layout_.planar ? Eigen::Vector3d(0.0, 0.0, x[off + j]) : Eigen::Vector3d(x.segment<3>(off + 3 * j));
  }
  return w;
}

double QiFitProblem::length(const Eigen::VectorXd& x, int seg) const {
  return std::exp(x[layout_.offset(seg + 1) - 1]);
}

Eigen::Quaterniond QiFitProblem::q00(const Eigen::VectorXd& x) const {
  if (layout_.startVars == 0) return baseQ00_;
  const Eigen::Vector3d eta = layout_.startVars == 1 ? Eigen::Vector3d(x[0] * freeAxis1_)
                                                     : Eigen::Vector3d(x[0] * freeAxis1_ + x[1] * freeAxis2_);
  return (quaternionExp(eta) * baseQ00_).normalized();
}

void QiFitProblem::evaluate(const Eigen::VectorXd& x, QiFitEvaluation& ev) const {
  ev.p.assign(layout_.segments + 1, start_);
  ev.q.assign(layout_.segments + 1, q00(x));
  evaluateFrom(x, 0, ev);
}

void QiFitProblem::evaluateFrom(const Eigen::VectorXd& x, int from, QiFitEvaluation& ev) const {
  const int k = layout_.degree;
  ev.r.resize(3 * points_.rows());
  ev.e.resize(static_cast<std::size_t>(nodes_) * k);
  ev.t.resize(nodes_);
  std::vector<double> norms(k);
  for (int seg = from; seg < layout_.segments; ++seg) {
    const std::vector<Eigen::Vector3d> w = omegas(x, seg);
    for (int j = 0; j < k; ++j) norms[j] = w[j].norm();
    const double l = length(x, seg);
    const Eigen::Quaterniond q0 = ev.q[seg];
    const Eigen::Vector3d p0 = ev.p[seg];
    const SegmentPlan& plan = plans_[seg];
    Eigen::Vector3d running = Eigen::Vector3d::Zero();
    int node = 0;
    const int lo = firstPoint(seg);
    for (std::size_t out = 0; out < plan.closeAfter.size(); ++out) {
      for (; node < plan.closeAfter[out]; ++node) {
        const std::size_t at = static_cast<std::size_t>(plan.firstNode + node);
        Eigen::Quaterniond* e = &ev.e[at * k];
        const double* b = &plan.basis[static_cast<std::size_t>(node) * k];
        Eigen::Quaterniond q = q0;
        for (int j = 0; j < k; ++j) {
          e[j] = scaledExp(w[j], norms[j], b[j]);
          q = form_ == ProductForm::Local ? Eigen::Quaterniond(q * e[j]) : Eigen::Quaterniond(e[j] * q);
        }
        ev.t[at] = rotateFixedVector(q.normalized(), Eigen::Vector3d::UnitX());
        running += plan.weight[node] * ev.t[at];
      }
      if (out + 1 < plan.closeAfter.size()) {
        const int i = lo + static_cast<int>(out);
        ev.r.segment<3>(3 * i) = p0 + l * running - points_.row(i).transpose();
      } else {
        ev.p[seg + 1] = p0 + l * running;
      }
    }
    Eigen::Quaterniond q1 = q0;
    for (int j = 0; j < k; ++j) {
      const Eigen::Quaterniond e = quaternionExp(w[j]);
      q1 = form_ == ProductForm::Local ? Eigen::Quaterniond(q1 * e) : Eigen::Quaterniond(e * q1);
    }
    ev.q[seg + 1] = q1.normalized();
  }
}

void QiFitProblem::analyticJacobian(const Eigen::VectorXd& x, const QiFitEvaluation& ev, Eigen::MatrixXd& jac) const {
  const int nv = size();
  const int k = layout_.degree;
  const bool planar = layout_.planar;
  const int od = layout_.omegaDim();
  // Entries right of a segment's block stay zero, so they are cleared only when the shape changes.
  if (jac.rows() != 3 * points_.rows() || jac.cols() != nv) jac.setZero(3 * points_.rows(), nv);
  // dp, dphi: derivatives of the current segment's start point and start orientation (rotation
  // vector of a left perturbation, world frame) with respect to all variables.
  Eigen::Matrix<double, 3, Eigen::Dynamic> dp = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, nv);
  Eigen::Matrix<double, 3, Eigen::Dynamic> dphi = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, nv);
  if (layout_.startVars > 0) {
    const Eigen::Vector3d eta = layout_.startVars == 1 ? Eigen::Vector3d(x[0] * freeAxis1_)
                                                       : Eigen::Vector3d(x[0] * freeAxis1_ + x[1] * freeAxis2_);
    const Eigen::Matrix3d jl = leftJacobian(2.0 * eta);
    dphi.col(0) = 2.0 * jl * freeAxis1_;
    if (layout_.startVars == 2) dphi.col(1) = 2.0 * jl * freeAxis2_;
  }
  // Running integrals per segment, 3 x cols: [d t / d w_1 .. d t / d w_k | d t / d phi0 | t].
  const int ownCols = k * od;
  const int cols = ownCols + 4;
  Eigen::Matrix<double, 3, Eigen::Dynamic> acc(3, cols);
  std::vector<double> norms(k);
  std::vector<Eigen::Quaterniond> frame(k);
  for (int seg = 0; seg < layout_.segments; ++seg) {
    const std::vector<Eigen::Vector3d> w = omegas(x, seg);
    for (int j = 0; j < k; ++j) norms[j] = w[j].norm();
    const double l = length(x, seg);
    const Eigen::Quaterniond q0 = ev.q[seg];
    const SegmentPlan& plan = plans_[seg];
    const int off = layout_.offset(seg);
    acc.setZero();
    int node = 0;
    const int lo = firstPoint(seg);
    const auto writeRows = [&](auto&& target) {
      // target: 3 x nv; upstream columns through the start state, then this segment's own columns.
      const Eigen::Matrix3d g = l * acc.block<3, 3>(0, ownCols);
      target.leftCols(off) = dp.leftCols(off) + g.lazyProduct(dphi.leftCols(off));
      target.middleCols(off, ownCols) = l * acc.leftCols(ownCols);
      target.col(off + ownCols) = l * acc.col(ownCols + 3);  // d/d lambda = l * (d/dl)
    };
    for (std::size_t out = 0; out < plan.closeAfter.size(); ++out) {
      for (; node < plan.closeAfter[out]; ++node) {
        const std::size_t at = static_cast<std::size_t>(plan.firstNode + node);
        const Eigen::Quaterniond* e = &ev.e[at * k];
        const double* b = &plan.basis[static_cast<std::size_t>(node) * k];
        const Eigen::Vector3d& tan = ev.t[at];
        // Frames left of each factor: E_k..E_{j+1} (form A) or q0 E_1..E_{j-1} (form B).
        Eigen::Quaterniond full = Eigen::Quaterniond::Identity();
        if (form_ == ProductForm::Global) {
          Eigen::Quaterniond suffix = Eigen::Quaterniond::Identity();
          for (int j = k - 1; j >= 0; --j) {
            frame[j] = suffix;
            suffix = suffix * e[j];
          }
          full = suffix;
        } else {
          Eigen::Quaterniond prefix = q0;
          for (int j = 0; j < k; ++j) {
            frame[j] = prefix;
            prefix = prefix * e[j];
          }
        }
        const Eigen::Matrix3d cross = minusCross(tan);
        const double wt = plan.weight[node];
        for (int j = 0; j < k; ++j) {
          // d t / d w_j = -[t]x R(frame_j) J_l(2 b_j w_j) 2 b_j.
          const Eigen::Matrix3d jl = leftJacobianOfExp(e[j], w[j], norms[j], b[j]);
          const Eigen::Matrix3d rf = frame[j].normalized().toRotationMatrix();
          if (planar) {
            acc.col(j) += (wt * 2.0 * b[j]) * (cross * (rf * jl.col(2)));
          } else {
            acc.block<3, 3>(0, 3 * j) += (wt * 2.0 * b[j]) * (cross * (rf * jl));
          }
        }
        if (form_ == ProductForm::Global) {
          acc.block<3, 3>(0, ownCols) += wt * (cross * full.normalized().toRotationMatrix());
        } else {
          acc.block<3, 3>(0, ownCols) += wt * cross;
        }
        acc.col(ownCols + 3) += wt * tan;
      }
      if (out + 1 < plan.closeAfter.size()) {
        const int i = lo + static_cast<int>(out);
        writeRows(jac.middleRows(3 * i, 3));
      } else {
        writeRows(dp);
      }
    }
    // Start orientation of the next segment: q(1) = E_k(1)..E_1(1) q0 (A) or q0 E_1(1)..E_k(1) (B).
    const int ownBegin = off;
    if (form_ == ProductForm::Global) {
      Eigen::Quaterniond f1 = Eigen::Quaterniond::Identity();
      for (int j = 0; j < k; ++j) f1 = quaternionExp(w[j]) * f1;
      dphi.leftCols(off) = f1.normalized().toRotationMatrix() * dphi.leftCols(off);
      Eigen::Quaterniond suffix = Eigen::Quaterniond::Identity();
      for (int j = k - 1; j >= 0; --j) {
        const Eigen::Matrix3d d = suffix.normalized().toRotationMatrix() * leftJacobian(2.0 * w[j]) * 2.0;
        if (planar) {
          dphi.col(ownBegin + j) = d.col(2);
        } else {
          dphi.block<3, 3>(0, ownBegin + 3 * j) = d;
        }
        suffix = suffix * quaternionExp(w[j]);
      }
    } else {
      Eigen::Quaterniond prefix = q0;
      for (int j = 0; j < k; ++j) {
        const Eigen::Matrix3d d = prefix.normalized().toRotationMatrix() * leftJacobian(2.0 * w[j]) * 2.0;
        if (planar) {
          dphi.col(ownBegin + j) = d.col(2);
        } else {
          dphi.block<3, 3>(0, ownBegin + 3 * j) = d;
        }
        prefix = prefix * quaternionExp(w[j]);
      }
    }
  }
}

int QiFitProblem::finiteDifferenceJacobian(const Eigen::VectorXd& x, const QiFitEvaluation& ev,
                                           Eigen::MatrixXd& jac) const {
  const int nv = size();
  const Eigen::Index rows = ev.r.size();
  jac.setZero(rows, nv);
  const double eps = std::sqrt(std::numeric_limits<double>::epsilon());
  QiFitEvaluation work = ev;
  for (int c = 0; c < nv; ++c) {
    const int seg = c < layout_.startVars ? 0 : (c - layout_.startVars) / layout_.segmentVars();
    Eigen::VectorXd xp = x;
    const double h = eps * std::max(std::abs(x[c]), 1.0);
    xp[c] += h;
    work.p = ev.p;
    work.q = ev.q;
    if (c < layout_.startVars) work.q[0] = q00(xp);
    evaluateFrom(xp, seg, work);
    const int row0 = rowBegin(seg);
    jac.col(c).tail(rows - row0) = (work.r.tail(rows - row0) - ev.r.tail(rows - row0)) / h;
  }
  return nv;
}

}  // namespace ffdkit::geometry::quaternion::detail
