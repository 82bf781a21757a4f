#include "qi_fit_problem.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
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

// The node loops below run a few thousand times per evaluation: GCC left these small helpers as calls.
#define FFDKIT_QI_INLINE inline __attribute__((always_inline))

// Per-node scratch of the factors: fixed size for the common degrees (unrolled), a vector otherwise.
template <typename T, int K>
struct FactorArray {
  explicit FactorArray(int) {}
  T& operator[](int j) { return data[j]; }
  const T& operator[](int j) const { return data[j]; }
  T data[K];
};
template <typename T>
struct FactorArray<T, 0> {
  explicit FactorArray(int k) : data(k) {}
  T& operator[](int j) { return data[j]; }
  const T& operator[](int j) const { return data[j]; }
  std::vector<T> data;
};

// exp(b w) in the convention (cos|v|, sin|v| v/|v|), v = b w, b >= 0, with |w| given.
FFDKIT_QI_INLINE Eigen::Quaterniond scaledExp(const Eigen::Vector3d& w, double norm, double b) {
  const double theta = b * norm;
  const double sine = std::sin(theta), cosine = std::cos(theta);  // one sincos
  const double s = (theta < 1e-8 ? 1.0 - theta * theta / 6.0 : sine / theta) * b;
  return Eigen::Quaterniond(cosine, s * w.x(), s * w.y(), s * w.z());
}

// Hamilton product, inline (the optimiser's inner loops run it a few thousand times per evaluation).
FFDKIT_QI_INLINE Eigen::Quaterniond mul(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return Eigen::Quaterniond(a.w() * b.w() - a.x() * b.x() - a.y() * b.y() - a.z() * b.z(),
                            a.w() * b.x() + a.x() * b.w() + a.y() * b.z() - a.z() * b.y(),
                            a.w() * b.y() - a.x() * b.z() + a.y() * b.w() + a.z() * b.x(),
                            a.w() * b.z() + a.x() * b.y() - a.y() * b.x() + a.z() * b.w());
}

// R(q / |q|) e_x, the first column of the rotation matrix: the unit tangent of orientation q.
FFDKIT_QI_INLINE Eigen::Vector3d rotatedUnitX(const Eigen::Quaterniond& q) {
  const double inv = 1.0 / q.squaredNorm();
  return Eigen::Vector3d((q.w() * q.w() + q.x() * q.x() - q.y() * q.y() - q.z() * q.z()) * inv,
                         2.0 * (q.x() * q.y() + q.w() * q.z()) * inv, 2.0 * (q.x() * q.z() - q.w() * q.y()) * inv);
}

// R(q) of a unit quaternion, inline (Eigen's toRotationMatrix is an out-of-line call here).
FFDKIT_QI_INLINE Eigen::Matrix3d rotationOf(const Eigen::Quaterniond& q) {
  const double tx = 2.0 * q.x(), ty = 2.0 * q.y(), tz = 2.0 * q.z();
  const double twx = tx * q.w(), twy = ty * q.w(), twz = tz * q.w();
  const double txx = tx * q.x(), txy = ty * q.x(), txz = tz * q.x();
  const double tyy = ty * q.y(), tyz = tz * q.y(), tzz = tz * q.z();
  Eigen::Matrix3d r;
  r << 1.0 - (tyy + tzz), txy - twz, txz + twy, txy + twz, 1.0 - (txx + tzz), tyz - twx, txz - twy, tyz + twx,
      1.0 - (txx + tyy);
  return r;
}

FFDKIT_QI_INLINE Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
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

// The same at phi = 2 b w from e = exp(b w) = (cos theta, sin theta w/|w|), theta = b |w|, whose sine
// and cosine are known: 1 - cos 2theta = 2 sin^2 theta, sin 2theta = 2 sin theta cos theta. With
// K = [phi]x, K^2 = phi phi^T - |phi|^2 I, so J_l = I + alpha K + beta (phi phi^T - a^2 I), a = |phi|.
FFDKIT_QI_INLINE void leftJacobianCoefficients(const Eigen::Quaterniond& e, const Eigen::Vector3d& w, double norm, double b,
                              double& alpha, double& beta) {
  const double a = 2.0 * b * norm;
  if (a < 1e-3) {
    // Series: (1 - cos a)/a^2 = 1/2 - a^2/24 + ..., (a - sin a)/a^3 = 1/6 - a^2/120 + ...
    alpha = 0.5 - a * a / 24.0;
    beta = 1.0 / 6.0 - a * a / 120.0;
    return;
  }
  const double sine = e.vec().dot(w) / norm;  // sin theta, signed
  alpha = 2.0 * sine * sine / (a * a);
  beta = (a - 2.0 * sine * e.w()) / (a * a * a);
}

