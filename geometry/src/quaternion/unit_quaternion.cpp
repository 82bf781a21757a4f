#include "ffdkit/geometry/quaternion/unit_quaternion.h"

#include <cmath>
#include <sstream>

#include "ffdkit/geometry/quaternion/quaternion_error.h"

namespace ffdkit::geometry::quaternion {

Eigen::Quaterniond pureQuaternion(const Eigen::Vector3d& v) {
  return Eigen::Quaterniond(0.0, v.x(), v.y(), v.z());
}

Eigen::Quaterniond quaternionExp(const Eigen::Vector3d& v) {
  const double theta = v.norm();
  // sin(theta)/theta with its series near 0 keeps exp smooth for finite differences.
  const double sinc = theta < 1e-8 ? 1.0 - theta * theta / 6.0 : std::sin(theta) / theta;
  const Eigen::Vector3d u = sinc * v;
  return Eigen::Quaterniond(std::cos(theta), u.x(), u.y(), u.z());
}

Eigen::Vector3d quaternionLog(const Eigen::Quaterniond& q) {
  const Eigen::Vector3d u = q.vec();
  const double s = u.norm();
  const double norm = std::sqrt(q.w() * q.w() + s * s);
  if (norm == 0.0 || (s <= 1e-300 && q.w() < 0.0)) {
    std::ostringstream msg;
    msg << "quaternionLog: expected a quaternion off the negative real axis, got (" << q.w() << ", " << q.x()
        << ", " << q.y() << ", " << q.z() << ") whose rotation axis is undefined";
    throw QuaternionCurveError(msg.str());
  }
  const double theta = std::atan2(s, q.w());
  if (s < 1e-8 * norm) {
    // theta ~ s/w: the series keeps log smooth near the identity.
    return u / q.w();
  }
  return (theta / s) * u;
}

Eigen::Vector3d rotateFixedVector(const Eigen::Quaterniond& q, const Eigen::Vector3d& v) {
  const Eigen::Vector3d u = q.vec();
  const Eigen::Vector3d uv = u.cross(v);
  return v + 2.0 * q.w() * uv + 2.0 * u.cross(uv);
}

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

Eigen::Vector3d slerpSphere(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t) {
  const double phi = angleBetween(a, b);
  if (phi > M_PI - 1e-12) {
    std::ostringstream msg;
    msg << "slerpSphere: expected non-antipodal directions, got angle " << phi << " rad between (" << a.transpose()
        << ") and (" << b.transpose() << ")";
    throw QuaternionCurveError(msg.str());
  }
  if (phi < 1e-12) {
    return ((1.0 - t) * a + t * b).normalized();
  }
  const double s = std::sin(phi);
  return (std::sin((1.0 - t) * phi) / s) * a + (std::sin(t * phi) / s) * b;
}

Eigen::Quaterniond minimalRotation(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                   const Eigen::Vector3d& fallbackAxis) {
  const Eigen::Vector3d f = from.normalized();
  const Eigen::Vector3d g = to.normalized();
  const Eigen::Vector3d c = f.cross(g);
  const double theta = angleBetween(f, g);
  if (c.norm() > 1e-14) {
    return quaternionExp(0.5 * theta * c.normalized());
  }
  if (f.dot(g) > 0.0) {
    return Eigen::Quaterniond::Identity();
  }
  Eigen::Vector3d axis = fallbackAxis - fallbackAxis.dot(f) * f;
  if (axis.norm() < 1e-12) {
    axis = f.unitOrthogonal();
  }
  return quaternionExp(0.5 * M_PI * axis.normalized());
}

}  // namespace ffdkit::geometry::quaternion
