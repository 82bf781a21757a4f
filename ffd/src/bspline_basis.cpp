#include "ffdkit/ffd/bspline_basis.h"

#include <string>

#include "ffdkit/ffd/lattice_error.h"

namespace ffdkit::ffd {
namespace {

void checkDegree(int count, int degree, const char* what) {
  if (count < 2) {
    throw LatticeError(std::string(what) + ": needs >= 2 control points, got " + std::to_string(count));
  }
  if (degree < 1 || degree > count - 1) {
    throw LatticeError(std::string(what) + ": degree must be in [1, " + std::to_string(count - 1) +
                       "] for " + std::to_string(count) + " control points, got " + std::to_string(degree));
  }
}

}  // namespace

Eigen::VectorXd clampedUniformKnots(int count, int degree) {
  checkDegree(count, degree, "clampedUniformKnots");
  Eigen::VectorXd knots(count + degree + 1);
  const int interiorSpans = count - degree;
  for (int i = 0; i < knots.size(); ++i) {
    const int k = std::min(std::max(i - degree, 0), interiorSpans);
    knots[i] = static_cast<double>(k) / interiorSpans;
  }
  return knots;
}

Eigen::VectorXd periodicUniformKnots(int count, int degree) {
  checkDegree(count, degree, "periodicUniformKnots");
  Eigen::VectorXd knots(count + 2 * degree + 1);
  for (int i = 0; i < knots.size(); ++i) knots[i] = static_cast<double>(i - degree) / count;
  return knots;
}

void bsplineBasisOnSpan(const double* knots, int span, int degree, double t, double* values,
                        double* derivatives) {
  // Cox-de Boor, The NURBS Book A2.2; the degree-1 lower row is kept for the derivative (A2.3).
  constexpr int kMaxDegree = 32;
  double left[kMaxDegree + 1];
  double right[kMaxDegree + 1];
  double lower[kMaxDegree + 1];
  values[0] = 1.0;
  for (int j = 1; j <= degree; ++j) {
    if (j == degree && derivatives != nullptr) {
      for (int r = 0; r < degree; ++r) lower[r] = values[r];
    }
    left[j] = t - knots[span + 1 - j];
    right[j] = knots[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = values[r] / (right[r + 1] + left[j - r]);
      values[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    values[j] = saved;
  }
  if (derivatives == nullptr) return;
  if (degree == 0) {
    derivatives[0] = 0.0;
    return;
  }
  // dN_(i,p) = p ( N_(i,p-1) / (t_(i+p) - t_i) - N_(i+1,p-1) / (t_(i+p+1) - t_(i+1)) ), i = span-p+r;
  // lower[q] = N_(span-p+1+q, p-1).
  for (int r = 0; r <= degree; ++r) {
    const int i = span - degree + r;
    double d = 0.0;
    if (r >= 1) d += lower[r - 1] / (knots[i + degree] - knots[i]);
    if (r < degree) d -= lower[r] / (knots[i + degree + 1] - knots[i + 1]);
    derivatives[r] = degree * d;
  }
}

Eigen::VectorXd bsplineBasis(const Eigen::Ref<const Eigen::VectorXd>& knots, int span, int degree,
                             double t) {
  if (degree < 0 || degree > 32 || span < degree || span + degree + 1 >= knots.size() + 1 ||
      !(knots[span] < knots[span + 1])) {
    throw LatticeError("bsplineBasis: span " + std::to_string(span) + " is not a non-empty span of degree " +
                       std::to_string(degree) + " in a knot vector of length " + std::to_string(knots.size()));
  }
  Eigen::VectorXd contiguous = knots;
  Eigen::VectorXd values(degree + 1);
  bsplineBasisOnSpan(contiguous.data(), span, degree, t, values.data());
  return values;
}

Eigen::VectorXd grevilleAbscissae(const Eigen::Ref<const Eigen::VectorXd>& knots, int count, int degree) {
  if (degree < 1 || knots.size() < count + degree + 1) {
    throw LatticeError("grevilleAbscissae: need degree >= 1 and >= " + std::to_string(count + degree + 1) +
                       " knots, got degree " + std::to_string(degree) + " and " + std::to_string(knots.size()));
  }
  Eigen::VectorXd g(count);
  for (int i = 0; i < count; ++i) g[i] = knots.segment(i + 1, degree).sum() / degree;
  return g;
}

}  // namespace ffdkit::ffd
