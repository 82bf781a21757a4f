// Tests the internal curvature bound (ffd/src/curvature_bound.h) behind Newton's early exit
// against second derivatives of the rest map taken by central differences of its Jacobian.
#include "curvature_bound.h"

#include <algorithm>
#include <random>

#include <gtest/gtest.h>

#include "ffdkit/ffd/cylindrical_lattice.h"
#include "test_lattices.h"

namespace ffdkit::ffd {
namespace {

Eigen::Matrix3d boundOf(const Lattice& lattice) {
  const detail::CellPolynomials poly[3] = {detail::CellPolynomials(lattice.axis(0)),
                                           detail::CellPolynomials(lattice.axis(1)),
                                           detail::CellPolynomials(lattice.axis(2))};
  return detail::restCurvatureBound(lattice, poly);
}

// max over sampled points of |d^2 Xbar / du_a du_b|, each point strictly inside a cell.
Eigen::Matrix3d sampledCurvature(const Lattice& lattice, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Eigen::Matrix3d worst = Eigen::Matrix3d::Zero();
  for (int sample = 0; sample < 300; ++sample) {
    Eigen::Vector3d uvw, width;
    for (int a = 0; a < 3; ++a) {
      const AxisSpline& axis = lattice.axis(a);
      const int cell = std::uniform_int_distribution<int>(0, axis.cellCount() - 1)(rng);
      width[a] = axis.cellMax(cell) - axis.cellMin(cell);
      uvw[a] = axis.cellMin(cell) + width[a] * (0.01 + 0.98 * U(rng));
    }
    for (int b = 0; b < 3; ++b) {
      const double h = 1e-4 * width[b];
      Eigen::Vector3d step = Eigen::Vector3d::Zero();
      step[b] = h;
      const Eigen::Matrix3d d2 = (lattice.restJacobian(uvw + step) - lattice.restJacobian(uvw - step)) / (2.0 * h);
      for (int a = 0; a < 3; ++a) worst(a, b) = std::max(worst(a, b), d2.col(a).norm());
    }
  }
  return worst;
}

TEST(CurvatureBound, BoundsTheSecondDerivativesOfUserShapedAndCylindricalLattices) {
  std::mt19937 rng(41);
  for (int trial = 0; trial < 40; ++trial) {
    Lattice lattice = trial % 4 == 3 ? makeCylindricalLattice(CylindricalLatticeOptions{})
                                     : testing::randomLattice(rng, 0.1 + 0.02 * trial, /*maxCount=*/4);
    if (trial % 8 == 7) {
      // A folded lattice: two rest points swapped.
      Eigen::MatrixX3d rest = lattice.restPoints();
      rest.row(0).swap(rest.row(rest.rows() - 1));
      lattice.setRestPoints(rest);
    }
    const Eigen::Matrix3d H = boundOf(lattice);
    const Eigen::Matrix3d sampled = sampledCurvature(lattice, rng);
    const double scale = H.maxCoeff();
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        // Central differences of a polynomial Jacobian: truncation ~1e-8 relative, rounding ~1e-11.
        EXPECT_LE(sampled(a, b), H(a, b) * (1.0 + 1e-6) + 1e-7 * scale)
            << "trial " << trial << " (" << a << ", " << b << ")\nbound\n" << H << "\nsampled\n" << sampled;
      }
  }
}

TEST(CurvatureBound, IsZeroForAffineBoxLattices) {
  std::mt19937 rng(42);
  for (int trial = 0; trial < 20; ++trial) {
    const Lattice lattice = testing::randomLattice(rng, 0.0, /*maxCount=*/4);
    ASSERT_TRUE(lattice.restIsAffine());
    EXPECT_LT(boundOf(lattice).maxCoeff(), 1e-10 * lattice.restSize()) << "trial " << trial;
  }
}

}  // namespace
}  // namespace ffdkit::ffd
