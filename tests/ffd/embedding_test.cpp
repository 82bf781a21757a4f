#include "ffdkit/ffd/embedding.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "ffdkit/ffd/cylindrical_lattice.h"
#include "test_lattices.h"

namespace ffdkit::ffd {
namespace {

// max_p |frame * Xbar(embed(Q)_p) - Q_p| relative to the lattice size (in world units).
double roundTripError(const Lattice& lattice, const Embedding& e, const Eigen::MatrixX3d& Q) {
  const Eigen::MatrixX3d uvw = e.parameters();
  double worst = 0.0;
  for (Eigen::Index r = 0; r < Q.rows(); ++r) {
    const Eigen::Vector3d x = lattice.frame() * lattice.evaluateRest(uvw.row(r).transpose());
    worst = std::max(worst, (x - Q.row(r).transpose()).norm());
  }
  const double worldSize = lattice.restSize() * lattice.frame().linear().norm();
  return worst / worldSize;
}

TEST(Embedding, BoxLatticesEmbedInClosedFormForEveryBasis) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 30; ++trial) {
    const Lattice lattice = testing::randomLattice(rng, 0.0);
    ASSERT_TRUE(lattice.restIsAffine());
    const Eigen::MatrixX3d uvw = testing::randomParameters(lattice, 300, rng);
    const Eigen::MatrixX3d Q = testing::restImages(lattice, uvw);
    const Embedding e = embed(lattice, Q);
    EXPECT_EQ(e.insideCount(), 300);
    EXPECT_LT(roundTripError(lattice, e, Q), 1e-12);
    EXPECT_LT((e.parameters() - uvw).cwiseAbs().maxCoeff(), 1e-10);
  }
}

TEST(Embedding, NewtonRoundTripsOnRandomUserShapedLattices) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 30; ++trial) {
    const Lattice lattice = testing::randomLattice(rng, 0.25);
    ASSERT_FALSE(lattice.restIsAffine());
    const Eigen::MatrixX3d uvw = testing::randomParameters(lattice, 300, rng);
    const Eigen::MatrixX3d Q = testing::restImages(lattice, uvw);
    const Embedding e = embed(lattice, Q);
    EXPECT_EQ(e.failedCount(), 0) << "trial " << trial;
    EXPECT_EQ(e.insideCount() + e.outsideCount(), 300);
    // Every point was generated inside; only points within the boundary epsilon band may be judged outside.
    EXPECT_GE(e.insideCount(), 299) << "trial " << trial;
    EXPECT_LT(roundTripError(lattice, e, Q), 1e-12) << "trial " << trial;
  }
}

TEST(Embedding, CylindricalLatticeRoundTripsIncludingTheAxis) {
  std::mt19937 rng(3);
  for (int inner : {0, 1}) {
    CylindricalLatticeOptions options;
    options.counts = {3, 8, 4};
    options.innerRadius = inner * 0.3;
    options.outerRadius = 1.2;
    options.zMin = -0.5;
    options.zMax = 0.8;
    options.frame = testing::randomFrame(rng);
    const Lattice lattice = makeCylindricalLattice(options);
    Eigen::MatrixX3d uvw = testing::randomParameters(lattice, 400, rng);
    if (inner == 0) {
      // A few points exactly on the axis and very close to it.
      for (int r = 0; r < 10; ++r) uvw(r, 0) = r < 5 ? 0.0 : 1e-9 * r;
    }
    const Eigen::MatrixX3d Q = testing::restImages(lattice, uvw);
    const Embedding e = embed(lattice, Q);
    EXPECT_TRUE(e.parameters().allFinite());
    EXPECT_EQ(e.failedCount(), 0);
    EXPECT_EQ(e.insideCount(), 400);
    EXPECT_LT(roundTripError(lattice, e, Q), 1e-12);
  }
}

TEST(Embedding, ReportsOutsidePointsEpsilonInclusively) {
  BoxLatticeOptions options;
  const Lattice lattice = makeBoxLattice(options);
  Eigen::MatrixX3d Q(5, 3);
  Q << 0.5, 0.5, 0.5,      // inside
      1.0, 0.5, 0.5,       // on a face: inside
      1.0 + 1e-12, 0, 1,   // within epsilon of a corner: inside
      1.5, 0.5, 0.5,       // outside
      -0.1, -0.1, -0.1;    // outside
  const Embedding e = embed(lattice, Q);
  EXPECT_EQ(e.insideCount(), 3);
  EXPECT_EQ(e.outsideCount(), 2);
  EXPECT_EQ(e.status(3), PointStatus::Outside);
  EXPECT_EQ(e.status(1), PointStatus::Inside);
  EXPECT_THROW(e.status(5), LatticeError);
}

TEST(Embedding, NewtonFindsOutsidePointsOfUserShapedLattices) {
  std::mt19937 rng(5);
  const Lattice lattice = testing::randomLattice(rng, 0.2);
  Eigen::MatrixX3d uvw = testing::randomParameters(lattice, 50, rng);
  uvw.col(0).array() += 1.3;  // beyond the box along u
  const Eigen::MatrixX3d Q = testing::restImages(lattice, uvw);
  const Embedding e = embed(lattice, Q);
  EXPECT_EQ(e.insideCount(), 0);
  EXPECT_EQ(e.outsideCount() + e.failedCount(), 50);
}

TEST(Embedding, RejectsNonFinitePoints) {
  const Lattice lattice = makeBoxLattice();
  Eigen::MatrixX3d Q = Eigen::MatrixX3d::Constant(4, 3, 0.5);
  Q(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(embed(lattice, Q), LatticeError);
}

TEST(Embedding, RefusesAStaleLattice) {
  Lattice lattice = makeBoxLattice();
  const Embedding e = embed(lattice, Eigen::MatrixX3d::Constant(3, 3, 0.5));
  EXPECT_NO_THROW(e.checkLattice(lattice));
  lattice.setControlPoint(0, Eigen::Vector3d(-1, 0, 0));  // editing does not invalidate
  EXPECT_NO_THROW(e.checkLattice(lattice));
  Eigen::Affine3d moved = Eigen::Affine3d::Identity();
  moved.translate(Eigen::Vector3d(0.1, 0, 0));
  lattice.setFrame(moved);
  EXPECT_THROW(e.checkLattice(lattice), LatticeError);
  BoxLatticeOptions other;
  other.counts = {3, 3, 3};
  EXPECT_THROW(e.checkLattice(makeBoxLattice(other)), LatticeError);
}

TEST(Embedding, SingleCellLatticesKeepTheOriginalOrder) {
  const Lattice lattice = makeBoxLattice();  // 4x4x4 cubic: one cell
  std::mt19937 rng(9);
  const Embedding e = embed(lattice, testing::restImages(lattice, testing::randomParameters(lattice, 100, rng)));
  EXPECT_TRUE(e.order().empty());
  EXPECT_LE(e.memoryBytes(), 100u * 64u + 4096u);
}

}  // namespace
}  // namespace ffdkit::ffd
