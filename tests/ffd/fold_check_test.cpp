// Fold-over bound: det J patches against finite differences of Lattice::evaluate, lattices
// certified positive (identity, affine, mildly bent, mirrored frame) and a lattice built to
// fold caught with a witness where det J <= 0.
#include "ffdkit/ffd/fold_check.h"

#include <limits>
#include <random>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "test_lattices.h"

namespace ffdkit::ffd {
namespace {

// det of the central-difference Jacobian of X (lattice-local) with respect to (u, v, w).
double finiteDifferenceDeterminant(const Lattice& lattice, const Eigen::Vector3d& uvw, double h) {
  Eigen::Matrix3d J;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(a);
    J.col(a) = (lattice.evaluate(uvw + e) - lattice.evaluate(uvw - e)) / (2 * h);
  }
  return J.determinant();
}

std::array<int, 3> cellAt(const Lattice& lattice, const Eigen::Vector3d& uvw) {
  return {lattice.axis(0).cellOf(uvw[0]), lattice.axis(1).cellOf(uvw[1]), lattice.axis(2).cellOf(uvw[2])};
}

TEST(FoldCheck, DeterminantPatchMatchesFiniteDifferencesOfTheEvaluator) {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 20; ++trial) {
    Lattice lattice = testing::randomLattice(rng, 0.0, 6);
    lattice.setControlPoints(lattice.controlPoints() + 0.1 * Eigen::MatrixX3d::Random(lattice.pointCount(), 3));
    const Eigen::MatrixX3d uvw = testing::randomParameters(lattice, 10, rng);
    for (Eigen::Index r = 0; r < uvw.rows(); ++r) {
      const Eigen::Vector3d t = uvw.row(r).transpose();
      const JacobianDeterminantPatch patch = jacobianDeterminantPatch(lattice, cellAt(lattice, t));
      const double expected = finiteDifferenceDeterminant(lattice, t, 1e-6);
      // Also against the evaluator's analytic Jacobian.
      EXPECT_NEAR(patch.value(t), lattice.jacobian(t).determinant(), 1e-10 * (1 + std::abs(expected)));
      EXPECT_NEAR(patch.value(t), expected, 1e-6 * (1 + std::abs(expected))) << "trial " << trial;
    }
  }
}

TEST(FoldCheck, IdentityAffineAndMirroredLatticesAreCertifiedPositive) {
  std::mt19937 rng(22);
  for (int trial = 0; trial < 20; ++trial) {
    Lattice lattice = testing::randomLattice(rng, 0.0, 6);
    FoldCheckResult identity = checkFolding(lattice);
    EXPECT_TRUE(identity.certifiedPositive()) << "trial " << trial;
    EXPECT_EQ(identity.positiveCount, Eigen::Index(identity.cells.size()));
    // An affine map of the control points with positive determinant keeps every cell positive
    // (det J is then a positive constant on a box lattice's affine rest map).
    Eigen::Matrix3d A = Eigen::Matrix3d::Identity() + 0.3 * Eigen::Matrix3d::Random();
    if (A.determinant() < 0) A.col(0) *= -1;
    Eigen::MatrixX3d p = (lattice.controlPoints() * A.transpose()).rowwise() + Eigen::RowVector3d(0.3, -1, 2);
    lattice.setControlPoints(p);
    EXPECT_TRUE(checkFolding(lattice).certifiedPositive()) << "trial " << trial;
    // The rest lattice's orientation is the reference: a mirroring affine map folds everything.
    Eigen::MatrixX3d mirrored = p;
    mirrored.col(0) *= -1;
    lattice.setControlPoints(mirrored);
    const FoldCheckResult flipped = checkFolding(lattice);
    EXPECT_EQ(flipped.foldsCount, Eigen::Index(flipped.cells.size())) << "trial " << trial;
  }
  // A mirrored frame alone is not a fold.
  BoxLatticeOptions options;
  options.frame = Eigen::Affine3d(Eigen::Scaling(Eigen::Vector3d(-1, 1, 1)));
  EXPECT_TRUE(checkFolding(makeBoxLattice(options)).certifiedPositive());
}

