// Direct manipulation (Hsu, Hughes & Kaufman 1992): basis weights reproduce eq. (6.1), and the
// least-norm control change moves the constrained points exactly, with the smallest change.
#include "ffdkit/ffd/direct_manipulation.h"

#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "ffdkit/ffd/cylindrical_lattice.h"
#include "test_lattices.h"

namespace ffdkit::ffd {
namespace {

Eigen::Vector3d weighted(const Lattice& lattice, const std::vector<BasisWeight>& weights) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (const BasisWeight& w : weights) x += w.weight * lattice.controlPoints().row(w.point).transpose();
  return x;
}

TEST(DirectManipulation, BasisWeightsReproduceTheLatticeAndSumToOne) {
  std::mt19937 rng(41);
  for (int trial = 0; trial < 20; ++trial) {
    Lattice lattice = testing::randomLattice(rng, 0.0);
    Eigen::MatrixX3d p = lattice.controlPoints();
    p += 0.2 * Eigen::MatrixX3d::Random(p.rows(), 3);
    lattice.setControlPoints(p);
    const Eigen::MatrixX3d uvw = testing::randomParameters(lattice, 20, rng);
    for (Eigen::Index r = 0; r < uvw.rows(); ++r) {
      const auto weights = basisWeights(lattice, uvw.row(r).transpose());
      double sum = 0.0;
      for (const BasisWeight& w : weights) sum += w.weight;
      EXPECT_NEAR(sum, 1.0, 1e-13);  // partition of unity
      EXPECT_LT((weighted(lattice, weights) - lattice.evaluate(uvw.row(r).transpose())).norm(), 1e-13);
    }
  }
}

TEST(DirectManipulation, OnePointMovesExactlyWithTheLeastNormChange) {
  std::mt19937 rng(42);
  for (int trial = 0; trial < 20; ++trial) {
    Lattice lattice = testing::randomLattice(rng, 0.0);
    const Eigen::MatrixX3d uvw = testing::randomParameters(lattice, 1, rng);
    const Eigen::MatrixX3d d = Eigen::MatrixX3d::Random(1, 3);
    const Eigen::Vector3d before = lattice.evaluate(uvw.row(0).transpose());
    const Eigen::MatrixX3d change = leastNormControlChange(lattice, uvw, d);
    lattice.setControlPoints(lattice.controlPoints() + change);
    EXPECT_LT((lattice.evaluate(uvw.row(0).transpose()) - before - d.row(0).transpose()).norm(), 1e-12);
    // HHK eq. (6) for one point: dP_i = w_i d / sum w^2 (each control point moves parallel to d).
    const auto weights = basisWeights(lattice, uvw.row(0).transpose());
    double w2 = 0.0;
    for (const BasisWeight& w : weights) w2 += w.weight * w.weight;
    Eigen::MatrixX3d expected = Eigen::MatrixX3d::Zero(change.rows(), 3);
    for (const BasisWeight& w : weights) expected.row(w.point) += (w.weight / w2) * d.row(0);
    EXPECT_LT((change - expected).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(DirectManipulation, SeveralPointsAreMetAndNoSmallerChangeMeetsThem) {
  std::mt19937 rng(43);
  BoxLatticeOptions options;
  options.counts = Eigen::Vector3i(5, 4, 6);
  options.bases = {AxisBasis::bspline(3), AxisBasis::bernstein(), AxisBasis::bspline(2)};
  Lattice lattice = makeBoxLattice(options);
  const Eigen::MatrixX3d uvw = testing::randomParameters(lattice, 6, rng);
  const Eigen::MatrixX3d d = 0.1 * Eigen::MatrixX3d::Random(6, 3);
  const Eigen::MatrixX3d change = leastNormControlChange(lattice, uvw, d);
  Lattice moved = lattice;
  moved.setControlPoints(lattice.controlPoints() + change);
  for (Eigen::Index r = 0; r < uvw.rows(); ++r)
    EXPECT_LT((moved.evaluate(uvw.row(r).transpose()) - lattice.evaluate(uvw.row(r).transpose()) - d.row(r).transpose()).norm(),
              1e-12);
  // Any other solution differs by a null-space vector of B, orthogonal to the least-norm one:
  // adding a random null-space change keeps the constraints and only grows the norm.
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(uvw.rows(), lattice.pointCount());
  for (Eigen::Index r = 0; r < uvw.rows(); ++r)
    for (const BasisWeight& w : basisWeights(lattice, uvw.row(r).transpose())) B(r, w.point) += w.weight;
  const Eigen::MatrixXd nullBasis = Eigen::FullPivLU<Eigen::MatrixXd>(B).kernel();
  const Eigen::MatrixX3d other = change + nullBasis * Eigen::MatrixXd::Random(nullBasis.cols(), 3);
  EXPECT_LT((B * other - d).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_GT(other.norm(), change.norm());
  EXPECT_LT(std::abs((other - change).cwiseProduct(change).sum()), 1e-10);  // orthogonal
}

TEST(DirectManipulation, DependentConstraintsAreMetInTheLeastSquaresSense) {
  Lattice lattice = makeBoxLattice({});
  Eigen::MatrixX3d uvw(2, 3);
  uvw << 0.3, 0.4, 0.5, 0.3, 0.4, 0.5;  // one point asked to go two ways
  Eigen::MatrixX3d d(2, 3);
  d << 1, 0, 0, 0, 1, 0;
  const Eigen::MatrixX3d change = leastNormControlChange(lattice, uvw, d);
  lattice.setControlPoints(lattice.controlPoints() + change);
  const Eigen::Vector3d moved = lattice.evaluate(uvw.row(0).transpose()) - makeBoxLattice({}).evaluate(uvw.row(0).transpose());
  EXPECT_LT((moved - Eigen::Vector3d(0.5, 0.5, 0.0)).norm(), 1e-12);  // the average
  EXPECT_TRUE(change.allFinite());
}

TEST(DirectManipulation, PeriodicAxesWrapLikeEvaluate) {
  CylindricalLatticeOptions options;
  options.counts = Eigen::Vector3i(3, 8, 3);
  const Lattice lattice = makeCylindricalLattice(options);
  for (double angle : {0.05, 0.5, 0.97, 1.3, -0.2}) {
    const Eigen::Vector3d uvw(0.6, angle, 0.4);
    EXPECT_LT((weighted(lattice, basisWeights(lattice, uvw)) - lattice.evaluate(uvw)).norm(), 1e-13) << angle;
  }
}

TEST(DirectManipulation, BadInputIsRefusedWithAClearMessage) {
  const Lattice lattice = makeBoxLattice({});
  try {
    leastNormControlChange(lattice, Eigen::MatrixX3d::Zero(2, 3), Eigen::MatrixX3d::Zero(1, 3));
    ADD_FAILURE() << "expected a LatticeError";
  } catch (const LatticeError& e) {
    EXPECT_NE(std::string(e.what()).find("2 parameters but 1 displacements"), std::string::npos) << e.what();
  }
  Eigen::MatrixX3d d = Eigen::MatrixX3d::Zero(1, 3);
  d(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(leastNormControlChange(lattice, Eigen::MatrixX3d::Constant(1, 3, 0.5), d), LatticeError);
  EXPECT_THROW(basisWeights(lattice, Eigen::Vector3d(0.5, std::numeric_limits<double>::infinity(), 0.5)), LatticeError);
  EXPECT_EQ(leastNormControlChange(lattice, Eigen::MatrixX3d(0, 3), Eigen::MatrixX3d(0, 3)).cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace
}  // namespace ffdkit::ffd
