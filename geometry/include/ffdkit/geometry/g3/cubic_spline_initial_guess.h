#pragma once

#include <Eigen/Core>

namespace ffdkit::geometry::g3 {

/// The initial guess of the G3 solve, taken from a parametric cubic C^2 interpolating spline
/// (chord-length parameter, not-a-knot ends; the interpolating parabola for 3 points, the line
/// for 2), as the paper does in sec. 4.
struct CubicSplineInitialGuess {
  Eigen::VectorXd unknowns;     ///< 2n+3: (Delta s_0..Delta s_{n-1}, d_{-1}..d_{n+1})
  Eigen::VectorXd spanLengths;  ///< n: arc lengths of the cubic's spans (64 panels x 16 Gauss-Legendre nodes)
  Eigen::VectorXd deBoor;       ///< n+3: unwrapped cubic tangent angle at the Greville abscissae
  Eigen::VectorXd curvatureAtPoints;  ///< n+1: the cubic's curvature at p_0..p_n
  Eigen::VectorXd tangentAtPoints;    ///< n+1: the cubic's unwrapped tangent angle at p_0..p_n
  double length = 0.0;                ///< the cubic's total arc length
};

/// Builds the guess for points p_0..p_n ((n+1) x 2, n >= 1).
/// The Greville abscissae xi_j = (s_{j-1}+s_j+s_{j+1})/3 are mapped back to the spline
/// parameter through a 64-per-span arc-length table, and the tangent angle is unwrapped
/// continuously along the spline (Kuroda et al. 1997, sec. 4 steps 1-3).
/// @throws G3InputError for < 2 points, non-finite or coincident consecutive points.
/// @see Kuroda et al. 1997, secs. 4, 5 (not-a-knot, Fig. 2(a)).
CubicSplineInitialGuess initialGuessFromCubicSpline(const Eigen::Ref<const Eigen::MatrixX2d>& points);

}  // namespace ffdkit::geometry::g3
