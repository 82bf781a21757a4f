#include "ffdkit/ffd/bernstein_basis.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace ffdkit::ffd {
namespace {

double binomial(int n, int k) {
  double c = 1.0;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

TEST(BernsteinBasis, MatchesClosedFormAndSumsToOne) {
  for (int degree = 0; degree <= 8; ++degree) {
    for (double t : {-0.5, 0.0, 0.1, 0.5, 0.77, 1.0, 1.3}) {
      const Eigen::VectorXd b = bernsteinBasis(degree, t);
      ASSERT_EQ(b.size(), degree + 1);
      for (int i = 0; i <= degree; ++i) {
        const double expected = binomial(degree, i) * std::pow(t, i) * std::pow(1.0 - t, degree - i);
        EXPECT_NEAR(b[i], expected, 1e-13) << "degree " << degree << " i " << i << " t " << t;
      }
      EXPECT_NEAR(b.sum(), 1.0, 1e-13);
    }
  }
}

TEST(BernsteinBasis, RejectsNegativeDegree) {
  EXPECT_THROW(bernsteinBasis(-1, 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace ffdkit::ffd
