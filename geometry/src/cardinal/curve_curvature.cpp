#include "ffdkit/geometry/cardinal/curve_curvature.h"

#include <cmath>

#include <Eigen/Geometry>

#include "ffdkit/geometry/gauss_legendre.h"

namespace ffdkit::geometry::cardinal {

CurvatureSamples sampleCurvature(const std::function<Eigen::Vector3d(double, int)>& derivative,
                                 const Eigen::VectorXd& params) {
  const Eigen::Index count = params.size();
  CurvatureSamples out;
  out.parameter = params;
  out.arcLength = Eigen::VectorXd::Zero(count);
  out.curvature = Eigen::VectorXd::Zero(count);
  out.torsion = Eigen::VectorXd::Zero(count);
  out.points.resize(count, 3);
  out.normals = Eigen::MatrixX3d::Zero(count, 3);
  const GaussLegendreRule rule = gaussLegendreRule(8);
  for (Eigen::Index k = 0; k < count; ++k) {
    const double x = params[k];
    const Eigen::Vector3d d1 = derivative(x, 1), d2 = derivative(x, 2), d3 = derivative(x, 3);
    out.points.row(k) = derivative(x, 0).transpose();
    const Eigen::Vector3d b = d1.cross(d2);
    const double speed = d1.norm();
    const double bb = b.squaredNorm();
    if (speed > 0.0) out.curvature[k] = std::sqrt(bb) / (speed * speed * speed);
    if (bb > 0.0) {
      out.torsion[k] = b.dot(d3) / bb;
      // Principal normal: B x T.
      out.normals.row(k) = b.cross(d1).normalized().transpose();
    }
    if (k > 0) {
      out.arcLength[k] = out.arcLength[k - 1] +
                         integrateGaussLegendre(rule, params[k - 1], x, [&](double y) {
                           return derivative(y, 1).norm();
                         });
    }
  }
  return out;
}

}  // namespace ffdkit::geometry::cardinal