FFDKIT_QI_INLINE Eigen::Matrix3d leftJacobianOfExp(const Eigen::Quaterniond& e, const Eigen::Vector3d& w, double norm, double b) {
  double alpha, beta;
  leftJacobianCoefficients(e, w, norm, b, alpha, beta);
  const Eigen::Vector3d p = (2.0 * b) * w;
  const double diag = 1.0 - beta * p.squaredNorm();
  Eigen::Matrix3d m;
  m(0, 0) = diag + beta * p.x() * p.x();
  m(1, 1) = diag + beta * p.y() * p.y();
  m(2, 2) = diag + beta * p.z() * p.z();
  m(0, 1) = -alpha * p.z() + beta * p.x() * p.y();
  m(1, 0) = alpha * p.z() + beta * p.x() * p.y();
  m(0, 2) = alpha * p.y() + beta * p.x() * p.z();
  m(2, 0) = -alpha * p.y() + beta * p.x() * p.z();
  m(1, 2) = -alpha * p.x() + beta * p.y() * p.z();
  m(2, 1) = alpha * p.x() + beta * p.y() * p.z();
  return m;
}

// Its third column J_l e_z (planar fits: w along e_z).
FFDKIT_QI_INLINE Eigen::Vector3d leftJacobianOfExpColumnZ(const Eigen::Quaterniond& e, const Eigen::Vector3d& w, double norm,
                                         double b) {
  double alpha, beta;
  leftJacobianCoefficients(e, w, norm, b, alpha, beta);
  const Eigen::Vector3d p = (2.0 * b) * w;
  return Eigen::Vector3d(alpha * p.y() + beta * p.x() * p.z(), -alpha * p.x() + beta * p.y() * p.z(),
                         1.0 - beta * (p.x() * p.x() + p.y() * p.y()));
}

}  // namespace

namespace {
// Until when (steady clock, ns) threaded sweeps stay off after a fit saw them stall.
std::atomic<std::int64_t> threadsStalledUntil{0};
std::int64_t steadyNanoseconds() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}
}  // namespace

bool QiFitProblem::SweepGovernor::threaded() const {
  if (off_ || serialSeconds_ < 0.0 || calls_ % 16 == 15) return false;
  return steadyNanoseconds() >= threadsStalledUntil.load(std::memory_order_relaxed);
}

