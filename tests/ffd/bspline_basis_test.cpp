#include "ffdkit/ffd/bspline_basis.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace ffdkit::ffd {
namespace {

// Independent evaluation: the textbook Cox-de Boor recursion written out directly (0/0 = 0),
// not the triangular scheme of Piegl & Tiller A2.2 that the library uses. Valid inside the span.
double coxDeBoor(const std::vector<double>& knots, int i, int degree, double t, int span) {
  if (degree == 0) return i == span ? 1.0 : 0.0;
  double value = 0.0;
  const double leftWidth = knots[i + degree] - knots[i];
  if (leftWidth > 0.0) value += (t - knots[i]) / leftWidth * coxDeBoor(knots, i, degree - 1, t, span);
  const double rightWidth = knots[i + degree + 1] - knots[i + 1];
  if (rightWidth > 0.0) {
    value += (knots[i + degree + 1] - t) / rightWidth * coxDeBoor(knots, i + 1, degree - 1, t, span);
  }
  return value;
}

struct KnotCase {
  const char* name;
  int degree;
  std::vector<double> knots;
};

// Clamped uniform, clamped non-uniform with a repeated interior knot, and unclamped knots.
std::vector<KnotCase> knotCases() {
  return {
      {"clamped cubic", 3, {0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1}},
      {"repeated interior knot, quadratic", 2, {0, 0, 0, 0.3, 0.3, 0.8, 1, 1, 1}},
      {"non-uniform quartic", 4, {0, 0, 0, 0, 0, 0.1, 0.45, 0.5, 1, 1, 1, 1, 1}},
      {"unclamped linear", 1, {-0.2, 0.1, 0.4, 0.9, 1.3}},
      {"unclamped quintic", 5, {0, 0.1, 0.25, 0.3, 0.5, 0.55, 0.7, 0.8, 0.95, 1.1, 1.2, 1.4}},
  };
}

TEST(BsplineBasis, ValuesMatchTheCoxDeBoorRecursion) {
  for (const KnotCase& c : knotCases()) {
    const int p = c.degree;
    const int last = static_cast<int>(c.knots.size()) - p - 2;
    for (int span = p; span <= last; ++span) {
      if (!(c.knots[span] < c.knots[span + 1])) continue;
      for (double s : {0.0, 0.13, 0.5, 0.87}) {
        const double t = c.knots[span] + s * (c.knots[span + 1] - c.knots[span]);
        std::vector<double> values(p + 1);
        bsplineBasisOnSpan(c.knots.data(), span, p, t, values.data());
        for (int r = 0; r <= p; ++r) {
          EXPECT_NEAR(values[r], coxDeBoor(c.knots, span - p + r, p, t, span), 1e-14)
              << c.name << " span " << span << " r " << r << " t " << t;
        }
      }
    }
  }
}

TEST(BsplineBasis, DerivativesMatchCentralDifferences) {
  // A central difference of the span's own polynomial piece (the function extrapolates past
  // the span, so t +- h stays on one piece): error O(h^2) ~ 1e-10 relative to the knot spacing.
  const double h = 1e-5;
  for (const KnotCase& c : knotCases()) {
    const int p = c.degree;
    const int last = static_cast<int>(c.knots.size()) - p - 2;
    for (int span = p; span <= last; ++span) {
      const double width = c.knots[span + 1] - c.knots[span];
      if (!(width > 0.0)) continue;
      for (double s : {0.0, 0.21, 0.5, 0.93}) {
        const double t = c.knots[span] + s * width;
        std::vector<double> values(p + 1), derivatives(p + 1), ahead(p + 1), behind(p + 1);
        bsplineBasisOnSpan(c.knots.data(), span, p, t, values.data(), derivatives.data());
        bsplineBasisOnSpan(c.knots.data(), span, p, t + h, ahead.data());
        bsplineBasisOnSpan(c.knots.data(), span, p, t - h, behind.data());
        double derivativeSum = 0.0;
        for (int r = 0; r <= p; ++r) {
          const double difference = (ahead[r] - behind[r]) / (2.0 * h);
          EXPECT_NEAR(derivatives[r], difference, 1e-6 * (1.0 + std::abs(difference)))
              << c.name << " span " << span << " r " << r << " t " << t;
          derivativeSum += derivatives[r];
        }
        // The basis sums to one on the span, so its derivatives sum to zero.
        EXPECT_NEAR(derivativeSum, 0.0, 1e-10) << c.name << " span " << span << " t " << t;
      }
    }
  }
}

TEST(BsplineBasis, DegreeZeroHasZeroDerivative) {
  const std::vector<double> knots{0.0, 0.5, 1.0};
  double value = -1.0;
  double derivative = -1.0;
  bsplineBasisOnSpan(knots.data(), 1, 0, 0.7, &value, &derivative);
  EXPECT_EQ(value, 1.0);
  EXPECT_EQ(derivative, 0.0);
}

}  // namespace
}  // namespace ffdkit::ffd
