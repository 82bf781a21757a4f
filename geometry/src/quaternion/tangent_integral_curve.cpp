#include "ffdkit/geometry/quaternion/tangent_integral_curve.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "ffdkit/geometry/quaternion/frenet.h"
#include "ffdkit/geometry/quaternion/quaternion_error.h"
#include "ffdkit/geometry/quaternion/tangent_integration.h"
#include "ffdkit/geometry/quaternion/unit_quaternion.h"

namespace ffdkit::geometry::quaternion {

namespace {
void requirePositiveLength(const char* where, double length) {
  if (!(length > 0.0) || !std::isfinite(length)) {
    std::ostringstream msg;
    msg << where << ": expected a positive finite length, got " << length;
    throw QuaternionCurveError(msg.str());
  }
}
}  // namespace

TangentIntegralCurve::TangentIntegralCurve(SphereBezierTangent tangentPath, double length, const Eigen::Vector3d& start,
                                           TangentQuadrature quadrature)
    : path_(std::move(tangentPath)), length_(length), start_(start), quadrature_(quadrature) {
  requirePositiveLength("TangentIntegralCurve", length);
}

Eigen::Vector3d TangentIntegralCurve::position(double s) const {
  Eigen::VectorXd t(1);
  t[0] = std::clamp(s / length_, 0.0, 1.0);
  const Eigen::MatrixX3d i =
      cumulativeGaussLegendre([this](double x) { return path_.tangent(x); }, t, quadrature_.order, quadrature_.panels);
  return start_ + length_ * i.row(0).transpose();
}

Eigen::MatrixX3d TangentIntegralCurve::samplePositions(int count) const {
  if (count < 2) {
    std::ostringstream msg;
    msg << "TangentIntegralCurve::samplePositions: expected at least 2 samples, got " << count;
    throw QuaternionCurveError(msg.str());
  }
  const Eigen::MatrixX3d i = cumulativeGaussLegendre([this](double x) { return path_.tangent(x); },
                                                     Eigen::VectorXd::LinSpaced(count, 0.0, 1.0), quadrature_.order,
                                                     quadrature_.panels);
  return (length_ * i).rowwise() + start_.transpose();
}

Eigen::Vector3d TangentIntegralCurve::tangent(double s) const { return path_.tangent(std::clamp(s / length_, 0.0, 1.0)); }

double TangentIntegralCurve::curvature(double s) const {
  return path_.tangentDt(std::clamp(s / length_, 0.0, 1.0)).norm() / length_;
}

double TangentIntegralCurve::torsion(double s) const {
  const double t = std::clamp(s / length_, 0.0, 1.0);
  return torsionFromTangentDerivatives(path_.tangent(t), path_.tangentDt(t), path_.tangentDtt(t), length_);
}

Eigen::Vector3d TangentIntegralCurve::curvatureVector(double s) const {
  return path_.tangentDt(std::clamp(s / length_, 0.0, 1.0)) / length_;
}

QuaternionIntegralCurve::QuaternionIntegralCurve(CumulativeBezierQuaternion rotation, const Eigen::Vector3d& v,
                                                 double length, const Eigen::Vector3d& start,
                                                 TangentQuadrature quadrature)
    : rotation_(std::move(rotation)), v_(v), length_(length), start_(start), quadrature_(quadrature) {
  requirePositiveLength("QuaternionIntegralCurve", length);
  if (!(v.norm() > 0.0)) {
    throw QuaternionCurveError("QuaternionIntegralCurve: expected a non-zero fixed vector v, got (0, 0, 0)");
  }
  v_.normalize();
}

Eigen::Vector3d QuaternionIntegralCurve::tangentAt(double t) const {
  return rotateFixedVector(rotation_.value(t).normalized(), v_);
}

Eigen::Vector3d QuaternionIntegralCurve::tangentDtAt(double t) const {
  Eigen::Quaterniond q, dq;
  rotation_.evaluate(t, q, dq);
  const Eigen::Vector3d omega = 2.0 * (dq * q.conjugate()).vec() / q.squaredNorm();
  return omega.cross(rotateFixedVector(q.normalized(), v_));
}

Eigen::Vector3d QuaternionIntegralCurve::position(double s) const {
  Eigen::VectorXd t(1);
  t[0] = std::clamp(s / length_, 0.0, 1.0);
  const Eigen::MatrixX3d i =
      cumulativeGaussLegendre([this](double x) { return tangentAt(x); }, t, quadrature_.order, quadrature_.panels);
  return start_ + length_ * i.row(0).transpose();
}

Eigen::Vector3d QuaternionIntegralCurve::tangent(double s) const { return tangentAt(std::clamp(s / length_, 0.0, 1.0)); }

double QuaternionIntegralCurve::curvature(double s) const {
  return tangentDtAt(std::clamp(s / length_, 0.0, 1.0)).norm() / length_;
}

double QuaternionIntegralCurve::torsion(double s) const {
  const double t = std::clamp(s / length_, 0.0, 1.0);
  const Eigen::Vector3d tt = fivePointDerivative([this](double x) { return tangentDtAt(x); }, t);
  return torsionFromTangentDerivatives(tangentAt(t), tangentDtAt(t), tt, length_);
}

Eigen::Vector3d QuaternionIntegralCurve::curvatureVector(double s) const {
  return tangentDtAt(std::clamp(s / length_, 0.0, 1.0)) / length_;
}

}  // namespace ffdkit::geometry::quaternion
