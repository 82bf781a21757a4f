#pragma once

#include <Eigen/Core>

namespace ffdkit::geometry::g3 {

/// Bezier ordinates b_0..b_{3n} of the clamped cubic B-spline psi(s) (triple end knots,
/// Farin's convention: knots s_{-2}=s_{-1}=s_0=0 < s_1 < ... < s_n=s_{n+1}=s_{n+2}), by
/// Boehm's conversion with the phantom lengths Delta s_{-1} = Delta s_n = 0.
///   spanLengths  n     Delta s_0..Delta s_{n-1}, all > 0 (not checked here: callers validate)
///   deBoor       n+3   d_{-1}..d_{n+1}
///   returns      3n+1  b_0..b_{3n}; b_{3i} = psi(s_i)
/// @see Kuroda et al. 1997, sec. 3 (Boehm, ref. 12), appendix getb3 app. 1.
Eigen::VectorXd bezierOrdinatesFromDeBoor(const Eigen::Ref<const Eigen::VectorXd>& spanLengths,
                                          const Eigen::Ref<const Eigen::VectorXd>& deBoor);

/// Analytic derivative of bezierOrdinatesFromDeBoor with respect to the unknown vector
/// v = (Delta s_0..Delta s_{n-1}, d_{-1}..d_{n+1}) (the paper's text order,
/// Kuroda et al. 1997, sec. 3).
///   returns (3n+1) x (2n+3), row k = d b_k / d v.
/// Uses the weight form b_{3i+1} = (1-alpha_i) d_i + alpha_i d_{i+1}, ... (Farin;
/// Kuroda et al. 1997, sec. 2).
Eigen::MatrixXd bezierOrdinateJacobian(const Eigen::Ref<const Eigen::VectorXd>& spanLengths,
                                       const Eigen::Ref<const Eigen::VectorXd>& deBoor);

}  // namespace ffdkit::geometry::g3
