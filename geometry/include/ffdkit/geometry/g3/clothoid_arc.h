#pragma once

#include <Eigen/Core>

namespace ffdkit::geometry::g3 {

/// A clothoid (Euler spiral) arc: curvature linear in arc length,
/// psi(sigma) = startAngle + startCurvature sigma + sharpness sigma^2 / 2, sigma in [0, length].
/// Positions integrate (cos psi, sin psi) by composite Gauss-Legendre rather than Fresnel
/// integrals, which cancel badly for small sharpness (Kuroda et al. 1997, sec. 6, "Clothoid arc
/// evaluation").
struct ClothoidArc {
  Eigen::Vector2d start = Eigen::Vector2d::Zero();  ///< start point
  double startAngle = 0.0;      ///< rad
  double startCurvature = 0.0;  ///< 1/length
  double sharpness = 0.0;       ///< dkappa/ds, 1/length^2
  double length = 0.0;          ///< > 0

  /// Tangent angle at arc length sigma from the start (rad).
  double angle(double sigma) const { return startAngle + sigma * (startCurvature + 0.5 * sharpness * sigma); }
  /// Curvature at arc length sigma from the start.
  double curvature(double sigma) const { return startCurvature + sharpness * sigma; }
  /// Tangent angle at the end.
  double endAngle() const { return angle(length); }
  /// Curvature at the end.
  double endCurvature() const { return curvature(length); }
  /// r(sigma), sigma in [0, length] (not checked: extrapolation is well defined).
  Eigen::Vector2d position(double sigma) const;
  /// Where the arc ends, r(length).
  Eigen::Vector2d endPoint() const { return position(length); }
};

}  // namespace ffdkit::geometry::g3
