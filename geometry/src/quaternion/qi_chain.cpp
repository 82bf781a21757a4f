#include "ffdkit/geometry/quaternion/qi_chain.h"

#include <algorithm>
#include <sstream>

#include "ffdkit/geometry/quaternion/frenet.h"
#include "ffdkit/geometry/quaternion/quaternion_error.h"
#include "ffdkit/geometry/quaternion/tangent_integration.h"
#include "ffdkit/geometry/quaternion/unit_quaternion.h"

namespace ffdkit::geometry::quaternion {

QiChainSegment::QiChainSegment(const Eigen::Vector3d& start, const Eigen::Quaterniond& q0,
                               std::vector<Eigen::Vector3d> omegas, double length, ProductForm form,
                               const Eigen::Vector3d& v0, QiQuadrature quadrature)
    : start_(start),
      rotation_(q0, std::move(omegas), form),
      length_(length),
      v0_(v0.normalized()),
      quadrature_(quadrature) {
  if (!(length > 0.0) || !std::isfinite(length)) {
    std::ostringstream msg;
    msg << "QiChainSegment: expected a positive finite length, got " << length;
    throw QuaternionCurveError(msg.str());
  }
}

Eigen::Quaterniond QiChainSegment::orientation(double u) const { return rotation_.value(u).normalized(); }

Eigen::Vector3d QiChainSegment::tangent(double u) const { return rotateFixedVector(orientation(u), v0_); }

Eigen::Vector3d QiChainSegment::angularVelocity(double u) const {
  Eigen::Quaterniond q, dq;
  rotation_.evaluate(u, q, dq);
  return 2.0 * (dq * q.conjugate()).vec() / q.squaredNorm();
}

Eigen::Vector3d QiChainSegment::tangentDerivative(double u) const {
  Eigen::Quaterniond q, dq;
  rotation_.evaluate(u, q, dq);
  const double n2 = q.squaredNorm();
  const Eigen::Vector3d omega = 2.0 * (dq * q.conjugate()).vec() / n2;
  return omega.cross(rotateFixedVector(q.normalized(), v0_));
}

double QiChainSegment::curvature(double u) const { return tangentDerivative(u).norm() / length_; }

double QiChainSegment::signedPlanarCurvature(double u) const {
  return tangent(u).cross(tangentDerivative(u)).z() / length_;
}

double QiChainSegment::torsion(double u) const {
  const Eigen::Vector3d tu = tangentDerivative(u);
  const Eigen::Vector3d tuu = fivePointDerivative([this](double x) { return tangentDerivative(x); }, u);
  return torsionFromTangentDerivatives(tangent(u), tu, tuu, length_);
}

Eigen::Vector3d QiChainSegment::point(double u) const {
  Eigen::VectorXd p(1);
  p[0] = std::clamp(u, 0.0, 1.0);
  return points(p).row(0).transpose();
}

Eigen::MatrixX3d QiChainSegment::points(const Eigen::VectorXd& sortedU) const {
  const Eigen::MatrixX3d integral = cumulativeGaussLegendre([this](double x) { return tangent(x); }, sortedU,
                                                            quadrature_.order, quadrature_.minPanels);
  return (length_ * integral).rowwise() + start_.transpose();
}

Eigen::Vector3d QiChainSegment::endPoint() const { return point(1.0); }

Eigen::Quaterniond QiChainSegment::endOrientation() const { return orientation(1.0); }

QiChain::QiChain(const Eigen::Vector3d& start, const Eigen::Quaterniond& q00, ProductForm form,
                 const Eigen::Vector3d& v0, QiQuadrature quadrature)
    : start_(start), q00_(q00.normalized()), form_(form), v0_(v0), quadrature_(quadrature) {}

void QiChain::appendSegment(std::vector<Eigen::Vector3d> omegas, double length) {
  const Eigen::Vector3d p = segments_.empty() ? start_ : segments_.back().endPoint();
  const Eigen::Quaterniond q = segments_.empty() ? q00_ : segments_.back().endOrientation();
  segments_.emplace_back(p, q, std::move(omegas), length, form_, v0_, quadrature_);
}

double QiChain::length() const {
  double sum = 0.0;
  for (const auto& s : segments_) sum += s.length();
  return sum;
}

std::pair<int, double> QiChain::locate(double s) const {
  if (segments_.empty()) {
    throw QuaternionCurveError("QiChain: the chain has no segments");
  }
  double at = std::max(0.0, s);
  for (int i = 0; i < segmentCount(); ++i) {
    const double l = segments_[i].length();
    if (at < l || i + 1 == segmentCount()) {
      return {i, std::clamp(at / l, 0.0, 1.0)};
    }
    at -= l;
  }
  return {segmentCount() - 1, 1.0};
}

double QiChain::arcLengthAtGlobal(double u) const {
  const int m = segmentCount();
  const double uc = std::clamp(u, 0.0, static_cast<double>(m));
  const int i = std::min(static_cast<int>(uc), m - 1);
  double s = 0.0;
  for (int k = 0; k < i; ++k) s += segments_[k].length();
  return s + (uc - i) * segments_[i].length();
}

Eigen::Vector3d QiChain::pointAtGlobal(double u) const { return position(arcLengthAtGlobal(u)); }

Eigen::Vector3d QiChain::position(double s) const {
  const auto [i, u] = locate(s);
  return segments_[i].point(u);
}

Eigen::Vector3d QiChain::tangent(double s) const {
  const auto [i, u] = locate(s);
  return segments_[i].tangent(u);
}

double QiChain::curvature(double s) const {
  const auto [i, u] = locate(s);
  return segments_[i].curvature(u);
}

double QiChain::torsion(double s) const {
  const auto [i, u] = locate(s);
  return segments_[i].torsion(u);
}

Eigen::Vector3d QiChain::curvatureVector(double s) const {
  const auto [i, u] = locate(s);
  return segments_[i].tangentDerivative(u) / segments_[i].length();
}

Eigen::MatrixX3d QiChain::samplePositions(int count) const {
  if (count < 2) {
    std::ostringstream msg;
    msg << "QiChain::samplePositions: expected at least 2 samples, got " << count;
    throw QuaternionCurveError(msg.str());
  }
  // Group the samples by segment so each segment is integrated in one cumulative sweep.
  Eigen::MatrixX3d out(count, 3);
  const double total = length();
  int k = 0;
  double segStart = 0.0;
  for (int i = 0; i < segmentCount() && k < count; ++i) {
    const double l = segments_[i].length();
    std::vector<double> us;
    const int first = k;
    while (k < count) {
      const double s = total * k / (count - 1);
      if (s > segStart + l && i + 1 < segmentCount()) break;
      us.push_back(std::clamp((s - segStart) / l, 0.0, 1.0));
      ++k;
    }
    if (!us.empty()) {
      out.middleRows(first, static_cast<Eigen::Index>(us.size())) =
          segments_[i].points(Eigen::Map<const Eigen::VectorXd>(us.data(), static_cast<Eigen::Index>(us.size())));
    }
    segStart += l;
  }
  return out;
}

}  // namespace ffdkit::geometry::quaternion