void QiFitProblem::SweepGovernor::record(bool threaded, double seconds) {
  ++calls_;
  if (!threaded) {
    serialSeconds_ = seconds;
  } else if (seconds > serialSeconds_ && ++strikes_ >= 2) {
    off_ = true;
    threadsStalledUntil.store(steadyNanoseconds() + 1'000'000'000, std::memory_order_relaxed);
  }
}

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
    // Panels: the data parameters are breakpoints (each residual closes its integral there), and a gap
    // wider than 1 / minPanels is split into equal parts, so no panel is wider than the uniform
    // grid. Unlike the union with that grid (cumulativeGaussLegendre, QiChain), dense data add no cuts:
    // the spiral's 27 points per segment give 27 panels instead of 34 (a fifth fewer nodes to sweep per
    // evaluation), and the objective still equals GL-24 on 64 panels to 1e-13 on the 3 / 6 / 12-segment
    // spirals (test: 1e-12); sparse data are cut about as finely as by the grid.
    std::vector<double> cuts = params;
    double prev = 0.0;
    for (const double next : params) {
      const int parts = static_cast<int>(std::ceil((next - prev) * quadrature.minPanels - 1e-9));
      for (int m = 1; m < parts; ++m) cuts.push_back(prev + (next - prev) * m / parts);
      prev = next;
    }
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
  // The start orientations first: q_{s+1} = E_k(1)..E_1(1) q_s (A) or q_s E_1(1)..E_k(1) (B) needs
  // no integral, so every segment's sweep below knows its start orientation and the sweeps are
  // independent. Each writes its positions relative to its start point; one pass then chains them.
  for (int seg = from; seg < layout_.segments; ++seg) {
    const std::vector<Eigen::Vector3d> w = omegas(x, seg);
    Eigen::Quaterniond q1 = ev.q[seg];
    for (int j = 0; j < k; ++j) {
      const Eigen::Quaterniond e = quaternionExp(w[j]);
      q1 = form_ == ProductForm::Local ? Eigen::Quaterniond(q1 * e) : Eigen::Quaterniond(e * q1);
    }
    ev.q[seg + 1] = q1.normalized();
  }
  const int count = layout_.segments - from;
  const bool eligible = parallel_ && count > 1 && nodes_ >= kParallelNodes && from == 0;
  const bool threaded = eligible && evaluationGovernor_.threaded();
  const auto begin = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static) if (threaded)
  for (int s = 0; s < count; ++s) sweepSegment(x, from + s, ev);
  if (eligible) {
    evaluationGovernor_.record(threaded,
                               std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count());
  }
  for (int seg = from; seg < layout_.segments; ++seg) {
    const Eigen::Vector3d p0 = ev.p[seg];
    for (int i = firstPoint(seg); i <= lastPoint(seg); ++i) {
      ev.r.segment<3>(3 * i) = p0 + ev.r.segment<3>(3 * i) - points_.row(i).transpose();
    }
    ev.p[seg + 1] = p0 + ev.p[seg + 1];
  }
}

void QiFitProblem::sweepSegment(const Eigen::VectorXd& x, int seg, QiFitEvaluation& ev) const {
  if (layout_.degree == 2) {
    sweepSegmentOfDegree<2>(x, seg, ev);
  } else if (layout_.degree == 3) {
    sweepSegmentOfDegree<3>(x, seg, ev);
  } else {
    sweepSegmentOfDegree<0>(x, seg, ev);
  }
}

template <int K>
void QiFitProblem::sweepSegmentOfDegree(const Eigen::VectorXd& x, int seg, QiFitEvaluation& ev) const {
  const int k = K > 0 ? K : layout_.degree;
  const bool local = form_ == ProductForm::Local;
  const std::vector<Eigen::Vector3d> wv = omegas(x, seg);
  FactorArray<Eigen::Vector3d, K> w(k);
  FactorArray<double, K> norms(k);
  for (int j = 0; j < k; ++j) w[j] = wv[j];
  for (int j = 0; j < k; ++j) norms[j] = w[j].norm();
  const double l = length(x, seg);
  const Eigen::Quaterniond q0 = ev.q[seg];
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
        q = local ? mul(q, e[j]) : mul(e[j], q);
      }
      ev.t[at] = rotatedUnitX(q);
      running += plan.weight[node] * ev.t[at];
    }
    // Relative to the start point p0 (added by evaluateFrom, in the order p0 + l running - P_i).
    if (out + 1 < plan.closeAfter.size()) {
      ev.r.segment<3>(3 * (lo + static_cast<int>(out))) = l * running;
    } else {
      ev.p[seg + 1] = l * running;
    }
  }
}

void QiFitProblem::segmentNormalSums(const Eigen::VectorXd& x, const QiFitEvaluation& ev, int seg,
                                     SegmentNormalSums& out) const {
  if (layout_.degree == 2) {
    segmentNormalSumsOfDegree<2>(x, ev, seg, out);
  } else if (layout_.degree == 3) {
    segmentNormalSumsOfDegree<3>(x, ev, seg, out);
  } else {
    segmentNormalSumsOfDegree<0>(x, ev, seg, out);
  }
}

