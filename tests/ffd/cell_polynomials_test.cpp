// Tests the internal cell polynomials (ffd/src/cell_polynomials.h) against the Cox-de Boor
// recursion of AxisSpline::basis, the independent evaluator every other path uses.
#include "cell_polynomials.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ffdkit/ffd/axis_basis.h"

namespace ffdkit::ffd {
namespace {

struct AxisCase {
  AxisBasis basis;
  int count;
  std::string name;
};

std::vector<AxisCase> axesUpToCubic() {
  std::vector<AxisCase> cases;
  for (int count = 2; count <= 4; ++count) cases.push_back({AxisBasis::bernstein(), count, "bernstein"});
  for (int degree = 1; degree <= 3; ++degree) {
    for (int count : {degree + 1, degree + 2, 9}) {
      cases.push_back({AxisBasis::bspline(degree), count, "bspline" + std::to_string(degree)});
    }
    for (int count : {degree + 1, 5, 8}) {
      cases.push_back({AxisBasis::periodic(degree), count, "periodic" + std::to_string(degree)});
    }
    // Clamped non-uniform knots with a narrow cell (width 0.01) beside a wide one.
    const int count = degree + 4;
    Eigen::VectorXd knots(count + degree + 1);
    knots.head(degree + 1).setZero();
    knots.tail(degree + 1).setOnes();
    const double inner[3] = {0.2, 0.21, 0.7};
    for (int i = 0; i < 3; ++i) knots[degree + 1 + i] = inner[i];
    cases.push_back({AxisBasis::bsplineWithKnots(degree, knots), count, "knots" + std::to_string(degree)});
  }
  return cases;
}

TEST(CellPolynomials, AgreeWithCoxDeBoorOnEveryCellIncludingItsEndsAndBeyond) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (const AxisCase& c : axesUpToCubic()) {
    const AxisSpline axis(c.basis, c.count);
    ASSERT_TRUE(detail::CellPolynomials::supports(axis)) << c.name;
    const detail::CellPolynomials poly(axis);
    for (int cell = 0; cell < axis.cellCount(); ++cell) {
      const double a = axis.cellMin(cell), b = axis.cellMax(cell), width = b - a;
      std::vector<double> ts = {a, std::nextafter(a, b), 0.5 * (a + b), std::nextafter(b, a)};
      if (!axis.periodic()) ts.push_back(b);
      for (int k = 0; k < 20; ++k) ts.push_back(a + width * U(rng));
      // The end cells extend as polynomials beyond the domain (extrapolation).
      if (!axis.periodic() && cell == 0) ts.push_back(a - 0.3 * (axis.domainMax() - axis.domainMin()));
      if (!axis.periodic() && cell == axis.cellCount() - 1) ts.push_back(b + 0.3 * (axis.domainMax() - axis.domainMin()));
      for (double t : ts) {
        double N[detail::CellPolynomials::kMaxDegree + 1], D[detail::CellPolynomials::kMaxDegree + 1];
        axis.basis(cell, t, N, D);
        detail::Lane4 n, d;
        poly.evaluate(cell, t, n, d);
        double dScale = 1.0;
        for (int r = 0; r <= axis.degree(); ++r) dScale = std::max(dScale, std::abs(D[r]));
        for (int r = 0; r < 4; ++r) {
          if (r > axis.degree()) {
            EXPECT_EQ(n[r], 0.0) << c.name;
            EXPECT_EQ(d[r], 0.0) << c.name;
            continue;
          }
          EXPECT_NEAR(n[r], N[r], 4e-15 * std::max(1.0, std::abs(N[r])))
              << c.name << " count " << c.count << " cell " << cell << " t " << t << " r " << r;
          EXPECT_NEAR(d[r], D[r], 4e-14 * dScale)
              << c.name << " count " << c.count << " cell " << cell << " t " << t << " r " << r;
        }
      }
    }
  }
}

TEST(CellPolynomials, SupportDegreesUpToThreeOnly) {
  EXPECT_TRUE(detail::CellPolynomials::supports(AxisSpline(AxisBasis::bernstein(), 4)));
  EXPECT_FALSE(detail::CellPolynomials::supports(AxisSpline(AxisBasis::bernstein(), 5)));
  EXPECT_FALSE(detail::CellPolynomials::supports(AxisSpline(AxisBasis::bspline(4), 6)));
}

}  // namespace
}  // namespace ffdkit::ffd
