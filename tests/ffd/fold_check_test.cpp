// Fold-over bound: det J patches against finite differences of Lattice::evaluate, lattices
// certified positive (identity, affine, mildly bent, mirrored frame) and a lattice built to
// fold caught with a witness where det J <= 0.
#include "ffdkit/ffd/fold_check.h"

#include <limits>
#include <random>

#include <Eigen/LU>
#include <gtest/gtest.h>
#include <omp.h>

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

// A lattice whose three axes share a degree 1..3: random counts, a uniform, non-uniform or
// Bernstein basis, control points moved by up to `move` control spacings (0.05 certifies; 0.5
// and more fold some cells and leave others inconclusive), a random frame, mirrored or not.
Lattice equalDegreeLattice(std::mt19937& rng, double move) {
  const int degree = std::uniform_int_distribution<int>(1, 3)(rng);
  const int kind = std::uniform_int_distribution<int>(0, 2)(rng);
  BoxLatticeOptions options;
  for (int a = 0; a < 3; ++a) {
    options.counts[a] = kind == 0 ? degree + 1 : std::uniform_int_distribution<int>(degree + 1, degree + 4)(rng);
    if (kind == 0) {
      options.bases[a] = AxisBasis::bernstein();
    } else if (kind == 1) {
      options.bases[a] = AxisBasis::bspline(degree);
    } else {
      Eigen::VectorXd knots(options.counts[a] + degree + 1);
      knots.head(degree + 1).setZero();
      knots.tail(degree + 1).setOnes();
      for (int i = degree + 1; i < options.counts[a]; ++i)
        knots[i] = knots[i - 1] + std::uniform_real_distribution<double>(0.3, 1.0)(rng) / (options.counts[a] - degree);
      options.bases[a] = AxisBasis::bsplineWithKnots(degree, knots);
    }
  }
  options.frame = testing::randomFrame(rng);
  if (rng() % 2) options.frame = options.frame * Eigen::Scaling(Eigen::Vector3d(1, -1, 1));
  Lattice lattice = makeBoxLattice(options);
  Eigen::MatrixX3d p = lattice.controlPoints();
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (Eigen::Index r = 0; r < p.rows(); ++r)
    for (int c = 0; c < 3; ++c) p(r, c) += move / (options.counts[c] - 1) * U(rng);
  lattice.setControlPoints(p);
  return lattice;
}

// The batched products (several cells per SIMD lane set, compiled for AVX2 / AVX-512 too) against
// the general product of nets one cell at a time: the same verdict in every cell, and lowest
// coefficients that agree to 1e-12 of the cell's largest coefficient (jacobianDeterminantPatch).
TEST(FoldCheck, BatchedProductsAgreeWithTheReferenceExpansion) {
  std::mt19937 rng(24);
  Eigen::Index verdicts[3] = {0, 0, 0};
  for (int trial = 0; trial < 60; ++trial) {
    const double move = std::array{0.05, 0.5, 1.0, 2.0}[std::size_t(trial % 4)];
    const Lattice lattice = equalDegreeLattice(rng, move);
    FoldCheckOptions options;
    options.maxDepth = std::array{0, 1, 3}[std::size_t(trial % 3)];
    const FoldCheckResult fast = checkFolding(lattice, options);
    options.referenceExpansion = true;
    const FoldCheckResult reference = checkFolding(lattice, options);
    ASSERT_EQ(fast.cells.size(), reference.cells.size());
    EXPECT_EQ(fast.orientation, reference.orientation);
    for (std::size_t flat = 0; flat < fast.cells.size(); ++flat) {
      const std::array<int, 3> cell = {int(flat % fast.cellCounts[0]), int(flat / fast.cellCounts[0] % fast.cellCounts[1]),
                                       int(flat / fast.cellCounts[0] / fast.cellCounts[1])};
      const JacobianDeterminantPatch patch = jacobianDeterminantPatch(lattice, cell);
      const double scale = patch.coefficients.cwiseAbs().maxCoeff();
      EXPECT_EQ(fast.cells[flat], reference.cells[flat]) << "trial " << trial << " cell " << flat;
      EXPECT_NEAR(fast.lowerBound[flat], reference.lowerBound[flat], 1e-12 * scale) << "trial " << trial << " cell " << flat;
      if (fast.cells[flat] == CellFolding::Folds) {
        ASSERT_TRUE(fast.witness[flat].allFinite());
        // det J of the cell's own polynomial there (at a cell's face, Lattice::jacobian of a degree 1
        // axis takes the neighbour's piece: det J is not continuous across cells of degree 1).
        EXPECT_LE(fast.orientation * patch.value(fast.witness[flat]), 1e-12 * scale) << "trial " << trial;
      }
      ++verdicts[int(fast.cells[flat])];
    }
    EXPECT_EQ(fast.positiveCount, reference.positiveCount);
    EXPECT_EQ(fast.foldsCount, reference.foldsCount);
  }
  // The random lattices exercised every verdict.
  EXPECT_GT(verdicts[int(CellFolding::Positive)], 100);
  EXPECT_GT(verdicts[int(CellFolding::Folds)], 100);
  EXPECT_GT(verdicts[int(CellFolding::Unknown)], 10);
}