TEST(FoldCheck, MildlyBentLatticesAreCertifiedPositive) {
  std::mt19937 rng(23);
  for (int trial = 0; trial < 10; ++trial) {
    BoxLatticeOptions options;
    options.counts = Eigen::Vector3i(4 + trial % 3, 5, 4);
    Lattice lattice = makeBoxLattice(options);
    // Moves of up to 15% of the control spacing.
    Eigen::MatrixX3d p = lattice.controlPoints();
    for (Eigen::Index r = 0; r < p.rows(); ++r)
      for (int c = 0; c < 3; ++c) p(r, c) += 0.15 / (options.counts[c] - 1) * std::uniform_real_distribution<double>(-1, 1)(rng);
    lattice.setControlPoints(p);
    const FoldCheckResult result = checkFolding(lattice);
    EXPECT_TRUE(result.certifiedPositive()) << "trial " << trial << ": " << result.foldsCount << " fold, "
                                            << result.unknownCount << " unknown";
  }
}

// The box lattice with the four inner control points (1, j, k), j, k in {1, 2}, pushed along u
// by `push` (in units of the box): past their neighbours for large pushes.
Lattice pushedLattice(const AxisBasis& basis, double push) {
  BoxLatticeOptions options;
  options.counts = Eigen::Vector3i(4, 4, 4);
  options.bases = {basis, basis, basis};
  Lattice lattice = makeBoxLattice(options);
  Eigen::MatrixX3d p = lattice.controlPoints();
  for (int j = 1; j <= 2; ++j)
    for (int k = 1; k <= 2; ++k) p(lattice.index(1, j, k), 0) += push;
  lattice.setControlPoints(p);
  return lattice;
}

// The smallest det J over a 41^3 grid of the parameter box (the test's own sampling).
double sampledMinimum(const Lattice& lattice) {
  double smallest = std::numeric_limits<double>::infinity();
  for (int a = 0; a <= 40; ++a)
    for (int b = 0; b <= 40; ++b)
      for (int c = 0; c <= 40; ++c)
        smallest = std::min(smallest, lattice.jacobian(Eigen::Vector3d(a, b, c) / 40.0).determinant());
  return smallest;
}

TEST(FoldCheck, ALatticeBuiltToFoldIsCaughtWithAWitness) {
  for (const auto& [basis, push] : {std::pair{AxisBasis::bernstein(), 3.0}, std::pair{AxisBasis::bspline(2), 1.0},
                                    std::pair{AxisBasis::bspline(3), 2.0}}) {
    const Lattice lattice = pushedLattice(basis, push);
    ASSERT_LT(sampledMinimum(lattice), 0.0);  // the construction does fold
    const FoldCheckResult result = checkFolding(lattice);
    ASSERT_GT(result.foldsCount, 0);
    EXPECT_FALSE(result.certifiedPositive());
    for (std::size_t c = 0; c < result.cells.size(); ++c) {
      if (result.cells[c] != CellFolding::Folds) continue;
      const Eigen::Vector3d w = result.witness[c];
      ASSERT_TRUE(w.allFinite());
      EXPECT_LE(result.orientation * lattice.jacobian(w).determinant(), 1e-12);
    }
  }
}

TEST(FoldCheck, SubdivisionCertifiesWhatTheFirstBoundLeavesUnknown) {
  // Pushed by 1.5: the sampled det J stays above 0.15, but some Bernstein coefficients of the
  // undivided patch are negative.
  const Lattice lattice = pushedLattice(AxisBasis::bernstein(), 1.5);
  ASSERT_GT(sampledMinimum(lattice), 0.1);
  FoldCheckOptions shallow;
  shallow.maxDepth = 0;
  const FoldCheckResult first = checkFolding(lattice, shallow);
  EXPECT_EQ(first.unknownCount, 1);
  EXPECT_LT(first.lowerBound[0], 0.0);
  EXPECT_TRUE(checkFolding(lattice).certifiedPositive());
  shallow.maxDepth = 11;
  EXPECT_THROW(checkFolding(lattice, shallow), LatticeError);
  EXPECT_THROW(jacobianDeterminantPatch(lattice, {1, 0, 0}), LatticeError);
}

}  // namespace
}  // namespace ffdkit::ffd
