#pragma once
// Internal: composite Gauss-Legendre integrals of the unit tangent over one span. Shared by
// evaluation, the Newton residual / Jacobian and the bi-clothoid fit so that they all use the
// same nodes.

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "ffdkit/geometry/gauss_legendre.h"

namespace ffdkit::geometry::g3::detail {

/// The default 16-point rule, built once.
const GaussLegendreRule& defaultRule();

/// One panel per radian of turning: 16 nodes then reproduce every reference value of the
/// tests to ~1e-15.
constexpr double kMaxTurnPerPanel = 1.0;

/// Panel count P = max(1, ceil(V / maxTurn)), V bounding the total turning from the control
/// polygon of psi.
inline int panelCount(double totalTurningBound, double maxTurnPerPanel) {
  const double p = std::ceil(totalTurningBound / maxTurnPerPanel);
  if (!(p >= 1.0)) return 1;
  return static_cast<int>(std::min(p, 4096.0));
}

inline double cubicBezier(const Eigen::Vector4d& b, double t) {
  const double u = 1.0 - t;
  return b[0] * u * u * u + 3.0 * b[1] * u * u * t + 3.0 * b[2] * u * t * t + b[3] * t * t * t;
}

inline double controlPolygonTurning(const Eigen::Vector4d& b) {
  return std::abs(b[1] - b[0]) + std::abs(b[2] - b[1]) + std::abs(b[3] - b[2]);
}

/// integral_a^b (cos psi(t), sin psi(t)) dt, over `panels` equal panels.
template <class Psi>
Eigen::Vector2d integrateTangent(const GaussLegendreRule& rule, Psi&& psi, double a, double b, int panels) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  const double w = (b - a) / panels;
  for (int p = 0; p < panels; ++p) {
    sum += integrateGaussLegendre(rule, a + p * w, a + (p + 1) * w, [&](double t) {
      const double angle = psi(t);
      return Eigen::Vector2d(std::cos(angle), std::sin(angle));
    });
  }
  return sum;
}

/// I = integral_0^1 (cos, sin) psi and the Bernstein moments M(k) = integral_0^1 B^3_k (cos, sin)
/// psi, for the analytic Jacobian. Layout: rows 0-1 I, rows 2+2k..3+2k M_k.
using SpanMoments = Eigen::Matrix<double, 10, 1>;
SpanMoments cubicSpanMoments(const GaussLegendreRule& rule, const Eigen::Vector4d& b, int panels);

}  // namespace ffdkit::geometry::g3::detail
