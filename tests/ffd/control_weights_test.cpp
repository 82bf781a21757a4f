#include "ffdkit/ffd/control_weights.h"

#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "ffdkit/ffd/cylindrical_lattice.h"
#include "ffdkit/ffd/deformer.h"
#include "test_lattices.h"

namespace ffdkit::ffd {
namespace {

// x = Q + sum_kept w_j F.linear() (P_j - Pbar_j): the weighted sum the weights stand for.
Eigen::MatrixX3d weightedSum(const Lattice& lattice, const ControlWeights& cw, const Eigen::MatrixX3d& Q) {
  const Eigen::MatrixX3d D = (lattice.controlPoints() - lattice.restPoints()) * lattice.frame().linear().transpose();
  Eigen::MatrixX3d out = Q;
  for (Eigen::Index p = 0; p < Q.rows(); ++p)
    for (int r = 0; r < cw.k; ++r)
      if (cw.indices(p, r) >= 0) out.row(p) += cw.weights(p, r) * D.row(cw.indices(p, r));
  return out;
}

Eigen::MatrixX3d moved(const Lattice& lattice, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-0.2, 0.2);
  Eigen::MatrixX3d P = lattice.controlPoints();
  for (Eigen::Index r = 0; r < P.rows(); ++r)
    for (int c = 0; c < 3; ++c) P(r, c) += U(rng);
  return P;
}

// 300 points in world coordinates: 200 inside the lattice and 100 around it (outside policies).
Eigen::MatrixX3d pointsAround(const Lattice& lattice, std::mt19937& rng) {
  Eigen::MatrixX3d uvw = testing::randomParameters(lattice, 300, rng);
  uvw.topRows(100).array() = uvw.topRows(100).array() * 1.6 - 0.3;
  Eigen::MatrixX3d Q(uvw.rows(), 3);
  for (Eigen::Index p = 0; p < Q.rows(); ++p)
    Q.row(p) = (lattice.frame() * lattice.evaluateRest(uvw.row(p).transpose())).transpose();
  return Q;
}

TEST(ControlWeights, TheWholeWindowReproducesTheDeformerOnEveryBasisAndPolicy) {
  std::mt19937 rng(7);
  std::vector<Lattice> lattices;
  for (int t = 0; t < 8; ++t) lattices.push_back(testing::randomLattice(rng, t % 2 ? 0.2 : 0.0));
  lattices.push_back(makeCylindricalLattice());
  BoxLatticeOptions falloff;
  falloff.outsidePolicy = OutsidePolicy::falloff(0.3);
  lattices.push_back(makeBoxLattice(falloff));
  BoxLatticeOptions extrapolate;
  extrapolate.bases = {AxisBasis::bernstein(), AxisBasis::bernstein(), AxisBasis::bernstein()};
  extrapolate.outsidePolicy = OutsidePolicy::extrapolate();
  lattices.push_back(makeBoxLattice(extrapolate));
  for (Lattice& lattice : lattices) {
    const Eigen::MatrixX3d Q = pointsAround(lattice, rng);
    const Embedding embedding = embed(lattice, Q);
    lattice.setControlPoints(moved(lattice, rng));
    Deformer deformer(embedding);
    const Eigen::MatrixX3d exact = deformer.deform(lattice, Q);
    int window = 1;
    for (int a = 0; a < 3; ++a) window *= lattice.axis(a).degree() + 1;
    const ControlWeights all = largestControlWeights(lattice, embedding, window);
    const double scale = lattice.restSize() * lattice.frame().linear().norm();
    EXPECT_LT((weightedSum(lattice, all, Q) - exact).rowwise().norm().maxCoeff(), 1e-12 * scale);
    for (Eigen::Index p = 0; p < Q.rows(); ++p) {
      EXPECT_NEAR(all.weights.row(p).sum(), all.total[p], 1e-12);
      EXPECT_EQ(all.dropped[p], 0.0);
      const PointStatus status = embedding.status(p);
      if (status == PointStatus::Inside) {
        EXPECT_EQ(all.total[p], 1.0);
      }
      for (int r = 1; r < window; ++r) EXPECT_GE(all.weights(p, r - 1), all.weights(p, r));
    }
  }
}

TEST(ControlWeights, PruningKeepsTheLargestAndCountsWhatItDrops) {
  std::mt19937 rng(3);
  const Lattice lattice = makeBoxLattice();  // cubic 4x4x4: a window of 64
  const Eigen::MatrixX3d Q = testing::restImages(lattice, testing::randomParameters(lattice, 500, rng));
  const Embedding embedding = embed(lattice, Q);
  const ControlWeights all = largestControlWeights(lattice, embedding, 64);
  const ControlWeights four = largestControlWeights(lattice, embedding, 4);
  for (Eigen::Index p = 0; p < Q.rows(); ++p) {
    double kept = 0.0;
    for (int r = 0; r < 4; ++r) {
      EXPECT_EQ(four.indices(p, r), all.indices(p, r));
      EXPECT_EQ(four.weights(p, r), all.weights(p, r));
      kept += four.weights(p, r);
    }
    EXPECT_NEAR(kept + four.dropped[p], 1.0, 1e-12);  // all weights are >= 0 inside
  }
}

TEST(ControlWeights, OneControlPointsWeightIsHowFarItsMoveMovesEachPoint) {
  // Independent of the kernel: the deformer's output when only control point f moves by dP,
  // minus the output before, is weight[p] * F.linear() dP (the output is linear in P).
  std::mt19937 rng(11);
  std::vector<Lattice> lattices;
  for (int t = 0; t < 6; ++t) lattices.push_back(testing::randomLattice(rng, t % 2 ? 0.2 : 0.0));
  lattices.push_back(makeCylindricalLattice());  // periodic: windows wrap onto a control point
  BoxLatticeOptions falloff;
  falloff.outsidePolicy = OutsidePolicy::falloff(0.3);
  lattices.push_back(makeBoxLattice(falloff));
  BoxLatticeOptions identity;
  identity.outsidePolicy = OutsidePolicy::identity();
  lattices.push_back(makeBoxLattice(identity));
  for (Lattice& lattice : lattices) {
    const Eigen::MatrixX3d Q = pointsAround(lattice, rng);
    const Embedding embedding = embed(lattice, Q);
    lattice.setControlPoints(moved(lattice, rng));
    Deformer deformer(embedding);
    const Eigen::MatrixX3d before = deformer.deform(lattice, Q);
    int window = 1;
    for (int a = 0; a < 3; ++a) window *= lattice.axis(a).degree() + 1;
    const ControlWeights all = largestControlWeights(lattice, embedding, window);
    const double scale = lattice.restSize() * lattice.frame().linear().norm();
    std::uniform_int_distribution<Eigen::Index> pick(0, lattice.pointCount() - 1);
    for (int trial = 0; trial < 4; ++trial) {
      const Eigen::Index f = pick(rng);
      const Eigen::VectorXd w = controlPointWeights(lattice, embedding, f);
      ASSERT_EQ(w.size(), Q.rows());
      const Eigen::Vector3d dP(0.3, -0.2, 0.25);
      Lattice pushed = lattice;
      pushed.setControlPoint(f, lattice.controlPoints().row(f).transpose() + dP);
      const Eigen::MatrixX3d after = Deformer(embedding).deform(pushed, Q);
      const Eigen::RowVector3d world = (lattice.frame().linear() * dP).transpose();
      int supported = 0;
      for (Eigen::Index p = 0; p < Q.rows(); ++p) {
        EXPECT_LT((after.row(p) - before.row(p) - w[p] * world).norm(), 1e-12 * scale) << "point " << p;
        double expected = 0.0;  // the window's weights that name f
        for (int r = 0; r < window; ++r)
          if (all.indices(p, r) == f) expected += all.weights(p, r);
        EXPECT_NEAR(w[p], expected, 1e-15);
        supported += w[p] != 0.0;
      }
      EXPECT_GT(supported, 0);
    }
  }
  const Lattice lattice = makeBoxLattice();
  const Embedding embedding = embed(lattice, Eigen::MatrixX3d::Constant(1, 3, 0.5));
  EXPECT_THROW(controlPointWeights(lattice, embedding, 64), LatticeError);
  EXPECT_THROW(controlPointWeights(lattice, embedding, -1), LatticeError);
}

TEST(ControlWeights, OneControlPointsWeightsIntoAReusedBufferAreTheSameBits) {
  // The form the view's drags use (one buffer for every drag's first step) writes every point,
  // also those outside the support and left unchanged, whatever the buffer held: the bits of the
  // returning form on every basis and policy, and on a rational lattice.
  std::mt19937 rng(12);
  std::vector<Lattice> lattices;
  for (int t = 0; t < 4; ++t) lattices.push_back(testing::randomLattice(rng, t % 2 ? 0.2 : 0.0));
  lattices.push_back(makeCylindricalLattice());
  BoxLatticeOptions falloff;
  falloff.outsidePolicy = OutsidePolicy::falloff(0.3);
  lattices.push_back(makeBoxLattice(falloff));
  BoxLatticeOptions identity;
  identity.outsidePolicy = OutsidePolicy::identity();
  lattices.push_back(makeBoxLattice(identity));
  Lattice rational = makeBoxLattice();
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(rational.pointCount());
  weights[21] = 3.0;
  weights[42] = 0.5;
  rational.setRestWeights(weights);
  rational.setWeights(weights);
  lattices.push_back(rational);
  for (const Lattice& lattice : lattices) {
    const Eigen::MatrixX3d Q = pointsAround(lattice, rng);
    const Embedding embedding = embed(lattice, Q);
    Eigen::VectorXd reused = Eigen::VectorXd::Constant(Q.rows(), std::numeric_limits<double>::quiet_NaN());
    const double* memory = reused.data();
    std::uniform_int_distribution<Eigen::Index> pick(0, lattice.pointCount() - 1);
    for (int trial = 0; trial < 4; ++trial) {
      const Eigen::Index f = pick(rng);
      controlPointWeights(lattice, embedding, f, reused);
      const Eigen::VectorXd fresh = controlPointWeights(lattice, embedding, f);
      EXPECT_EQ(reused.data(), memory);  // the buffer's own memory, no new one
      ASSERT_EQ(reused.size(), fresh.size());
      for (Eigen::Index p = 0; p < Q.rows(); ++p) EXPECT_EQ(reused[p], fresh[p]) << "point " << p << " of control point " << f;
    }
  }
  // A buffer of another size is resized; a bad control point throws before the buffer is touched.
  const Lattice lattice = makeBoxLattice();
  const Embedding embedding = embed(lattice, Eigen::MatrixX3d::Constant(2, 3, 0.5));
  Eigen::VectorXd other = Eigen::VectorXd::Constant(5, 7.0);
  EXPECT_THROW(controlPointWeights(lattice, embedding, 64, other), LatticeError);
  EXPECT_EQ(other, Eigen::VectorXd::Constant(5, 7.0));
  controlPointWeights(lattice, embedding, 21, other);
  EXPECT_EQ(other, controlPointWeights(lattice, embedding, 21));
}

TEST(ControlWeights, RejectsKBelowOneAndAStaleEmbedding) {
  Lattice lattice = makeBoxLattice();
  const Embedding embedding = embed(lattice, Eigen::MatrixX3d::Constant(1, 3, 0.5));
  EXPECT_THROW(largestControlWeights(lattice, embedding, 0), LatticeError);
  lattice.setFrame(Eigen::Affine3d(Eigen::Translation3d(1.0, 0.0, 0.0)));
  EXPECT_THROW(largestControlWeights(lattice, embedding, 4), LatticeError);
}

}  // namespace
}  // namespace ffdkit::ffd
