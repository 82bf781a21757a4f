#include "ffdkit/geometry/g3/bohm_conversion.h"

namespace ffdkit::geometry::g3 {

Eigen::VectorXd bezierOrdinatesFromDeBoor(const Eigen::Ref<const Eigen::VectorXd>& spanLengths,
                                          const Eigen::Ref<const Eigen::VectorXd>& deBoor) {
  const Eigen::Index n = spanLengths.size();
  const auto& ds = spanLengths;
  // d_k lives at deBoor[k + 1].
  auto d = [&](Eigen::Index k) { return deBoor[k + 1]; };
  Eigen::VectorXd b(3 * n + 1);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double dm = i > 0 ? ds[i - 1] : 0.0;
    const double dp = i + 1 < n ? ds[i + 1] : 0.0;
    const double sigma = dm + ds[i] + dp;
    b[3 * i + 1] = (dm * d(i + 1) + (ds[i] + dp) * d(i)) / sigma;
    b[3 * i + 2] = ((dm + ds[i]) * d(i + 1) + dp * d(i)) / sigma;
  }
  b[0] = d(-1);
  b[3 * n] = d(n + 1);
  for (Eigen::Index i = 1; i < n; ++i) {
    b[3 * i] = (ds[i - 1] * b[3 * i + 1] + ds[i] * b[3 * i - 1]) / (ds[i - 1] + ds[i]);
  }
  return b;
}

Eigen::MatrixXd bezierOrdinateJacobian(const Eigen::Ref<const Eigen::VectorXd>& spanLengths,
                                       const Eigen::Ref<const Eigen::VectorXd>& deBoor) {
  const Eigen::Index n = spanLengths.size();
  const auto& ds = spanLengths;
  auto d = [&](Eigen::Index k) { return deBoor[k + 1]; };
  auto colD = [&](Eigen::Index k) { return n + k + 1; };  // column of d_k
  const Eigen::VectorXd b = bezierOrdinatesFromDeBoor(spanLengths, deBoor);
  Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(3 * n + 1, 2 * n + 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double dm = i > 0 ? ds[i - 1] : 0.0;
    const double dp = i + 1 < n ? ds[i + 1] : 0.0;
    const double sigma = dm + ds[i] + dp;
    const double sigma2 = sigma * sigma;
    const double alpha = dm / sigma;
    const double beta = dp / sigma;
    // b_{3i+1} = (1 - alpha) d_i + alpha d_{i+1}
    auto r1 = jac.row(3 * i + 1);
    r1[colD(i)] = 1.0 - alpha;
    r1[colD(i + 1)] = alpha;
    const double jump = d(i + 1) - d(i);
    if (i > 0) r1[i - 1] += jump * (ds[i] + dp) / sigma2;
    r1[i] += jump * (-dm / sigma2);
    if (i + 1 < n) r1[i + 1] += jump * (-dm / sigma2);
    // b_{3i+2} = beta d_i + (1 - beta) d_{i+1}
    auto r2 = jac.row(3 * i + 2);
    r2[colD(i)] = beta;
    r2[colD(i + 1)] = 1.0 - beta;
    if (i + 1 < n) r2[i + 1] += -jump * (dm + ds[i]) / sigma2;
    if (i > 0) r2[i - 1] += -jump * (-dp / sigma2);
    r2[i] += -jump * (-dp / sigma2);
  }
  jac(0, colD(-1)) = 1.0;
  jac(3 * n, colD(n + 1)) = 1.0;
  for (Eigen::Index i = 1; i < n; ++i) {
    // b_{3i} = (1 - gamma) b_{3i-1} + gamma b_{3i+1}, gamma = ds_{i-1} / (ds_{i-1} + ds_i)
    const double sum = ds[i - 1] + ds[i];
    const double gamma = ds[i - 1] / sum;
    jac.row(3 * i) = (1.0 - gamma) * jac.row(3 * i - 1) + gamma * jac.row(3 * i + 1);
    const double gap = b[3 * i + 1] - b[3 * i - 1];
    jac(3 * i, i - 1) += gap * ds[i] / (sum * sum);
    jac(3 * i, i) += gap * (-ds[i - 1]) / (sum * sum);
  }
  return jac;
}

}  // namespace ffdkit::geometry::g3
