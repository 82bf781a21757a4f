#include "ffdkit/geometry/curvenet/ngon_domain.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace ffdkit::geometry::curvenet {

NGonDomain::NGonDomain(int sides) : n_(sides) {
  if (sides < 3) {
    throw std::invalid_argument("N-gon domain needs >= 3 sides, got " + std::to_string(sides));
  }
  for (int k = 0; k < n_; ++k) {
    const double th = -std::numbers::pi / 2 - std::numbers::pi / n_ + 2 * std::numbers::pi * k / n_;
    vertices_.emplace_back(std::cos(th), std::sin(th));
  }
}

Eigen::Vector2d NGonDomain::vertex(int k) const { return vertices_[((k % n_) + n_) % n_]; }

std::vector<Jet> NGonDomain::barycentric(const Eigen::Vector2d& p) const {
  // a_k(p) = 1/2 det[p_k - p, p_{k+1} - p]: affine in p, so its jet has constant gradient.
  std::vector<Jet> a(n_);
  for (int k = 0; k < n_; ++k) {
    const Eigen::Vector2d pk = vertex(k), pk1 = vertex(k + 1);
    const Eigen::Vector2d d0 = pk - p, d1 = pk1 - p;
    a[k] = Jet{0.5 * (d0.x() * d1.y() - d0.y() * d1.x()), 0.5 * (pk.y() - pk1.y()),
               0.5 * (pk1.x() - pk.x()), 0, 0, 0};
  }
  std::vector<Jet> pi(n_);
  Jet total = Jet::constant(0.0);
  for (int i = 0; i < n_; ++i) {
    Jet prod = Jet::constant(1.0);
    for (int k = 0; k < n_; ++k) {
      if (k == (i - 1 + n_) % n_ || k == i) continue;
      prod = prod * a[k];
    }
    pi[i] = prod;
    total = total + prod;
  }
  for (int i = 0; i < n_; ++i) pi[i] = pi[i] / total;
  return pi;
}

Jet NGonDomain::uTilde(int i, const std::vector<Jet>& b) const {
  auto at = [&](int k) -> const Jet& { return b[((k % n_) + n_) % n_]; };
  Jet sum = Jet::constant(0.0);
  if (n_ % 2 == 0) {
    for (int k = 1; k <= n_ / 2; ++k) sum = sum + at(i + k);
    return sum;
  }
  for (int k = 1; k <= (n_ - 1) / 2; ++k) sum = sum + at(i + k);
  const Jet denom = 1.0 - at(i + (n_ + 1) / 2);
  if (std::abs(denom.v) < 1e-14) return Jet::constant(0.5);
  return sum / denom;
}

Jet NGonDomain::distance(int i, const std::vector<Jet>& b) const {
  return 1.0 - b[((i % n_) + n_) % n_] - b[((i + 1) % n_ + n_) % n_];
}

std::vector<Jet> NGonDomain::blend(const std::vector<Jet>& b, int exponent) const {
  std::vector<Jet> prod(n_);
  double maxValue = 0.0;
  for (int k = 0; k < n_; ++k) {
    prod[k] = b[k] * b[(k + 1) % n_];
    maxValue = std::max(maxValue, std::abs(prod[k].v));
  }
  std::vector<Jet> result(n_, Jet::constant(0.0));
  if (!(maxValue > 1e-300)) {
    // Exactly at a vertex p_j (b_j = 1): the thesis' rule B_{j-1} = B_j = 1/2 (sec. 5.2.2).
    int j = 0;
    for (int k = 1; k < n_; ++k) {
      if (b[k].v > b[j].v) j = k;
    }
    result[j] = Jet::constant(0.5);
    result[(j - 1 + n_) % n_] = Jet::constant(0.5);
    return result;
  }
  Jet total = Jet::constant(0.0);
  for (int k = 0; k < n_; ++k) {
    const Jet scaled = (1.0 / maxValue) * prod[k];
    Jet f = Jet::constant(1.0);
    for (int e = 0; e < exponent; ++e) f = f * scaled;
    result[k] = f;
    total = total + f;
  }
  for (int k = 0; k < n_; ++k) result[k] = result[k] / total;
  return result;
}

int NGonDomain::vertexAt(const Eigen::Vector2d& p, double tol) const {
  for (int k = 0; k < n_; ++k) {
    if ((p - vertices_[k]).norm() <= tol) return k;
  }
  return -1;
}

}  // namespace ffdkit::geometry::curvenet