template <int K>
void QiFitProblem::segmentNormalSumsOfDegree(const Eigen::VectorXd& x, const QiFitEvaluation& ev, int seg,
                                             SegmentNormalSums& out) const {
  const int k = K > 0 ? K : layout_.degree;
  const bool planar = layout_.planar;
  const int sv = layout_.segmentVars();
  // Running integrals over the segment, 3 x (sv + 3): [d t / d w_1 .. d t / d w_k | t | R(F) (form A)].
  Eigen::Matrix<double, 3, Eigen::Dynamic> acc = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, sv + 3);
  Eigen::Matrix<double, 3, Eigen::Dynamic>& own = out.own;
  own.resize(3, sv);
  // Sums over the segment's points i of M_i^T M_i, M_i^T O_i, O_i^T O_i, M_i^T r_i, O_i^T r_i, where
  // a point's Jacobian rows are [M_i D | O_i] with M_i = [I | G_i] (3 x 6) and O_i its own columns.
  Eigen::Matrix<double, 6, 6>& s66 = out.s66;
  Eigen::Matrix<double, 6, Eigen::Dynamic>& c6 = out.c6;
  Eigen::MatrixXd& oo = out.oo;
  Eigen::Matrix<double, 6, 1>& b6 = out.b6;
  Eigen::VectorXd& gOwn = out.gOwn;
  s66.setZero();
  c6.setZero(6, sv);
  oo.setZero(sv, sv);
  b6.setZero();
  gOwn.setZero(sv);
  FactorArray<double, K> norms(k);
  FactorArray<Eigen::Quaterniond, K> frame(k);
  const std::vector<Eigen::Vector3d> wv = omegas(x, seg);
  FactorArray<Eigen::Vector3d, K> w(k);
  for (int j = 0; j < k; ++j) {
    w[j] = wv[j];
    norms[j] = w[j].norm();
  }
  const double l = length(x, seg);
  const Eigen::Quaterniond q0 = ev.q[seg];
  const Eigen::Matrix3d minusCrossT0 = -skew(rotatedUnitX(q0));
  const SegmentPlan& plan = plans_[seg];
  int node = 0;
  const int lo = firstPoint(seg);
  for (std::size_t o = 0; o < plan.closeAfter.size(); ++o) {
    for (; node < plan.closeAfter[o]; ++node) {
      const std::size_t at = static_cast<std::size_t>(plan.firstNode + node);
      const Eigen::Quaterniond* e = &ev.e[at * k];
      const double* b = &plan.basis[static_cast<std::size_t>(node) * k];
      const Eigen::Vector3d& tan = ev.t[at];
      // Frames left of each factor: E_k..E_{j+1} (form A) or q0 E_1..E_{j-1} (form B).
      Eigen::Quaterniond full = Eigen::Quaterniond::Identity();
      if (form_ == ProductForm::Global) {
        frame[k - 1] = Eigen::Quaterniond::Identity();
        Eigen::Quaterniond suffix = e[k - 1];
        for (int j = k - 2; j >= 0; --j) {
          frame[j] = suffix;
          suffix = mul(suffix, e[j]);
        }
        full = suffix;
      } else {
        Eigen::Quaterniond prefix = q0;
        for (int j = 0; j < k; ++j) {
          frame[j] = prefix;
          prefix = mul(prefix, e[j]);
        }
      }
      const double wt = plan.weight[node];
      double* column = acc.data();  // column-major 3 x (sv + 3)
      const auto add = [&](int col, const Eigen::Vector3d& v) { Eigen::Map<Eigen::Vector3d>(column + 3 * col) += v; };
      for (int j = 0; j < k; ++j) {
        // d t / d w_j = -[t]x R(frame_j) J_l(2 b_j w_j) 2 b_j; -[t]x v = v x t.
        const double scale = wt * 2.0 * b[j];
        // The last factor's frame is the identity in form A (k >= 1): no rotation to apply.
        const bool identity = form_ == ProductForm::Global && j == k - 1;
        if (planar) {
          Eigen::Vector3d col = leftJacobianOfExpColumnZ(e[j], w[j], norms[j], b[j]);
          if (!identity) col = rotationOf(frame[j]) * col;
          add(j, scale * col.cross(tan));
        } else {
          Eigen::Matrix3d m = leftJacobianOfExp(e[j], w[j], norms[j], b[j]);
          if (!identity) m = rotationOf(frame[j]) * m;
          for (int c = 0; c < 3; ++c) add(3 * j + c, scale * m.col(c).cross(tan));
        }
      }
      add(sv - 1, wt * tan);
      // d t / d phi0 = -[t]x R(F) = R(F) (-[t0]x) in form A (t = R(F) t0, F = E_k..E_1): only R(F) is
      // integrated. In form B it is -[t]x, whose integral is -[int t]x: nothing to add per node.
      if (form_ == ProductForm::Global) Eigen::Map<Eigen::Matrix3d>(column + 3 * sv) += wt * rotationOf(full);
    }
    const Eigen::Matrix3d gl = form_ == ProductForm::Global ? Eigen::Matrix3d(l * acc.rightCols<3>() * minusCrossT0)
                                                           : Eigen::Matrix3d(-l * skew(acc.col(sv - 1)));
    own = l * acc.leftCols(sv);  // the length column: d/d lambda = l (d/dl) = l int t
    if (o + 1 < plan.closeAfter.size()) {
      const Eigen::Vector3d r = ev.r.segment<3>(3 * (lo + static_cast<int>(o)));
      s66.topLeftCorner<3, 3>().diagonal().array() += 1.0;
      s66.topRightCorner<3, 3>() += gl;
      s66.bottomRightCorner<3, 3>() += gl.transpose() * gl;
      c6.topRows<3>() += own;
      c6.bottomRows<3>() += gl.transpose() * own;
      // Symmetric: its upper triangle is all that analyticNormalEquations reads (a is mirrored at its
      // end). Small: a plain loop beats GEMM here.
      oo.triangularView<Eigen::Upper>() += own.transpose().lazyProduct(own);
      b6.head<3>() += r;
      b6.tail<3>() += gl.transpose() * r;
      gOwn += own.transpose() * r;
    } else {
      // End of the segment: G and the own columns of the end point, which carry D to the next one.
      s66.bottomLeftCorner<3, 3>() = s66.topRightCorner<3, 3>().transpose();
      out.gl = gl;
    }
  }
}

