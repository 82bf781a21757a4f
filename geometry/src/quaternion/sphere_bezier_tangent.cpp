#include "ffdkit/geometry/quaternion/sphere_bezier_tangent.h"

#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "ffdkit/geometry/quaternion/frenet.h"
#include "ffdkit/geometry/quaternion/quaternion_error.h"
#include "ffdkit/geometry/quaternion/unit_quaternion.h"

namespace ffdkit::geometry::quaternion {

namespace {
std::vector<Eigen::Vector3d> checkedDirections(std::vector<Eigen::Vector3d> d) {
  if (d.size() < 2) {
    std::ostringstream msg;
    msg << "SphereBezierTangent: expected at least 2 direction controls, got " << d.size();
    throw QuaternionCurveError(msg.str());
  }
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!(d[i].norm() > 0.0) || !d[i].allFinite()) {
      std::ostringstream msg;
      msg << "SphereBezierTangent: expected non-zero finite direction controls, got (" << d[i].transpose()
          << ") at index " << i;
      throw QuaternionCurveError(msg.str());
    }
    d[i].normalize();
    if (i > 0 && angleBetween(d[i - 1], d[i]) > M_PI - 1e-9) {
      std::ostringstream msg;
      msg << "SphereBezierTangent: controls " << i - 1 << " and " << i
          << " are antipodal (angle within 1e-9 of pi): the arc between them is undefined";
      throw QuaternionCurveError(msg.str());
    }
  }
  return d;
}

std::vector<Eigen::Quaterniond> pureControls(const std::vector<Eigen::Vector3d>& d) {
  std::vector<Eigen::Quaterniond> q;
  for (const auto& v : d) q.push_back(pureQuaternion(v));
  return q;
}
}  // namespace

SphereBezierTangent::SphereBezierTangent(std::vector<Eigen::Vector3d> directions, SphereCurveKind kind)
    : directions_(checkedDirections(std::move(directions))),
      kind_(kind),
      kim_(CumulativeBezierQuaternion::fromControls(pureControls(directions_), ProductForm::Local)) {}

Eigen::Vector3d SphereBezierTangent::tangent(double t) const {
  if (kind_ == SphereCurveKind::KimPure) {
    return kim_.value(t).vec().normalized();
  }
  std::vector<Eigen::Vector3d> level = directions_;
  for (std::size_t r = level.size() - 1; r > 0; --r) {
    for (std::size_t i = 0; i < r; ++i) level[i] = slerpSphere(level[i], level[i + 1], t);
  }
  return level[0].normalized();
}

Eigen::Vector3d SphereBezierTangent::tangentDt(double t) const {
  if (kind_ == SphereCurveKind::KimPure) {
    Eigen::Quaterniond q, dq;
    kim_.evaluate(t, q, dq);
    const Eigen::Vector3d u = q.vec();
    const double n = u.norm();
    const Eigen::Vector3d T = u / n;
    const Eigen::Vector3d ut = dq.vec();
    return (ut - T * T.dot(ut)) / n;
  }
  return fivePointDerivative([this](double x) { return tangent(x); }, t, 1e-3);
}

Eigen::Vector3d SphereBezierTangent::tangentDtt(double t) const {
  return fivePointDerivative([this](double x) { return tangentDt(x); }, t, kind_ == SphereCurveKind::KimPure ? 1e-4 : 1e-3);
}

double SphereBezierTangent::realPart(double t) const {
  if (kind_ != SphereCurveKind::KimPure) return 0.0;
  const Eigen::Quaterniond q = kim_.value(t);
  return std::abs(q.w()) / q.norm();
}

}  // namespace ffdkit::geometry::quaternion
