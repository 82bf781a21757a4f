#include "ffdkit/geometry/quaternion/bezier_qi_segment.h"

#include <cmath>
#include <sstream>

#include "ffdkit/geometry/quaternion/quaternion_error.h"
#include "ffdkit/geometry/quaternion/tangent_integration.h"
#include "ffdkit/geometry/quaternion/unit_quaternion.h"

namespace ffdkit::geometry::quaternion {

Eigen::Vector3d qiTangentFromAngles(double alpha, double beta) {
  const double s2 = std::sin(2.0 * beta);
  return {std::cos(2.0 * beta), std::sin(alpha) * s2, -std::cos(alpha) * s2};
}

Eigen::Quaterniond qiQuaternionFromAngles(double alpha, double beta) {
  const double sb = std::sin(beta);
  return Eigen::Quaterniond(std::cos(beta), 0.0, std::cos(alpha) * sb, std::sin(alpha) * sb);
}

QiAngles qiAnglesFromTangent(const Eigen::Vector3d& unitTangent) {
  const Eigen::Vector3d t = unitTangent.normalized();
  QiAngles a;
  // atan2 form of acos(T_x)/2, exact near T = +-e_x.
  a.beta = 0.5 * std::atan2(std::hypot(t.y(), t.z()), t.x());
  a.alpha = (t.y() == 0.0 && t.z() == 0.0) ? 0.0 : std::atan2(t.y(), -t.z());
  return a;
}

QiAngles nearestEquivalentAngles(QiAngles raw, QiAngles previous, AngleEquivalence equivalence) {
  if (std::abs(std::sin(2.0 * raw.beta)) < 1e-9) {
    raw.alpha = previous.alpha;
  }
  QiAngles best = raw;
  double bestDist = INFINITY;
  const auto consider = [&](double a, double b) {
    const double d = (a - previous.alpha) * (a - previous.alpha) + (b - previous.beta) * (b - previous.beta);
    if (d < bestDist) {
      bestDist = d;
      best = {a, b};
    }
  };
  const long k0 = std::lround((previous.alpha - raw.alpha) / M_PI);
  for (long k = k0 - 2; k <= k0 + 2; ++k) {
    const bool odd = (k % 2) != 0;
    const double a = raw.alpha + k * M_PI;
    const double b0 = odd ? -raw.beta : raw.beta;
    if (equivalence == AngleEquivalence::PaperOnly) {
      consider(a, b0);
      continue;
    }
    const long m0 = std::lround((previous.beta - b0) / M_PI);
    for (long m = m0 - 1; m <= m0 + 1; ++m) {
      consider(a, b0 + m * M_PI);
    }
  }
  return best;
}

BezierQiSegment::BezierQiSegment(const Eigen::Vector3d& start, double length, const std::array<double, 3>& alpha,
                                 const std::array<double, 3>& beta, int simpsonIntervals)
    : start_(start), length_(length), alpha_(alpha), beta_(beta), simpsonIntervals_(simpsonIntervals) {
  if (!(length > 0.0) || !std::isfinite(length)) {
    std::ostringstream msg;
    msg << "BezierQiSegment: expected a positive finite length, got " << length;
    throw QuaternionCurveError(msg.str());
  }
  if (simpsonIntervals <= 0 || simpsonIntervals % 2 != 0) {
    std::ostringstream msg;
    msg << "BezierQiSegment: expected a positive even Simpson interval count, got " << simpsonIntervals;
    throw QuaternionCurveError(msg.str());
  }
}

namespace {
double quad(const std::array<double, 3>& c, double t) {
  const double u = 1.0 - t;
  return c[0] * u * u + 2.0 * c[1] * u * t + c[2] * t * t;
}
double quadDot(const std::array<double, 3>& c, double t) {
  return 2.0 * ((c[1] - c[0]) * (1.0 - t) + (c[2] - c[1]) * t);
}
double quadDDot(const std::array<double, 3>& c) { return 2.0 * (c[2] - 2.0 * c[1] + c[0]); }
}  // namespace

QiAngles BezierQiSegment::angles(double t) const { return {quad(alpha_, t), quad(beta_, t)}; }
QiAngles BezierQiSegment::anglesDot(double t) const { return {quadDot(alpha_, t), quadDot(beta_, t)}; }
QiAngles BezierQiSegment::anglesDDot(double /*t*/) const { return {quadDDot(alpha_), quadDDot(beta_)}; }

Eigen::Quaterniond BezierQiSegment::quaternion(double t) const {
  const QiAngles a = angles(t);
  return qiQuaternionFromAngles(a.alpha, a.beta);
}

Eigen::Vector3d BezierQiSegment::omega(double t) const {
  const QiAngles a = angles(t);
  const QiAngles d = anglesDot(t);
  const double sb = std::sin(a.beta);
  const double s2b = std::sin(2.0 * a.beta);
  const double ca = std::cos(a.alpha);
  const double sa = std::sin(a.alpha);
  return d.alpha * Eigen::Vector3d(-sb * sb, -0.5 * sa * s2b, 0.5 * ca * s2b) + d.beta * Eigen::Vector3d(0.0, ca, sa);
}

Eigen::Vector3d BezierQiSegment::tangent(double t) const {
  const QiAngles a = angles(t);
  return qiTangentFromAngles(a.alpha, a.beta);
}

Eigen::Vector3d BezierQiSegment::point(double t) const {
  if (t == 0.0) {
    return start_;
  }
  return start_ + length_ * integrateSimpson([this](double x) { return tangent(x); }, 0.0, t, simpsonIntervals_);
}

Eigen::Vector3d BezierQiSegment::chordIntegral() const {
  return integrateSimpson([this](double x) { return tangent(x); }, 0.0, 1.0, simpsonIntervals_);
}

Eigen::Vector3d BezierQiSegment::curvatureVector(double t) const {
  return (2.0 / length_) * rotateFixedVector(quaternion(t), omega(t).cross(Eigen::Vector3d::UnitX()));
}

double BezierQiSegment::curvature(double t) const {
  const QiAngles a = angles(t);
  const QiAngles d = anglesDot(t);
  const double s2b = std::sin(2.0 * a.beta);
  return std::sqrt(d.alpha * d.alpha * s2b * s2b + 4.0 * d.beta * d.beta) / length_;
}

double BezierQiSegment::curvatureDerivative(double t) const {
  const double k = curvature(t);
  if (k <= 0.0) {
    return 0.0;
  }
  const QiAngles a = angles(t);
  const QiAngles d = anglesDot(t);
  const QiAngles dd = anglesDDot(t);
  const double s2b = std::sin(2.0 * a.beta);
  const double num = d.alpha * dd.alpha * s2b * s2b + d.alpha * d.alpha * d.beta * std::sin(4.0 * a.beta) +
                     4.0 * d.beta * dd.beta;
  return num / (length_ * length_ * length_ * k);
}

double BezierQiSegment::torsion(double t) const {
  const QiAngles a = angles(t);
  const QiAngles d = anglesDot(t);
  const QiAngles dd = anglesDDot(t);
  const double s2b = std::sin(2.0 * a.beta);
  const double c2b = std::cos(2.0 * a.beta);
  const double den = 0.25 * d.alpha * d.alpha * s2b * s2b + d.beta * d.beta;
  if (den <= 1e-300) {
    return 0.0;
  }
  const double num = d.beta * d.beta * d.alpha * c2b + 0.5 * s2b * (d.beta * dd.alpha - d.alpha * dd.beta);
  return (d.alpha * c2b + num / den) / length_;
}

}  // namespace ffdkit::geometry::quaternion
