#include "ffdkit/geometry/gauss_legendre.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace ffdkit::geometry {

GaussLegendreRule gaussLegendreRule(int n) {
  if (n < 1) {
    throw std::invalid_argument("gaussLegendreRule: need n >= 1 points, got " + std::to_string(n));
  }
  GaussLegendreRule rule{Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Tricomi's initial guess for the i-th root, then Newton on P_n.
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double pk = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = pk;
      }
      // p1 = P_n(x), p0 = P_{n-1}(x); P_n' from the standard identity.
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    rule.nodes[i] = -x;
    rule.nodes[n - 1 - i] = x;
    rule.weights[i] = w;
    rule.weights[n - 1 - i] = w;
  }
  return rule;
}

}  // namespace ffdkit::geometry
