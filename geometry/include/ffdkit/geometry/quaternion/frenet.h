#pragma once

#include <functional>

#include <Eigen/Core>

namespace ffdkit::geometry::quaternion {

/// Torsion of an arc-length curve of total length L from its unit tangent T(t), t = s/L, and the
/// t-derivatives Tt, Ttt: tau = det(T, Tt, Ttt) / (L |Tt|^2). Returns 0 where |Tt| < 1e-8
/// (cusp of the tangent path: tau undefined there). @see Sphere-tangent report, sec. 1.
double torsionFromTangentDerivatives(const Eigen::Vector3d& T, const Eigen::Vector3d& Tt, const Eigen::Vector3d& Ttt,
                                     double L);

/// Derivative of f at t in [0, 1] by a 5-point stencil of step h: central inside [2h, 1-2h],
/// one-sided (forward or backward, same order) within 2h of an end, so f is never evaluated
/// outside [0, 1].
Eigen::Vector3d fivePointDerivative(const std::function<Eigen::Vector3d(double)>& f, double t, double h = 1e-4);

}  // namespace ffdkit::geometry::quaternion
