#include "ffdkit/geometry/g3/bi_clothoid.h"

#include <cmath>
#include <sstream>

#include <Eigen/QR>

#include "ffdkit/geometry/g3/g3_error.h"
#include "span_quadrature.h"

namespace ffdkit::geometry::g3 {
namespace {

// Quadratic Bezier ordinates c_0..c_4 of the two arcs' tangent angle (Kuroda et al. 1997, sec. 6).
struct Ordinates {
  double c[5];
};

Ordinates ordinates(const BiClothoidEnds& e, double s0, double s1) {
  Ordinates o;
  o.c[0] = e.startAngle;
  o.c[4] = e.endAngle;
  o.c[1] = o.c[0] + 0.5 * e.startCurvature * s0;  // 1/2, not 2: the printed formula of sec. 6 is misprinted
  o.c[3] = o.c[4] - 0.5 * e.endCurvature * s1;
  o.c[2] = (o.c[3] * s0 + o.c[1] * s1) / (s0 + s1);
  return o;
}

// I = int_0^1 (cos, sin) psi(u) du and moments int B^2_k (cos, sin) psi for the quadratic piece.
using QuadMoments = Eigen::Matrix<double, 8, 1>;
QuadMoments quadraticMoments(double c0, double c1, double c2) {
  const int panels = detail::panelCount(std::abs(c1 - c0) + std::abs(c2 - c1), detail::kMaxTurnPerPanel);
  const auto& rule = detail::defaultRule();
  QuadMoments sum = QuadMoments::Zero();
  for (int p = 0; p < panels; ++p) {
    sum += integrateGaussLegendre(rule, static_cast<double>(p) / panels, static_cast<double>(p + 1) / panels, [&](double u) {
      const double w = 1.0 - u;
      const double bern[3] = {w * w, 2.0 * w * u, u * u};
      const double angle = c0 * bern[0] + c1 * bern[1] + c2 * bern[2];
      const double c = std::cos(angle), s = std::sin(angle);
      QuadMoments m;
      m << c, s, bern[0] * c, bern[0] * s, bern[1] * c, bern[1] * s, bern[2] * c, bern[2] * s;
      return m;
    });
  }
  return sum;
}

void validateEnds(const BiClothoidEnds& e) {
  if (!e.startPoint.allFinite() || !e.endPoint.allFinite() || !std::isfinite(e.startAngle) ||
      !std::isfinite(e.endAngle) || !std::isfinite(e.startCurvature) || !std::isfinite(e.endCurvature)) {
    throw G3InputError("bi-clothoid end data must be finite");
  }
}

}  // namespace

Eigen::Vector2d ClothoidArc::position(double sigma) const {
  const double turning = std::abs(startCurvature) * std::abs(sigma) + 0.5 * std::abs(sharpness) * sigma * sigma;
  const int panels = detail::panelCount(turning, detail::kMaxTurnPerPanel);
  return start + detail::integrateTangent(detail::defaultRule(), [&](double t) { return angle(t); }, 0.0, sigma, panels);
}

std::array<ClothoidArc, 2> makeBiClothoid(const BiClothoidEnds& ends, double sigma0, double sigma1) {
  validateEnds(ends);
  if (!(sigma0 > 0.0) || !(sigma1 > 0.0) || !std::isfinite(sigma0) || !std::isfinite(sigma1)) {
    std::ostringstream msg;
    msg << "bi-clothoid arc lengths must be finite and > 0, got (" << sigma0 << ", " << sigma1 << ")";
    throw G3InputError(msg.str());
  }
  const Ordinates o = ordinates(ends, sigma0, sigma1);
  std::array<ClothoidArc, 2> arcs;
  const double sigma[2] = {sigma0, sigma1};
  for (int k = 0; k < 2; ++k) {
    const double* c = o.c + 2 * k;
    ClothoidArc& a = arcs[k];
    a.length = sigma[k];
    a.startAngle = c[0];
    a.startCurvature = 2.0 * (c[1] - c[0]) / sigma[k];
    a.sharpness = 2.0 * (c[2] - 2.0 * c[1] + c[0]) / (sigma[k] * sigma[k]);
  }
  // The junction curvature from the second arc's formula equals the first arc's end curvature
  // by the C^1 choice of c_2; the end curvature is kappa_b exactly.
  arcs[0].start = ends.startPoint;
  arcs[1].start = arcs[0].endPoint();
  return arcs;
}

BiClothoidResult fitBiClothoid(const BiClothoidEnds& ends, double lengthGuess, const BiClothoidOptions& options) {
  validateEnds(ends);
  const Eigen::Vector2d chord = ends.endPoint - ends.startPoint;
  const double h = chord.norm();
  if (!(h > 0.0)) throw G3InputError("bi-clothoid end points coincide");
  if (!(lengthGuess > 0.0) || !std::isfinite(lengthGuess)) {
    std::ostringstream msg;
    msg << "bi-clothoid length guess must be finite and > 0, got " << lengthGuess;
    throw G3InputError(msg.str());
  }
  auto residual = [&](const Eigen::Vector2d& s, QuadMoments* m0, QuadMoments* m1) {
    const Ordinates o = ordinates(ends, s[0], s[1]);
    const QuadMoments a = quadraticMoments(o.c[0], o.c[1], o.c[2]);
    const QuadMoments b = quadraticMoments(o.c[2], o.c[3], o.c[4]);
    if (m0) *m0 = a;
    if (m1) *m1 = b;
    return Eigen::Vector2d(s[0] * a.head<2>() + s[1] * b.head<2>() - chord);
  };
  BiClothoidResult result;
  Eigen::Vector2d sigma = Eigen::Vector2d::Constant(0.5 * lengthGuess);
  QuadMoments m0, m1;
  Eigen::Vector2d f = residual(sigma, &m0, &m1);
  for (int it = 0; it < options.maxIterations && f.cwiseAbs().maxCoeff() > options.tolerance * h; ++it) {
    result.iterations = it + 1;
    const Ordinates o = ordinates(ends, sigma[0], sigma[1]);
    const double sum = sigma[0] + sigma[1];
    // d c_k / d sigma_j for k = 1, 2, 3 (c_0, c_4 are fixed).
    const double dc1[2] = {0.5 * ends.startCurvature, 0.0};
    const double dc3[2] = {0.0, -0.5 * ends.endCurvature};
    const double dc2[2] = {(o.c[3] - o.c[2] + 0.5 * sigma[1] * ends.startCurvature) / sum,
                           (o.c[1] - o.c[2] - 0.5 * sigma[0] * ends.endCurvature) / sum};
    Eigen::Matrix2d jac;
    for (int j = 0; j < 2; ++j) {
      // d/dsigma_j of sigma_k int e^{i psi_k}: [j = k] I_k + sigma_k int i e^{i psi_k} dpsi_k/dsigma_j.
      const double dpsi0[3] = {0.0, dc1[j], dc2[j]};
      const double dpsi1[3] = {dc2[j], dc3[j], 0.0};
      Eigen::Vector2d col = Eigen::Vector2d::Zero();
      for (int k = 0; k < 3; ++k) {
        col += sigma[0] * dpsi0[k] * Eigen::Vector2d(-m0[3 + 2 * k], m0[2 + 2 * k]);
        col += sigma[1] * dpsi1[k] * Eigen::Vector2d(-m1[3 + 2 * k], m1[2 + 2 * k]);
      }
      col += (j == 0 ? m0 : m1).head<2>();
      jac.col(j) = col;
    }
    // Pseudo-inverse: the system is singular when the data are one clothoid (
    // Kuroda et al. 1997, sec. 6).
    const Eigen::Vector2d step = -Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix2d>(jac).solve(f);
    if (!step.allFinite()) break;
    double lambda = 1.0;
    Eigen::Vector2d trial = sigma + step;
    while ((trial.array() <= 0.0).any() && lambda > 1e-6) {
      lambda *= 0.5;
      trial = sigma + lambda * step;
    }
    if ((trial.array() <= 0.0).any()) break;
    const bool tiny = (trial - sigma).cwiseAbs().maxCoeff() <= 1e-15 * sum;
    sigma = trial;
    f = residual(sigma, &m0, &m1);
    if (!f.allFinite() || tiny) break;
  }
  result.residual = f.norm();
  result.converged = f.allFinite() && f.cwiseAbs().maxCoeff() <= options.tolerance * h * 10.0;
  if ((sigma.array() > 0.0).all() && sigma.allFinite()) result.arcs = makeBiClothoid(ends, sigma[0], sigma[1]);
  return result;
}

}  // namespace ffdkit::geometry::g3
