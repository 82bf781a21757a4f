#include "ffdkit/ffd/pipeline.h"

#include <algorithm>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "test_lattices.h"

namespace ffdkit::ffd {
namespace {

Lattice boxAt(const Eigen::Vector3d& corner, double size, int count = 3) {
  BoxLatticeOptions options;
  options.counts = {count, count, count};
  options.frame = Eigen::Affine3d::Identity();
  options.frame.translate(corner);
  options.frame.scale(size);
  return makeBoxLattice(options);
}

Eigen::MatrixX3d randomPointsInUnitBox(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Eigen::MatrixX3d Q(n, 3);
  for (Eigen::Index r = 0; r < n; ++r) Q.row(r) << U(rng), U(rng), U(rng);
  return Q;
}

// The pipeline computed by hand: embed and deform lattice after lattice.
Eigen::MatrixX3d sequential(const std::vector<const Lattice*>& lattices, Eigen::MatrixX3d points) {
  for (const Lattice* lattice : lattices) {
    Deformer deformer(embed(*lattice, points));
    points = deformer.deform(*lattice, points);
  }
  return points;
}

void bend(Lattice& lattice, double amount) {
  Eigen::MatrixX3d P = lattice.controlPoints();
  P.col(2).array() += amount * P.col(0).array().square();
  lattice.setControlPoints(P);
}

TEST(Pipeline, RunsLatticesInPreOrderWithSiblingPriorities) {
  Pipeline pipeline(randomPointsInUnitBox(10, 1));
  const LatticeId a = pipeline.addLattice(boxAt({0, 0, 0}, 1.0));
  const LatticeId b = pipeline.addLattice(boxAt({0, 0, 0}, 0.5), a, 1);
  const LatticeId c = pipeline.addLattice(boxAt({0.5, 0, 0}, 0.5), a, 0);
  const LatticeId d = pipeline.addLattice(boxAt({0.5, 0.5, 0}, 0.25), c);
  const LatticeId e = pipeline.addLattice(boxAt({0, 0, 0}, 2.0));  // a second root
  EXPECT_EQ(pipeline.order(), (std::vector<LatticeId>{a, c, d, b, e}));
  pipeline.setPriority(b, -1);
  EXPECT_EQ(pipeline.order(), (std::vector<LatticeId>{a, b, c, d, e}));
  pipeline.update();
  ASSERT_EQ(pipeline.lastReport().size(), 5u);
  EXPECT_EQ(pipeline.lastReport()[1].id, b);
  pipeline.removeLattice(c);
  EXPECT_EQ(pipeline.order(), (std::vector<LatticeId>{a, b, e}));
  EXPECT_THROW(pipeline.lattice(d), LatticeError);
  EXPECT_THROW(pipeline.addLattice(boxAt({0, 0, 0}, 1.0), d), LatticeError);
}

TEST(Pipeline, OutputOfOneLatticeIsTheInputOfTheNext) {
  const Eigen::MatrixX3d Q = randomPointsInUnitBox(2000, 2);
  Pipeline pipeline(Q);
  const LatticeId parent = pipeline.addLattice(boxAt({-0.1, -0.1, -0.1}, 1.2, 4));
  const LatticeId child = pipeline.addLattice(boxAt({0.2, 0.2, 0.2}, 0.6, 3), parent);
  bend(pipeline.lattice(parent), 0.3);
  bend(pipeline.lattice(child), -0.2);
  const Eigen::MatrixX3d out = pipeline.update();
  const Eigen::MatrixX3d expected = sequential({&pipeline.lattice(parent), &pipeline.lattice(child)}, Q);
  EXPECT_LT((out - expected).cwiseAbs().maxCoeff(), 1e-12);
  // Order matters: the child deforms the parent's output, not the other way round.
  const Eigen::MatrixX3d swapped = sequential({&pipeline.lattice(child), &pipeline.lattice(parent)}, Q);
  EXPECT_GT((out - swapped).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(Pipeline, EditingTheLastLatticeUpdatesIncrementally) {
  const Eigen::MatrixX3d Q = randomPointsInUnitBox(2000, 3);
  Pipeline pipeline(Q);
  const LatticeId parent = pipeline.addLattice(boxAt({-0.1, -0.1, -0.1}, 1.2, 4));
  const LatticeId child = pipeline.addLattice(boxAt({0.2, 0.2, 0.2}, 0.6, 3), parent);
  pipeline.update();
  pipeline.setActiveLattice(child);
  pipeline.lattice(child).setControlPoint(13, Eigen::Vector3d(0.5, 0.6, 0.7));
  const Eigen::MatrixX3d out = pipeline.update();
  EXPECT_FALSE(pipeline.lastReport()[0].outputChanged);
  EXPECT_FALSE(pipeline.lastReport()[1].reembedded);
  EXPECT_TRUE(pipeline.lastReport()[1].outputChanged);
  const Eigen::MatrixX3d expected = sequential({&pipeline.lattice(parent), &pipeline.lattice(child)}, Q);
  EXPECT_LT((out - expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Pipeline, ThrottlesReembeddingOfLatticesOtherThanTheActiveOne) {
  const Eigen::MatrixX3d Q = randomPointsInUnitBox(2000, 4);
  for (ReembedThrottle throttle : {ReembedThrottle::immediate(), ReembedThrottle::everyN(3), ReembedThrottle::onDemand()}) {
    Pipeline pipeline(Q);
    const LatticeId parent = pipeline.addLattice(boxAt({-0.1, -0.1, -0.1}, 1.2, 4));
    const LatticeId child = pipeline.addLattice(boxAt({0.2, 0.2, 0.2}, 0.6, 3), parent);
    bend(pipeline.lattice(child), 0.2);
    pipeline.setThrottle(throttle);
    pipeline.update();
    pipeline.setActiveLattice(parent);
    int reembeds = 0;
    for (int step = 1; step <= 6; ++step) {
      bend(pipeline.lattice(parent), 0.02);  // the parent is dragged: the child's input moves
      pipeline.update();
      EXPECT_TRUE(pipeline.lastReport()[0].outputChanged);
      reembeds += pipeline.lastReport()[1].reembedded;
      EXPECT_NE(pipeline.lastReport()[1].reembedded, pipeline.lastReport()[1].approximate);
    }
    const Eigen::MatrixX3d expected = sequential({&pipeline.lattice(parent), &pipeline.lattice(child)}, Q);
    const double error = (pipeline.points() - expected).cwiseAbs().maxCoeff();
    switch (throttle.kind) {
      case ReembedThrottle::Kind::Immediate:
        EXPECT_EQ(reembeds, 6);
        EXPECT_LT(error, 1e-12);
        break;
      case ReembedThrottle::Kind::EveryN:
        EXPECT_EQ(reembeds, 2);  // steps 3 and 6
        EXPECT_LT(error, 1e-12);
        break;
      case ReembedThrottle::Kind::OnDemand:
        EXPECT_EQ(reembeds, 0);
        EXPECT_GT(error, 1e-6);  // approximate while dragging ...
        {
          // ... but close except for the few points that crossed the child's boundary since it was
          // embedded (Identity policy: those keep or lose the child's displacement).
          const Eigen::VectorXd rowError = (pipeline.points() - expected).rowwise().norm();
          EXPECT_LT((rowError.array() > 0.01).count(), Q.rows() / 20);
          std::vector<double> sorted(rowError.data(), rowError.data() + rowError.size());
          std::sort(sorted.begin(), sorted.end());
          EXPECT_LT(sorted[sorted.size() / 2], 1e-3) << "median error";
        }
        pipeline.reembedAll();    // gesture release
        EXPECT_TRUE(pipeline.lastReport()[1].reembedded);
        EXPECT_LT((pipeline.points() - expected).cwiseAbs().maxCoeff(), 1e-12);
        break;
    }
  }
}

TEST(Pipeline, MovingALatticeFrameReembedsIt) {
  const Eigen::MatrixX3d Q = randomPointsInUnitBox(500, 5);
  Pipeline pipeline(Q);
  const LatticeId id = pipeline.addLattice(boxAt({0, 0, 0}, 1.0, 3));
  bend(pipeline.lattice(id), 0.3);
  pipeline.update();
  Eigen::Affine3d frame = pipeline.lattice(id).frame();
  frame.translate(Eigen::Vector3d(0.1, 0, 0));
  pipeline.lattice(id).setFrame(frame);
  pipeline.setActiveLattice(id);
  pipeline.update();
  EXPECT_TRUE(pipeline.lastReport()[0].reembedded);
  EXPECT_LT((pipeline.points() - sequential({&pipeline.lattice(id)}, Q)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Pipeline, EmptyPipelineReturnsTheInput) {
  const Eigen::MatrixX3d Q = randomPointsInUnitBox(5, 6);
  Pipeline pipeline(Q);
  EXPECT_EQ(pipeline.update(), Q);
  EXPECT_THROW(pipeline.setThrottle(ReembedThrottle::everyN(0)), LatticeError);
  Eigen::MatrixX3d bad = Q;
  bad(1, 1) = std::nan("");
  EXPECT_THROW(pipeline.setPoints(bad), LatticeError);
}

}  // namespace
}  // namespace ffdkit::ffd
