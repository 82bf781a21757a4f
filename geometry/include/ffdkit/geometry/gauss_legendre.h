#pragma once

#include <type_traits>

#include <Eigen/Core>

namespace ffdkit::geometry {

/// Nodes and weights of the n-point Gauss-Legendre rule on [-1, 1].
struct GaussLegendreRule {
  Eigen::VectorXd nodes;    ///< n nodes, ascending, in (-1, 1)
  Eigen::VectorXd weights;  ///< n positive weights, summing to 2
};

/// The n-point Gauss-Legendre rule (exact for polynomials of degree <= 2n-1), computed by
/// Newton on the Legendre recurrence to full double precision.
/// @throws std::invalid_argument if n < 1.
GaussLegendreRule gaussLegendreRule(int n);

/// Integral of f over [a, b] with the rule mapped affinely from [-1, 1].
/// f: double -> T, where T is double or a fixed-size Eigen vector (anything with T * double
/// and T += T).
template <class F>
auto integrateGaussLegendre(const GaussLegendreRule& rule, double a, double b, F&& f) {
  using Value = std::remove_cvref_t<decltype(f(a))>;
  const double half = 0.5 * (b - a);
  const double mid = 0.5 * (a + b);
  Value sum = f(mid + half * rule.nodes[0]) * rule.weights[0];
  for (Eigen::Index i = 1; i < rule.nodes.size(); ++i) {
    sum += f(mid + half * rule.nodes[i]) * rule.weights[i];
  }
  return Value(sum * half);
}

}  // namespace ffdkit::geometry