// Rational lattices (weights in [0.5, 2] on some or all control points): the batched G =
// det[H_u, H_v, H_w, H] of cells with unequal window weights against the general Laplace expansion
// one cell at a time, and equal-weight cells against det J's reference path; the same verdicts,
// bounds to 1e-12 of the lattice's largest |bound|.
TEST(FoldCheck, BatchedRationalProductsAgreeWithTheReferenceExpansion) {
  std::mt19937 rng(26);
  Eigen::Index verdicts[3] = {0, 0, 0};
  for (int trial = 0; trial < 40; ++trial) {
    Lattice lattice = equalDegreeLattice(rng, std::array{0.05, 0.5, 1.0, 2.0}[std::size_t(trial % 4)]);
    Eigen::VectorXd w = lattice.weights();
    const bool all = trial % 2 == 0;
    for (Eigen::Index i = 0; i < w.size(); ++i)
      if (all || rng() % 4 == 0) w[i] = std::uniform_real_distribution<double>(0.5, 2.0)(rng);
    lattice.setWeights(w);
    FoldCheckOptions options;
    options.maxDepth = std::array{0, 1, 3}[std::size_t(trial % 3)];
    const FoldCheckResult fast = checkFolding(lattice, options);
    options.referenceExpansion = true;
    const FoldCheckResult reference = checkFolding(lattice, options);
    const double scale = Eigen::Map<const Eigen::VectorXd>(reference.lowerBound.data(), Eigen::Index(reference.lowerBound.size()))
                             .cwiseAbs()
                             .maxCoeff();
    for (std::size_t flat = 0; flat < fast.cells.size(); ++flat) {
      EXPECT_EQ(fast.cells[flat], reference.cells[flat]) << "trial " << trial << " cell " << flat;
      EXPECT_NEAR(fast.lowerBound[flat], reference.lowerBound[flat], 1e-12 * scale) << "trial " << trial << " cell " << flat;
      if (fast.cells[flat] == CellFolding::Folds) {
        ASSERT_TRUE(fast.witness[flat].allFinite());
        EXPECT_EQ(fast.witness[flat], reference.witness[flat]) << "trial " << trial << " cell " << flat;
      }
      ++verdicts[int(fast.cells[flat])];
    }
  }
  EXPECT_GT(verdicts[int(CellFolding::Positive)], 100);
  EXPECT_GT(verdicts[int(CellFolding::Folds)], 100);
  EXPECT_GT(verdicts[int(CellFolding::Unknown)], 3);  // 7 with this seed
}

// One thread or two: the same verdicts, bounds and witnesses, bit for bit (polynomial and rational).
TEST(FoldCheck, VerdictsDoNotDependOnTheThreadCount) {
  std::mt19937 rng(25);
  const int before = omp_get_max_threads();
  for (int trial = 0; trial < 8; ++trial) {
    Lattice lattice = equalDegreeLattice(rng, trial % 2 ? 1.0 : 0.1);
    if (trial >= 4) {  // rational: the batched G of unequal-weight cells
      Eigen::VectorXd w(lattice.pointCount());
      for (Eigen::Index i = 0; i < w.size(); ++i) w[i] = std::uniform_real_distribution<double>(0.5, 2.0)(rng);
      lattice.setWeights(w);
    }
    omp_set_num_threads(1);
    const FoldCheckResult one = checkFolding(lattice);
    omp_set_num_threads(2);
    const FoldCheckResult two = checkFolding(lattice);
    EXPECT_EQ(one.cells, two.cells);
    EXPECT_EQ(one.lowerBound, two.lowerBound);
    for (std::size_t c = 0; c < one.cells.size(); ++c) {
      if (one.cells[c] == CellFolding::Folds) {
        EXPECT_EQ(one.witness[c], two.witness[c]);
      }
    }
  }
  omp_set_num_threads(before);
}

// Degrees above kFoldCheckMaxDegree are refused with the axis and its degree; 10 is bounded.
TEST(FoldCheck, DegreesAboveTenAreRefusedWithTheAxisAndItsDegree) {
  BoxLatticeOptions options;
  options.bases = {AxisBasis::bernstein(), AxisBasis::bernstein(), AxisBasis::bernstein()};
  options.counts = Eigen::Vector3i(2, 12, 2);  // degree 11 along v
  const Lattice eleven = makeBoxLattice(options);
  try {
    checkFolding(eleven);
    ADD_FAILURE() << "degree 11 was not refused";
  } catch (const LatticeError& e) {
    EXPECT_STREQ(e.what(), "checkFolding: axis 1 has degree 11; the fold-over bound handles degrees up to 10");
  }
  try {
    jacobianDeterminantPatch(eleven, {0, 0, 0});
    ADD_FAILURE() << "degree 11 was not refused";
  } catch (const LatticeError& e) {
    EXPECT_STREQ(e.what(), "jacobianDeterminantPatch: axis 1 has degree 11; the fold-over bound handles degrees up to 10");
  }
  options.counts = Eigen::Vector3i(2, 11, 2);  // degree 10: bounded (the identity map is certified)
  const FoldCheckResult ten = checkFolding(makeBoxLattice(options));
  EXPECT_TRUE(ten.certifiedPositive());
  EXPECT_GT(ten.lowerBound[0], 0.0);
}

}  // namespace
}  // namespace ffdkit::ffd
