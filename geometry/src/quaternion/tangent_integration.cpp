#include "ffdkit/geometry/quaternion/tangent_integration.h"

#include <algorithm>
#include <sstream>
#include <vector>

#include "ffdkit/geometry/gauss_legendre.h"
#include "ffdkit/geometry/quaternion/quaternion_error.h"

namespace ffdkit::geometry::quaternion {

namespace {
// Rules are rebuilt by Newton iteration; optimisers integrate thousands of times per fit.
const GaussLegendreRule& cachedRule(int order) {
  thread_local std::vector<GaussLegendreRule> cache;
  if (order <= 64) {
    if (cache.empty()) cache.resize(65);
    if (cache[order].nodes.size() != order) cache[order] = gaussLegendreRule(order);
    return cache[order];
  }
  thread_local GaussLegendreRule big;
  big = gaussLegendreRule(order);
  return big;
}
}  // namespace

Eigen::Vector3d integrateSimpson(const TangentFunction& f, double a, double b, int intervals) {
  if (intervals <= 0 || intervals % 2 != 0) {
    std::ostringstream msg;
    msg << "integrateSimpson: expected a positive even number of subintervals, got " << intervals;
    throw QuaternionCurveError(msg.str());
  }
  const double h = (b - a) / intervals;
  Eigen::Vector3d sum = f(a) + f(b);
  for (int k = 1; k < intervals; ++k) {
    sum += (k % 2 == 1 ? 4.0 : 2.0) * f(a + k * h);
  }
  return sum * (h / 3.0);
}

Eigen::MatrixX3d cumulativeGaussLegendre(const TangentFunction& f, const Eigen::VectorXd& params, int order,
                                         int minPanels) {
  if (order < 1 || minPanels < 1) {
    std::ostringstream msg;
    msg << "cumulativeGaussLegendre: expected order >= 1 and minPanels >= 1, got " << order << " and " << minPanels;
    throw QuaternionCurveError(msg.str());
  }
  for (Eigen::Index k = 0; k < params.size(); ++k) {
    if (params[k] < 0.0 || params[k] > 1.0 || (k > 0 && params[k] < params[k - 1])) {
      std::ostringstream msg;
      msg << "cumulativeGaussLegendre: expected sorted parameters in [0, 1], got " << params[k] << " at index " << k;
      throw QuaternionCurveError(msg.str());
    }
  }
  const GaussLegendreRule& rule = cachedRule(order);
  std::vector<double> breaks(params.data(), params.data() + params.size());
  for (int p = 0; p <= minPanels; ++p) {
    breaks.push_back(static_cast<double>(p) / minPanels);
  }
  std::sort(breaks.begin(), breaks.end());
  Eigen::MatrixX3d out(params.size(), 3);
  Eigen::Vector3d running = Eigen::Vector3d::Zero();
  double at = 0.0;
  std::size_t b = 0;
  for (Eigen::Index k = 0; k < params.size(); ++k) {
    while (b < breaks.size() && breaks[b] <= params[k]) {
      if (breaks[b] > at) {
        running += integrateGaussLegendre(rule, at, breaks[b], f);
        at = breaks[b];
      }
      ++b;
    }
    out.row(k) = running.transpose();
  }
  return out;
}

Eigen::Vector3d integrateGaussLegendrePanels(const TangentFunction& f, int order, int panels) {
  if (order < 1 || panels < 1) {
    std::ostringstream msg;
    msg << "integrateGaussLegendrePanels: expected order >= 1 and panels >= 1, got " << order << " and " << panels;
    throw QuaternionCurveError(msg.str());
  }
  const GaussLegendreRule& rule = cachedRule(order);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int p = 0; p < panels; ++p) {
    sum += integrateGaussLegendre(rule, static_cast<double>(p) / panels, static_cast<double>(p + 1) / panels, f);
  }
  return sum;
}

}  // namespace ffdkit::geometry::quaternion
