// ffdkit::geometry from an installed package: an n-point Gauss-Legendre rule integrates
// polynomials up to degree 2n - 1 exactly (x^4 on [0, 1] with 3 points: 1/5) and not degree 2n
// (x^6 with 3 points: not 1/7).
#include <cmath>

#include "../consumer_check.h"
#include "ffdkit/geometry/gauss_legendre.h"

using namespace ffdkit;

int main() {
  const auto rule = geometry::gaussLegendreRule(3);
  const double quartic = geometry::integrateGaussLegendre(rule, 0.0, 1.0, [](double x) { return std::pow(x, 4); });
  const double sextic = geometry::integrateGaussLegendre(rule, 0.0, 1.0, [](double x) { return std::pow(x, 6); });
  consumer::check(std::abs(quartic - 0.2) < 1e-14, "x^4 on [0, 1] is 1/5");
  consumer::check(std::abs(sextic - 1.0 / 7.0) > 1e-4, "x^6 is beyond a 3-point rule");
  return consumer::exitCode();
}
