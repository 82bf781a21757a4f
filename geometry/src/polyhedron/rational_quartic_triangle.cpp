#include "ffdkit/geometry/polyhedron/rational_quartic_triangle.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

namespace ffdkit::geometry::polyhedron {
namespace {

struct Blend {
  Eigen::Vector3d value, dx, dy;
};

// f(x, y; a, b) = x y (x a + y b) / (x + y) and its partials (Kuriyama 1996, sec. 4.3.2).
Blend blend(double x, double y, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double s = x + y;
  if (s <= 0.0) return {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  const double s2 = s * s;
  return {x * y * (x * a + y * b) / s, y * a + (y * y * y / s2) * (b - a), x * b + (x * x * x / s2) * (a - b)};
}

double power(double x, int k) {
  double r = 1.0;
  for (int i = 0; i < k; ++i) r *= x;
  return r;
}

constexpr double kFactorial[5] = {1, 1, 2, 6, 24};

}  // namespace

std::array<Eigen::Vector3d, 5> elevateCubic(const std::array<Eigen::Vector3d, 4>& cubic) {
  std::array<Eigen::Vector3d, 5> e;
  e[0] = cubic[0];
  for (int i = 1; i < 4; ++i) e[i] = (i / 4.0) * cubic[i - 1] + (1.0 - i / 4.0) * cubic[i];
  e[4] = cubic[3];
  return e;
}

PatchDerivatives RationalQuarticTriangle::evaluateWithPartials(double u, double v, double w) const {
  PatchDerivatives out{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                       Eigen::Vector3d::Zero()};
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; i + j <= 4; ++j) {
      const int k = 4 - i - j;
      if (i > 0 && j > 0 && k > 0) continue;  // interior slots are the rational blends below
      const double c = 24.0 / (kFactorial[i] * kFactorial[j] * kFactorial[k]);
      const Eigen::Vector3d& p = d[index(i, j)];
      const double pu = power(u, i), pv = power(v, j), pw = power(w, k);
      out.point += c * pu * pv * pw * p;
      if (i > 0) out.du += c * i * power(u, i - 1) * pv * pw * p;
      if (j > 0) out.dv += c * j * pu * power(v, j - 1) * pw * p;
      if (k > 0) out.dw += c * k * pu * pv * power(w, k - 1) * p;
    }
  }
  // 12 u^2 f(v, w; D^w_211, D^v_211) and its two companions (eq. (4.18)).
  const Blend a = blend(v, w, dw211, dv211);
  out.point += 12.0 * u * u * a.value;
  out.du += 24.0 * u * a.value;
  out.dv += 12.0 * u * u * a.dx;
  out.dw += 12.0 * u * u * a.dy;
  const Blend b = blend(u, w, dw121, du121);
  out.point += 12.0 * v * v * b.value;
  out.dv += 24.0 * v * b.value;
  out.du += 12.0 * v * v * b.dx;
  out.dw += 12.0 * v * v * b.dy;
  const Blend c = blend(u, v, dv112, du112);
  out.point += 12.0 * w * w * c.value;
  out.dw += 24.0 * w * c.value;
  out.du += 12.0 * w * w * c.dx;
  out.dv += 12.0 * w * w * c.dy;
  return out;
}

Eigen::Vector3d& RationalQuarticTriangle::subPoint(int corner, int other) {
  if (corner < 0 || corner > 2 || other < 0 || other > 2 || corner == other) {
    throw std::invalid_argument("RationalQuarticTriangle::subPoint: expected two distinct corner slots in 0..2, got (" +
                                std::to_string(corner) + ", " + std::to_string(other) + ")");
  }
  // D^s belongs to edge s = 0: AB is w = 0, AC is v = 0, BC is u = 0 (eq. (4.18)).
  if (corner == 0) return other == 1 ? dw211 : dv211;
  if (corner == 1) return other == 0 ? dw121 : du121;
  return other == 0 ? dv112 : du112;
}

const Eigen::Vector3d& RationalQuarticTriangle::subPoint(int corner, int other) const {
  return const_cast<RationalQuarticTriangle*>(this)->subPoint(corner, other);
}

int RationalQuarticTriangle::cornerSlot(int vertex) const {
  for (int k = 0; k < 3; ++k) {
    if (corners[k] == vertex) return k;
  }
  return -1;
}

Eigen::Vector3d RationalQuarticTriangle::evaluate(double u, double v, double w) const {
  return evaluateWithPartials(u, v, w).point;
}

Eigen::Vector3d RationalQuarticTriangle::normal(double u, double v, double w) const {
  return unitNormal(evaluateWithPartials(u, v, w));
}

Eigen::Vector3d unitNormal(const PatchDerivatives& p) {
  const Eigen::Vector3d n = (p.du - p.dw).cross(p.dv - p.dw);
  const double length = n.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return Eigen::Vector3d::Zero();
  return n / length;
}

}  // namespace ffdkit::geometry::polyhedron