void QiFitProblem::segmentTransfer(const Eigen::VectorXd& x, const QiFitEvaluation& ev, int seg,
                                   const SegmentNormalSums& sums, SegmentTransfer& out) const {
  const int k = layout_.degree;
  const bool planar = layout_.planar;
  const int sv = layout_.segmentVars();
  const std::vector<Eigen::Vector3d> w = omegas(x, seg);
  out.columns.setZero(6, sv);
  out.columns.topRows<3>() = sums.own;
  auto dphi = out.columns.bottomRows<3>();
  const auto setOwnRotationColumns = [&](int j, const Eigen::Matrix3d& dj) {
    if (planar) {
      dphi.col(j) = dj.col(2);
    } else {
      dphi.middleCols<3>(3 * j) = dj;
    }
  };
  // End orientation: q(1) = E_k(1)..E_1(1) q0 (A), whose left perturbations of q0 turn with the
  // segment's rotation F(1), or q0 E_1(1)..E_k(1) (B), whose left perturbations of q0 stay as they are.
  if (form_ == ProductForm::Global) {
    Eigen::Quaterniond f1 = Eigen::Quaterniond::Identity();
    for (int j = 0; j < k; ++j) f1 = quaternionExp(w[j]) * f1;
    out.rotation = f1.normalized().toRotationMatrix();
    Eigen::Quaterniond suffix = Eigen::Quaterniond::Identity();
    for (int j = k - 1; j >= 0; --j) {
      setOwnRotationColumns(j, suffix.normalized().toRotationMatrix() * leftJacobian(2.0 * w[j]) * 2.0);
      suffix = suffix * quaternionExp(w[j]);
    }
  } else {
    out.rotation.setIdentity();
    Eigen::Quaterniond prefix = ev.q[seg];
    for (int j = 0; j < k; ++j) {
      setOwnRotationColumns(j, prefix.normalized().toRotationMatrix() * leftJacobian(2.0 * w[j]) * 2.0);
      prefix = prefix * quaternionExp(w[j]);
    }
  }
  out.a.setIdentity();
  out.a.topRightCorner<3, 3>() = sums.gl;
  out.a.bottomRightCorner<3, 3>() = out.rotation;
}

