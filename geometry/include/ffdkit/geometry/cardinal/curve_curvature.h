#pragma once

#include <functional>

#include <Eigen/Core>

namespace ffdkit::geometry::cardinal {

/// Curvature (and torsion) sampled against arc length, for plots and curvature combs.
struct CurvatureSamples {
  Eigen::VectorXd parameter;  ///< curve parameter of each sample
  Eigen::VectorXd arcLength;  ///< arc length from the start (Gauss-Legendre, 8 points per step)
  Eigen::VectorXd curvature;  ///< |Q' x Q''| / |Q'|^3 (0 where Q' = 0)
  Eigen::VectorXd torsion;    ///< (Q' x Q'') . Q''' / |Q' x Q''|^2 (0 where Q' x Q'' = 0)
  Eigen::MatrixX3d points;    ///< Q at each sample
  Eigen::MatrixX3d normals;   ///< principal normal (zero where undefined), for combs
};

/// Samples a curve given by its derivatives: derivative(x, k) = Q^(k)(x), k = 0..3, at the
/// parameters `params` (ascending). Each parameter is evaluated as-is (right-hand limits at
/// knots are the evaluator's business).
CurvatureSamples sampleCurvature(const std::function<Eigen::Vector3d(double, int)>& derivative,
                                 const Eigen::VectorXd& params);

}  // namespace ffdkit::geometry::cardinal
