#include "span_quadrature.h"

namespace ffdkit::geometry::g3::detail {

const GaussLegendreRule& defaultRule() {
  static const GaussLegendreRule rule = gaussLegendreRule(16);
  return rule;
}

SpanMoments cubicSpanMoments(const GaussLegendreRule& rule, const Eigen::Vector4d& b, int panels) {
  SpanMoments sum = SpanMoments::Zero();
  const double w = 1.0 / panels;
  for (int p = 0; p < panels; ++p) {
    sum += integrateGaussLegendre(rule, p * w, (p + 1) * w, [&](double t) {
      const double u = 1.0 - t;
      const double bern[4] = {u * u * u, 3.0 * u * u * t, 3.0 * u * t * t, t * t * t};
      const double angle = b[0] * bern[0] + b[1] * bern[1] + b[2] * bern[2] + b[3] * bern[3];
      const double c = std::cos(angle);
      const double s = std::sin(angle);
      SpanMoments m;
      m[0] = c;
      m[1] = s;
      for (int k = 0; k < 4; ++k) {
        m[2 + 2 * k] = bern[k] * c;
        m[3 + 2 * k] = bern[k] * s;
      }
      return m;
    });
  }
  return sum;
}

}  // namespace ffdkit::geometry::g3::detail