void QiFitProblem::analyticNormalEquations(const Eigen::VectorXd& x, const QiFitEvaluation& ev, Eigen::MatrixXd& a,
                                           Eigen::VectorXd& g) const {
  const int nv = size();
  const int sv = layout_.segmentVars();
  const int segments = layout_.segments;
  a.setZero(nv, nv);
  g.setZero(nv);
  // The node sweeps of the segments are independent (each needs only its start orientation and its
  // residuals); the chain below combines their sums in segment order, whatever the thread count.
  std::vector<SegmentNormalSums> sums(segments);
  const bool eligible = parallel_ && segments > 1 && nodes_ >= kParallelNodes;
  const bool threaded = eligible && normalGovernor_.threaded();
  const auto begin = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static) if (threaded)
  for (int seg = 0; seg < segments; ++seg) segmentNormalSums(x, ev, seg, sums[seg]);
  if (eligible) {
    normalGovernor_.record(threaded, std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count());
  }
  std::vector<SegmentTransfer> transfers(segments);
  for (int seg = 0; seg < segments; ++seg) segmentTransfer(x, ev, seg, sums[seg], transfers[seg]);
  // later[s] = sum over the points of segments >= s of (d rows / d state_s)^T (d rows / d state_s),
  // state_s the start point and orientation of segment s: the rows of segment s' > s depend on
  // state_s through A_{s'-1}..A_s, so later[s] = S_s + A_s^T later[s + 1] A_s (6 x 6 each).
  std::vector<Eigen::Matrix<double, 6, 6>> later(segments + 1);
  later[segments].setZero();
  for (int seg = segments - 1; seg >= 0; --seg) {
    const Eigen::Matrix<double, 6, 6>& t = transfers[seg].a;
    later[seg] = sums[seg].s66 + t.transpose() * later[seg + 1] * t;
  }
  // dp, dphi: derivatives of the current segment's start point and start orientation (rotation
  // vector of a left perturbation, world frame) with respect to all variables, stacked as D (6 x nv).
  Eigen::Matrix<double, 6, Eigen::Dynamic> d = Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, nv);
  auto dp = d.topRows<3>();
  auto dphi = d.bottomRows<3>();
  const int startVars = layout_.startVars;
  if (startVars > 0) {
    const Eigen::Vector3d eta = startVars == 1 ? Eigen::Vector3d(x[0] * freeAxis1_)
                                               : Eigen::Vector3d(x[0] * freeAxis1_ + x[1] * freeAxis2_);
    const Eigen::Matrix3d jl = leftJacobian(2.0 * eta);
    dphi.col(0) = 2.0 * jl * freeAxis1_;
    if (startVars == 2) dphi.col(1) = 2.0 * jl * freeAxis2_;
    const auto x0 = d.leftCols(startVars);
    a.topLeftCorner(startVars, startVars).noalias() = x0.transpose() * later[0] * x0;
  }
  for (int seg = 0; seg < segments; ++seg) {
    const SegmentNormalSums& s = sums[seg];
    const SegmentTransfer& t = transfers[seg];
    const int off = layout_.offset(seg);
    // Block (earlier variables, this segment's): through D from this segment's rows (c6) and, carried
    // by A, from the later segments' rows. Its own block: its rows (oo, upper triangle) and the later ones.
    const Eigen::Matrix<double, 6, Eigen::Dynamic> laterOwn = later[seg + 1] * t.columns;
    if (off > 0) {
      const auto du = d.leftCols(off);
      const Eigen::Matrix<double, 6, Eigen::Dynamic> cross = s.c6 + t.a.transpose() * laterOwn;
      a.block(0, off, off, sv).noalias() += du.transpose() * cross;
      g.head(off).noalias() += du.transpose() * s.b6;
    }
    a.block(off, off, sv, sv) += s.oo;
    a.block(off, off, sv, sv).noalias() += t.columns.transpose() * laterOwn;
    g.segment(off, sv) += s.gOwn;
    // D moves on to the segment's end: D <- A D on the earlier columns, then its own columns.
    dp.leftCols(off) += s.gl * dphi.leftCols(off);
    if (form_ == ProductForm::Global) dphi.leftCols(off) = t.rotation * dphi.leftCols(off);
    d.middleCols(off, sv) = t.columns;
  }
  a.triangularView<Eigen::StrictlyLower>() = a.transpose();
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
