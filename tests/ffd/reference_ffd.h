#pragma once

// An independent, deliberately straightforward FFD evaluator for the tests: the textbook
// definitions (Bernstein: binomial formula; B-spline: the recursive Cox-de Boor definition
// N_(i,0) = [t_i <= u < t_(i+1)], with 0/0 = 0) and a full triple sum over every control point
// (Kuriyama 1996, eq. (6.1)). It shares no code with the engine.

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Core>

namespace ffdkit::ffd::reference {

struct Axis {
  enum class Kind { Bernstein, BSpline, Periodic } kind = Kind::BSpline;
  int count = 4;
  int degree = 3;
  std::vector<double> knots;  // BSpline: count+degree+1; Periodic: extended, count+2*degree+1
};

inline double binomial(int n, int k) {
  double c = 1.0;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

inline double coxDeBoor(const std::vector<double>& t, int i, int p, double u, double domainMax) {
  if (p == 0) {
    // The right end of the domain belongs to the last non-empty span that ends there (and only
    // to it: with unclamped knots the span starting at domainMax is non-empty too).
    if (u == domainMax) return t[i] < t[i + 1] && t[i + 1] == domainMax ? 1.0 : 0.0;
    return t[i] <= u && u < t[i + 1] ? 1.0 : 0.0;
  }
  double value = 0.0;
  const double d1 = t[i + p] - t[i];
  const double d2 = t[i + p + 1] - t[i + 1];
  if (d1 > 0.0) value += (u - t[i]) / d1 * coxDeBoor(t, i, p - 1, u, domainMax);
  if (d2 > 0.0) value += (t[i + p + 1] - u) / d2 * coxDeBoor(t, i + 1, p - 1, u, domainMax);
  return value;
}

/// Basis value of control point `index` (0..count-1) at u in the domain.
inline double basis(const Axis& axis, int index, double u) {
  switch (axis.kind) {
    case Axis::Kind::Bernstein: {
      const int n = axis.count - 1;
      return binomial(n, index) * std::pow(u, index) * std::pow(1.0 - u, n - index);
    }
    case Axis::Kind::BSpline:
      return coxDeBoor(axis.knots, index, axis.degree, u, axis.knots[axis.count]);
    case Axis::Kind::Periodic: {
      // Functions i = 0 .. count+degree-1 of the extended knot vector act on point i mod count.
      double sum = 0.0;
      const double w = u - std::floor(u);
      for (int i = index; i < axis.count + axis.degree; i += axis.count) {
        sum += coxDeBoor(axis.knots, i, axis.degree, w, 2.0);
      }
      return sum;
    }
  }
  return 0.0;
}

/// X(u,v,w) = sum_ijk B_i(u) B_j(v) B_k(w) P_ijk, P one point per row, i fastest.
inline Eigen::Vector3d evaluate(const Axis (&axes)[3], const Eigen::MatrixX3d& P, const Eigen::Vector3d& uvw) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < axes[2].count; ++k) {
    for (int j = 0; j < axes[1].count; ++j) {
      for (int i = 0; i < axes[0].count; ++i) {
        const double b = basis(axes[0], i, uvw[0]) * basis(axes[1], j, uvw[1]) * basis(axes[2], k, uvw[2]);
        x += b * P.row(i + axes[0].count * (j + axes[1].count * k)).transpose();
      }
    }
  }
  return x;
}

inline std::vector<double> clampedUniform(int count, int degree) {
  std::vector<double> t;
  const int spans = count - degree;
  for (int i = 0; i < count + degree + 1; ++i) t.push_back(std::min(std::max(i - degree, 0), spans) / double(spans));
  return t;
}

inline std::vector<double> periodicUniform(int count, int degree) {
  std::vector<double> t;
  for (int i = 0; i < count + 2 * degree + 1; ++i) t.push_back(double(i - degree) / count);
  return t;
}

/// Clamped knots on [0, 1] whose interior knots are 1/3 and 2/3, each repeated `multiplicity`
/// times (1 <= multiplicity <= degree; multiplicity = degree leaves the basis C0 there).
/// count = degree + 1 + 2 * multiplicity.
inline std::vector<double> repeatedInterior(int degree, int multiplicity) {
  std::vector<double> t(degree + 1, 0.0);
  for (int r = 0; r < multiplicity; ++r) t.push_back(1.0 / 3.0);
  for (int r = 0; r < multiplicity; ++r) t.push_back(2.0 / 3.0);
  for (int r = 0; r <= degree; ++r) t.push_back(1.0);
  return t;
}

/// Unclamped (no repeated end knots) strictly increasing non-uniform knots, count+degree+1 of
/// them, starting below 0; the domain [t_degree, t_count] is a sub-range.
inline std::vector<double> randomUnclamped(int count, int degree, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(0.3, 1.0);
  std::vector<double> t{-0.5};
  for (int i = 1; i < count + degree + 1; ++i) t.push_back(t.back() + U(rng));
  return t;
}

/// Random clamped non-uniform knots on [0, 1].
inline std::vector<double> randomClamped(int count, int degree, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(0.05, 1.0);
  std::vector<double> gaps;
  double total = 0.0;
  for (int s = 0; s < count - degree; ++s) {
    gaps.push_back(U(rng));
    total += gaps.back();
  }
  std::vector<double> t(degree + 1, 0.0);
  double acc = 0.0;
  for (int s = 0; s + 1 < count - degree; ++s) {
    acc += gaps[s] / total;
    t.push_back(acc);
  }
  for (int r = 0; r <= degree; ++r) t.push_back(1.0);
  return t;
}

}  // namespace ffdkit::ffd::reference
