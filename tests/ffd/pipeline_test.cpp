#include "ffdkit/ffd/pipeline.h"

#include <algorithm>
#include <array>
#include <limits>
#include <random>
#include <thread>
#include <utility>
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

// A 4x4x4 parent lattice around the unit box bent by 0.3, and a 3x3x3 child inside it bent by -0.2.
std::pair<LatticeId, LatticeId> addBentParentAndChild(Pipeline& pipeline) {
  const LatticeId parent = pipeline.addLattice(boxAt({-0.1, -0.1, -0.1}, 1.2, 4));
  const LatticeId child = pipeline.addLattice(boxAt({0.2, 0.2, 0.2}, 0.6, 3), parent);
  bend(pipeline.lattice(parent), 0.3);
  bend(pipeline.lattice(child), -0.2);
  return {parent, child};
}

TEST(Pipeline, RunsLatticesInPreOrderWithSiblingPriorities) {
  Pipeline pipeline(testing::uniformPointsInUnitBox(10, 1));
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
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(2000, 2);
  Pipeline pipeline(Q);
  const auto [parent, child] = addBentParentAndChild(pipeline);
  const Eigen::MatrixX3d out = pipeline.update();
  const Eigen::MatrixX3d expected = sequential({&pipeline.lattice(parent), &pipeline.lattice(child)}, Q);
  EXPECT_LT((out - expected).cwiseAbs().maxCoeff(), 1e-12);
  // Order matters: the child deforms the parent's output, not the other way round.
  const Eigen::MatrixX3d swapped = sequential({&pipeline.lattice(child), &pipeline.lattice(parent)}, Q);
  EXPECT_GT((out - swapped).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(Pipeline, TakePointsHandsOverTheOutputAndTheNextRunEmbedsAgain) {
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(2000, 2);
  Pipeline pipeline(Q);
  EXPECT_EQ(pipeline.takePoints(), Q);  // no stage ran: the input, which stays
  const auto [parent, child] = addBentParentAndChild(pipeline);
  const Eigen::MatrixX3d expected = sequential({&pipeline.lattice(parent), &pipeline.lattice(child)}, Q);
  pipeline.update();
  const Eigen::MatrixX3d taken = pipeline.takePoints();
  EXPECT_LT((taken - expected).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(pipeline.points(), Q);
  EXPECT_EQ(pipeline.embedding(parent), nullptr);
  EXPECT_EQ(pipeline.update(), taken);  // bit for bit
  for (const StageReport& report : pipeline.lastReport()) EXPECT_TRUE(report.reembedded);
}

TEST(Pipeline, AdoptingTakesThePointsOverWithoutACopyAndChecksThem) {
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(200000, 5);  // several chunks of the check
  Pipeline copied(Q);
  Eigen::MatrixX3d moved = Q;
  const double* storage = moved.data();
  Pipeline adopted = Pipeline::adopting(std::move(moved));
  EXPECT_EQ(adopted.inputPoints().data(), storage);
  for (Pipeline* p : {&copied, &adopted}) addBentParentAndChild(*p);
  EXPECT_EQ(adopted.update(), copied.update());
  for (Eigen::Index bad : {Eigen::Index(0), Eigen::Index(131071), Q.rows() - 1}) {
    Eigen::MatrixX3d broken = Q;
    broken(bad, 1) = std::numeric_limits<double>::quiet_NaN();
    try {
      (void)Pipeline::adopting(std::move(broken));
      ADD_FAILURE() << "point " << bad << " is NaN";
    } catch (const LatticeError& error) {
      EXPECT_EQ(std::string(error.what()), "pipeline: object point " + std::to_string(bad) + " is not finite");
    }
  }
}

// Precision::Single reaches every stage, and a change of precision evaluates an embedded stage
// in full at the next run without embedding it again (the stages after it see a new input).
TEST(Pipeline, PrecisionReachesEveryStageAndAChangeEvaluatesThemInFull) {
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(20000, 4);
  Pipeline pipeline(Q);
  const auto [parent, child] = addBentParentAndChild(pipeline);
  const Eigen::MatrixX3d twice = pipeline.update();
  pipeline.setPrecision(Precision::Single);
  const Eigen::MatrixX3d once = pipeline.update();
  EXPECT_FALSE(pipeline.lastReport()[0].reembedded);  // evaluated in full in its new precision
  EXPECT_TRUE(pipeline.lastReport()[0].outputChanged);
  EXPECT_TRUE(pipeline.lastReport()[1].reembedded);  // its input moved
  // By hand: each stage a single-precision Deformer on the previous stage's output.
  // The stages by value: clang before 16 cannot capture a structured binding.
  auto singleByHand = [&, stages = std::array{parent, child}] {
    Eigen::MatrixX3d points = Q;
    for (LatticeId id : stages) {
      Deformer deformer(embed(pipeline.lattice(id), points));
      deformer.setPrecision(Precision::Single);
      points = deformer.deform(pipeline.lattice(id), points);
    }
    return points;
  };
  EXPECT_LT((once - singleByHand()).cwiseAbs().maxCoeff(), 1e-12);
  const double drift = (once - twice).cwiseAbs().maxCoeff();
  EXPECT_GT(drift, 1e-10);  // float rounding of displacements of at most 0.3
  EXPECT_LT(drift, 1e-6 * 0.3);
  // An edit of the child stays single and incremental.
  pipeline.lattice(child).setControlPoint(13, Eigen::Vector3d(0.5, 0.6, 0.7));
  const Eigen::MatrixX3d edited = pipeline.update();
  EXPECT_FALSE(pipeline.lastReport()[1].reembedded);
  EXPECT_LT((edited - singleByHand()).cwiseAbs().maxCoeff(), 1e-12);
  // Back to double: the double result again.
  pipeline.setPrecision(Precision::Double);
  const Eigen::MatrixX3d back = pipeline.update();
  EXPECT_LT((back - sequential({&pipeline.lattice(parent), &pipeline.lattice(child)}, Q)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT((back - edited).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(Pipeline, EditingTheLastLatticeUpdatesIncrementally) {
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(2000, 3);
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

TEST(Pipeline, DeltaUpdatesAgreeWithExactOnesAndTheNextExactRunIsBitIdentical) {
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(3000, 5);
  struct Chain {
    Pipeline pipeline;
    LatticeId parent, child;
    explicit Chain(const Eigen::MatrixX3d& points) : pipeline(points) {
      parent = pipeline.addLattice(boxAt({-0.1, -0.1, -0.1}, 1.2, 4));
      child = pipeline.addLattice(boxAt({0.2, 0.2, 0.2}, 0.6, 3), parent);
      bend(pipeline.lattice(child), 0.2);
      pipeline.update();
      pipeline.setActiveLattice(parent);
    }
  };
  Chain delta(Q), exact(Q), finished(Q);
  delta.pipeline.setUpdateMode(UpdateMode::Delta);
  finished.pipeline.setUpdateMode(UpdateMode::Delta);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> pick(0, 63);
  std::normal_distribution<double> move(0.0, 0.02);
  const double size = 1.2;  // of the dragged lattice
  for (int step = 1; step <= 200; ++step) {
    // One or two control points of the parent per step, as a drag moves them.
    const int moved = 1 + step % 2;
    for (int k = 0; k < moved; ++k) {
      const int f = pick(rng);
      const Eigen::Vector3d to = exact.pipeline.lattice(exact.parent).controlPoints().row(f).transpose() +
                                 Eigen::Vector3d(move(rng), move(rng), move(rng));
      for (Chain* c : {&delta, &exact, &finished}) c->pipeline.lattice(c->parent).setControlPoint(f, to);
    }
    for (Chain* c : {&delta, &exact, &finished}) c->pipeline.update();
    ASSERT_TRUE(delta.pipeline.lastReport()[0].delta) << step;
    ASSERT_FALSE(exact.pipeline.lastReport()[0].delta) << step;
    EXPECT_TRUE(delta.pipeline.lastReport()[1].reembedded);  // the child follows its moved input
    EXPECT_LE((delta.pipeline.points() - exact.pipeline.points()).cwiseAbs().maxCoeff(), 1e-12 * size) << step;
  }
  EXPECT_GT((delta.pipeline.points() - exact.pipeline.points()).cwiseAbs().maxCoeff(), 0.0)
      << "the deltas round differently from an exact evaluation (else this test proves nothing)";
  // The next exact run evaluates the parent in full (and re-embeds the child on its new output):
  // bit for bit what exact updates gave, whether an update() in Exact mode or reembedAll().
  delta.pipeline.setUpdateMode(UpdateMode::Exact);
  EXPECT_EQ(delta.pipeline.pointsToEmbed(), Q.rows());
  delta.pipeline.update();
  EXPECT_TRUE(delta.pipeline.lastReport()[0].outputChanged);
  EXPECT_FALSE(delta.pipeline.lastReport()[0].delta);
  EXPECT_TRUE(delta.pipeline.lastReport()[1].reembedded);
  EXPECT_TRUE(delta.pipeline.points() == exact.pipeline.points());
  EXPECT_EQ(finished.pipeline.pointsToEmbed(/*reembedAll=*/true), Q.rows());
  finished.pipeline.reembedAll();
  EXPECT_TRUE(finished.pipeline.points() == exact.pipeline.points());
  // Once exact, a further exact run has nothing to do.
  delta.pipeline.update();
  EXPECT_FALSE(delta.pipeline.lastReport()[0].outputChanged);
  EXPECT_EQ(delta.pipeline.pointsToEmbed(), 0);
}

TEST(Pipeline, ThrottlesReembeddingOfLatticesOtherThanTheActiveOne) {
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(2000, 4);
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
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(500, 5);
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
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(5, 6);
  Pipeline pipeline(Q);
  EXPECT_EQ(pipeline.update(), Q);
  EXPECT_THROW(pipeline.setThrottle(ReembedThrottle::everyN(0)), LatticeError);
  Eigen::MatrixX3d bad = Q;
  bad(1, 1) = std::nan("");
  EXPECT_THROW(pipeline.setPoints(bad), LatticeError);
}

// A chain root -> child -> grandchild of bent box lattices over n random points: every stage
// moves the points, so every stage's input depends on the one before.
struct Chain {
  Pipeline pipeline;
  std::vector<LatticeId> ids;
};

Chain makeChain(const Eigen::MatrixX3d& Q, ReembedThrottle throttle = ReembedThrottle::immediate()) {
  Chain c{Pipeline(Q), {}};
  c.ids.push_back(c.pipeline.addLattice(boxAt({-0.1, -0.1, -0.1}, 1.2, 4)));
  c.ids.push_back(c.pipeline.addLattice(boxAt({0.1, 0.1, 0.1}, 0.8, 3), c.ids[0]));
  c.ids.push_back(c.pipeline.addLattice(boxAt({0.2, 0.2, 0.2}, 0.6, 3), c.ids[1]));
  for (std::size_t i = 0; i < c.ids.size(); ++i) bend(c.pipeline.lattice(c.ids[i]), 0.1 + 0.05 * double(i));
  c.pipeline.setThrottle(throttle);
  return c;
}

// Moves a lattice's frame: its rest lattice moves in the world, so it must be re-embedded.
void shift(Lattice& lattice, double dx) {
  Eigen::Affine3d frame = lattice.frame();
  frame.pretranslate(Eigen::Vector3d(dx, 0, 0));
  lattice.setFrame(frame);
}

using Calls = std::vector<std::pair<Eigen::Index, Eigen::Index>>;

EmbedProgress recorder(Calls& calls) {
  return [&calls](Eigen::Index done, Eigen::Index total) {
    calls.emplace_back(done, total);
    return true;
  };
}

// Returns false (cancels) from the first call with done >= at.
EmbedProgress cancelAt(Eigen::Index at, Calls& calls) {
  return [&calls, at](Eigen::Index done, Eigen::Index total) {
    calls.emplace_back(done, total);
    return done < at;
  };
}

void expectMonotoneUpTo(const Calls& calls, Eigen::Index total) {
  ASSERT_GE(calls.size(), 2u);
  EXPECT_EQ(calls.front(), std::make_pair(Eigen::Index(0), total));
  EXPECT_EQ(calls.back(), std::make_pair(total, total));
  for (std::size_t i = 1; i < calls.size(); ++i) {
    EXPECT_EQ(calls[i].second, total);
    EXPECT_GE(calls[i].first, calls[i - 1].first) << "call " << i;
  }
}

TEST(PipelineProgress, CountsThePointsOfEveryStageThatReembeds) {
  const Eigen::Index n = kEmbedProgressChunk + 5000;
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(n, 21);
  Chain c = makeChain(Q);
  EXPECT_EQ(c.pipeline.pointsToEmbed(), 3 * n);
  Calls calls;
  c.pipeline.update(recorder(calls));
  expectMonotoneUpTo(calls, 3 * n);

  // An edit of control points re-embeds nothing: (0, 0) and (0, 0).
  bend(c.pipeline.lattice(c.ids[2]), 0.05);
  EXPECT_EQ(c.pipeline.pointsToEmbed(), 0);
  calls.clear();
  c.pipeline.update(recorder(calls));
  expectMonotoneUpTo(calls, 0);

  // The middle lattice moves: it and the stage after it (its input moved) re-embed.
  shift(c.pipeline.lattice(c.ids[1]), 0.02);
  EXPECT_EQ(c.pipeline.pointsToEmbed(), 2 * n);
  calls.clear();
  c.pipeline.update(recorder(calls));
  expectMonotoneUpTo(calls, 2 * n);
  EXPECT_FALSE(c.pipeline.lastReport()[0].reembedded);
  EXPECT_TRUE(c.pipeline.lastReport()[1].reembedded);
  EXPECT_TRUE(c.pipeline.lastReport()[2].reembedded);
  EXPECT_GT(c.pipeline.lastReport()[1].embedSeconds, 0.0);
  EXPECT_EQ(c.pipeline.lastReport()[0].embedSeconds, 0.0);

  // Throttled: only the active lattice and the stages that must (no compatible embedding) count.
  c.pipeline.setThrottle(ReembedThrottle::onDemand());
  c.pipeline.setActiveLattice(c.ids[0]);
  shift(c.pipeline.lattice(c.ids[0]), 0.01);
  EXPECT_EQ(c.pipeline.pointsToEmbed(), n);
  EXPECT_EQ(c.pipeline.pointsToEmbed(/*reembedAll=*/true), 3 * n);
  calls.clear();
  c.pipeline.update(recorder(calls));
  expectMonotoneUpTo(calls, n);
  EXPECT_TRUE(c.pipeline.lastReport()[1].approximate);
  EXPECT_EQ(c.pipeline.pointsToEmbed(true), 2 * n);
  calls.clear();
  c.pipeline.reembedAll(recorder(calls));
  expectMonotoneUpTo(calls, 2 * n);
}

TEST(PipelineProgress, ACancelledRunKeepsThePipelineConsistentAndTheNextRunExact) {
  const Eigen::Index n = kEmbedProgressChunk + 5000;
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(n, 22);
  Chain c = makeChain(Q);
  c.pipeline.update();
  const Eigen::MatrixX3d before = c.pipeline.points();
  for (LatticeId id : c.ids) shift(c.pipeline.lattice(id), 0.03);
  Calls calls;
  // Cancel inside the second stage's embedding (3n points to embed in all).
  EXPECT_THROW(c.pipeline.update(cancelAt(n + kEmbedProgressChunk, calls)), Cancelled);
  EXPECT_GE(calls.back().first, n + kEmbedProgressChunk);
  EXPECT_LE(calls.back().first, 2 * n);
  // The first stage finished; the second (cancelled) and third still hold their old embeddings
  // and outputs, so the object still shows the last complete result.
  EXPECT_NO_THROW(c.pipeline.embedding(c.ids[0])->checkLattice(c.pipeline.lattice(c.ids[0])));
  EXPECT_THROW(c.pipeline.embedding(c.ids[1])->checkLattice(c.pipeline.lattice(c.ids[1])), LatticeError);
  EXPECT_THROW(c.pipeline.embedding(c.ids[2])->checkLattice(c.pipeline.lattice(c.ids[2])), LatticeError);
  EXPECT_EQ(c.pipeline.points(), before);
  EXPECT_EQ(c.pipeline.pointsToEmbed(), 2 * n) << "the cancelled stage and the one after it";

  c.pipeline.update();
  EXPECT_FALSE(c.pipeline.lastReport()[0].reembedded) << "kept from the cancelled run";
  EXPECT_TRUE(c.pipeline.lastReport()[1].reembedded);
  Chain fresh = makeChain(Q);
  for (LatticeId id : fresh.ids) shift(fresh.pipeline.lattice(id), 0.03);
  EXPECT_EQ(c.pipeline.points(), fresh.pipeline.update()) << "bit for bit a never-cancelled result";
}

TEST(PipelineProgress, ACancelledThrottledRunIsRepeatedAsIfNeverCancelled) {
  // Dragging the root with the others throttled (every 2nd update): the middle stage is deformed
  // approximately, the last is re-embedded because it is active; cancel inside the last one.
  // Afterwards the pipeline must follow exactly the same path as a twin that was never cancelled.
  const Eigen::Index n = kEmbedProgressChunk + 5000;
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(n, 23);
  Chain cancelled = makeChain(Q, ReembedThrottle::everyN(2));
  Chain twin = makeChain(Q, ReembedThrottle::everyN(2));
  for (Chain* c : {&cancelled, &twin}) {
    c->pipeline.update();
    c->pipeline.setActiveLattice(c->ids[2]);
    bend(c->pipeline.lattice(c->ids[0]), 0.02);
    shift(c->pipeline.lattice(c->ids[2]), 0.01);
  }
  ASSERT_EQ(cancelled.pipeline.pointsToEmbed(), n);
  Calls calls;
  EXPECT_THROW(cancelled.pipeline.update(cancelAt(kEmbedProgressChunk, calls)), Cancelled);
  cancelled.pipeline.update();
  twin.pipeline.update();
  ASSERT_EQ(twin.pipeline.lastReport().size(), 3u);
  EXPECT_TRUE(twin.pipeline.lastReport()[1].approximate);
  EXPECT_TRUE(cancelled.pipeline.lastReport()[1].approximate);
  EXPECT_FALSE(cancelled.pipeline.lastReport()[1].outputChanged) << "kept from the cancelled run, not recomputed";
  EXPECT_EQ(cancelled.pipeline.points(), twin.pipeline.points());
  // The throttle counted the cancelled run once: the next drag step re-embeds the middle stage on both.
  for (Chain* c : {&cancelled, &twin}) {
    bend(c->pipeline.lattice(c->ids[0]), 0.02);
    c->pipeline.update();
    EXPECT_TRUE(c->pipeline.lastReport()[1].reembedded);
  }
  EXPECT_EQ(cancelled.pipeline.points(), twin.pipeline.points());
}

TEST(PipelineProgress, ACancelledRunAfterALatticeWasAddedKeepsTheLastOutput) {
  // The last complete output lives in the first stage; the new last stage is cancelled.
  const Eigen::Index n = kEmbedProgressChunk + 5000;
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(n, 24);
  Pipeline pipeline(Q);
  const LatticeId root = pipeline.addLattice(boxAt({-0.1, -0.1, -0.1}, 1.2, 4));
  bend(pipeline.lattice(root), 0.1);
  const Eigen::MatrixX3d before = pipeline.update();
  shift(pipeline.lattice(root), 0.02);  // the root re-embeds (its deformer is replaced) ...
  const LatticeId child = pipeline.addLattice(boxAt({0.2, 0.2, 0.2}, 0.6, 3), root);
  Calls calls;
  EXPECT_THROW(pipeline.update(cancelAt(n + 1, calls)), Cancelled);  // ... then the child is cancelled
  EXPECT_EQ(pipeline.points(), before);
  Pipeline moved = std::move(pipeline);
  EXPECT_EQ(moved.points(), before) << "a moved pipeline keeps its output";
  moved.update();
  EXPECT_EQ(moved.points(), sequential({&moved.lattice(root), &moved.lattice(child)}, Q));
}

TEST(PipelineProgress, ACancelAtTheLastCallRedoesOnlyTheLastEmbedding) {
  const Eigen::MatrixX3d Q = testing::uniformPointsInUnitBox(1000, 25);
  Chain c = makeChain(Q);
  const EmbedProgress refuseTheEnd = [](Eigen::Index done, Eigen::Index total) { return total == 0 || done < total; };
  EXPECT_THROW(c.pipeline.update(refuseTheEnd), Cancelled);
  // The last stage's own embedding was refused at its end: it is redone by the next run.
  EXPECT_EQ(c.pipeline.pointsToEmbed(), 1000);
  c.pipeline.update();
  EXPECT_EQ(c.pipeline.points(), makeChain(Q).pipeline.update());
}

}  // namespace
}  // namespace ffdkit::ffd
