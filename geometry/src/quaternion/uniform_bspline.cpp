#include "ffdkit/geometry/quaternion/uniform_bspline.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>
#include <Eigen/QR>

#include "ffdkit/geometry/gauss_legendre.h"
#include "ffdkit/geometry/quaternion/quaternion_error.h"

namespace ffdkit::geometry::quaternion {

namespace {
// Uniform cubic blending functions (Sakiyama et al. 2001, eq. (13)) and their derivatives at tau in
// [0, 1].
Eigen::Vector4d blending(double t, int order) {
  const double s = 1.0 - t;
  switch (order) {
    case 0:
      return {s * s * s / 6.0, (3 * t * t * t - 6 * t * t + 4) / 6.0, (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6.0,
              t * t * t / 6.0};
    case 1:
      return {-0.5 * s * s, 1.5 * t * t - 2 * t, -1.5 * t * t + t + 0.5, 0.5 * t * t};
    case 2:
      return {s, 3 * t - 2, -3 * t + 1, t};
    default:
      return {-1.0, 3.0, -3.0, 1.0};
  }
}
}  // namespace

UniformCubicBSpline::UniformCubicBSpline(Eigen::MatrixX3d control) : control_(std::move(control)) {
  if (control_.rows() < 4) {
    std::ostringstream msg;
    msg << "UniformCubicBSpline: expected at least 4 control points, got " << control_.rows();
    throw QuaternionCurveError(msg.str());
  }
}

Eigen::Vector3d UniformCubicBSpline::derivative(double x, int order) const {
  const int m = std::clamp(static_cast<int>(std::floor(x)), 0, spans() - 1);
  const double t = std::clamp(x, 0.0, static_cast<double>(spans())) - m;
  const Eigen::Vector4d b = blending(t, order);
  return (control_.middleRows(m, 4).transpose() * b);
}

double UniformCubicBSpline::curvature(double x) const {
  const Eigen::Vector3d d1 = derivative(x, 1);
  const double n = d1.norm();
  return d1.cross(derivative(x, 2)).norm() / (n * n * n);
}

double UniformCubicBSpline::signedPlanarCurvature(double x) const {
  const Eigen::Vector3d d1 = derivative(x, 1);
  const double n = d1.norm();
  return d1.cross(derivative(x, 2)).z() / (n * n * n);
}

double UniformCubicBSpline::length() const {
  const GaussLegendreRule rule = gaussLegendreRule(8);
  double sum = 0.0;
  for (int m = 0; m < spans(); ++m) {
    for (int p = 0; p < 4; ++p) {
      sum += integrateGaussLegendre(rule, m + p / 4.0, m + (p + 1) / 4.0,
                                    [this](double x) { return derivative(x, 1).norm(); });
    }
  }
  return sum;
}

UniformCubicBSpline fitLeastSquaresCubicBSpline(const Eigen::MatrixX3d& points, const Eigen::VectorXd& u, int spans) {
  if (spans < 1 || u.size() != points.rows()) {
    std::ostringstream msg;
    msg << "fitLeastSquaresCubicBSpline: expected spans >= 1 and one parameter per point, got spans " << spans << ", "
        << u.size() << " parameters for " << points.rows() << " points";
    throw QuaternionCurveError(msg.str());
  }
  if (!u.allFinite()) throw QuaternionCurveError("fitLeastSquaresCubicBSpline: expected finite parameters");
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(points.rows(), spans + 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const int m = std::clamp(static_cast<int>(std::floor(u[i])), 0, spans - 1);
    a.block<1, 4>(i, m) = blending(u[i] - m, 0).transpose();
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < spans + 3) {
    std::ostringstream msg;
    msg << "fitLeastSquaresCubicBSpline: rank " << qr.rank() << " < " << spans + 3
        << " control points: too few points per span";
    throw QuaternionCurveError(msg.str());
  }
  return UniformCubicBSpline(qr.solve(Eigen::MatrixXd(points)));
}

UniformCubicBSpline convertToCubicBSpline(const ArcLengthCurve& curve, int spans, int samples) {
  const Eigen::MatrixX3d p = curve.samplePositions(samples);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(samples, 0.0, static_cast<double>(spans));
  return fitLeastSquaresCubicBSpline(p, x, spans);
}

}  // namespace ffdkit::geometry::quaternion
