// Tests that a drag's steps of one control point, which read the weights the deformer kept at the
// step before (DeformStats::weightsReused), give the bits the basis gives, and stay with the full
// evaluation.
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "ffdkit/ffd/control_weights.h"
#include "ffdkit/ffd/deformer.h"
#include "test_lattices.h"

namespace ffdkit::ffd {
namespace {

// An 8x8x8 cubic B-spline lattice (5 cells per axis) on the unit box under a random frame,
// Falloff outside, and points at parameters in the first four cells of each axis (none in the
// last, where the far corner's control point acts alone), a tenth of them just outside the lower
// faces (blended).
struct DragCase {
  Lattice lattice;
  Eigen::MatrixX3d Q;
};

DragCase dragCase(std::mt19937& rng) {
  BoxLatticeOptions options;
  options.counts = {8, 8, 8};
  options.bases = {AxisBasis::bspline(3), AxisBasis::bspline(3), AxisBasis::bspline(3)};
  options.frame = testing::randomFrame(rng);
  options.outsidePolicy = OutsidePolicy::falloff(0.3);
  DragCase c{makeBoxLattice(options), Eigen::MatrixX3d()};
  const Eigen::Index n = 40000;
  const Eigen::Vector3d lo = c.lattice.parameterMin(), hi = c.lattice.parameterMax();
  std::uniform_real_distribution<double> inside(0.0, 0.8), below(0.0, 0.08);
  c.Q.resize(n, 3);
  for (Eigen::Index r = 0; r < n; ++r) {
    Eigen::Vector3d t(inside(rng), inside(rng), inside(rng));
    // Every tenth point: on a lower face of the (unit, lattice-local) box, then pushed off it.
    const int face = int(r / 10 % 3);
    if (r % 10 == 0) t[face] = 0.0;
    Eigen::Vector3d local = c.lattice.evaluateRest(lo + t.cwiseProduct(hi - lo));
    if (r % 10 == 0) local[face] -= below(rng);
    c.Q.row(r) = (c.lattice.frame() * local).transpose();
  }
  return c;
}

TEST(DeformerStepWeights, ADragOfOneControlPointReadsItsKeptWeightsAndGivesTheBitsOfTheBasis) {
  std::mt19937 rng(39);
  DragCase c = dragCase(rng);
  Deformer dragged(embed(c.lattice, c.Q));
  // The same steps with the far corner's control point moved too: two control points, so the
  // basis is evaluated at every step; that corner's cells hold no point, so the output is the
  // one the moved control point gives alone.
  Deformer twoMoved(embed(c.lattice, c.Q));
  ASSERT_GT(dragged.embedding().outsideCount(), 1000);
  dragged.deform(c.lattice, c.Q);
  twoMoved.deform(c.lattice, c.Q);
  Lattice withCorner = c.lattice;
  const Eigen::Index corner = c.lattice.index(7, 7, 7);
  std::uniform_real_distribution<double> U(-0.05, 0.05);
  Eigen::Index evaluated = 0;
  // Two drags: of an inner control point, then of one on the lower faces (its blended points).
  for (const Eigen::Index moved : {c.lattice.index(2, 2, 3), c.lattice.index(0, 1, 2)}) {
    for (int step = 1; step <= 12; ++step) {
      const Eigen::Vector3d move(U(rng), U(rng), U(rng));
      c.lattice.setControlPoint(moved, c.lattice.controlPoints().row(moved).transpose() + move);
      withCorner.setControlPoint(moved, c.lattice.controlPoints().row(moved).transpose());
      withCorner.setControlPoint(corner, withCorner.controlPoints().row(corner).transpose() + move);
      const Eigen::MatrixX3d& out = dragged.update(c.lattice);
      EXPECT_EQ(dragged.lastStats().changedControlPoints, 1);
      EXPECT_EQ(dragged.lastStats().weightsReused, step > 1) << "step " << step;
      twoMoved.update(withCorner);
      EXPECT_EQ(twoMoved.lastStats().changedControlPoints, 2);
      EXPECT_FALSE(twoMoved.lastStats().weightsReused);
      EXPECT_EQ(dragged.lastStats().evaluatedPoints, twoMoved.lastStats().evaluatedPoints);
      evaluated = dragged.lastStats().evaluatedPoints;
      ASSERT_TRUE((out.array() == twoMoved.points().array()).all()) << "control point " << moved << " step " << step;
    }
    EXPECT_GT(evaluated, 2000);
    EXPECT_LT(evaluated, c.Q.rows());
    // And both stay with a full evaluation of the lattice (the corner moved nothing).
    Deformer full(embed(c.lattice, c.Q));
    const Eigen::MatrixX3d reference = full.deform(c.lattice, c.Q);
    EXPECT_LT((dragged.points() - reference).cwiseAbs().maxCoeff(), 1e-13 * (1.0 + reference.cwiseAbs().maxCoeff()));
  }
}

TEST(DeformerStepWeights, KeptWeightsSurviveAnExactEvaluationAndServeTheNextDragOfTheSamePoint) {
  // A release evaluates exactly (deform) with the same embedding: the weights of the control
  // point stay valid, and the next drag of it reads them from its first step; a drag of another
  // control point keeps its own.
  std::mt19937 rng(40);
  DragCase c = dragCase(rng);
  Deformer deformer(embed(c.lattice, c.Q));
  deformer.deform(c.lattice, c.Q);
  const Eigen::Index a = c.lattice.index(2, 2, 2), b = c.lattice.index(3, 1, 2);
  const auto step = [&](Eigen::Index f, double by) {
    c.lattice.setControlPoint(f, c.lattice.controlPoints().row(f).transpose() + Eigen::Vector3d(by, -by, 0.5 * by));
    deformer.update(c.lattice);
    return deformer.lastStats().weightsReused;
  };
  EXPECT_FALSE(step(a, 0.01));
  EXPECT_TRUE(step(a, 0.02));
  deformer.deform(c.lattice, c.Q);  // the release
  EXPECT_TRUE(step(a, 0.01));
  EXPECT_FALSE(step(b, 0.01));
  EXPECT_TRUE(step(b, 0.01));
  EXPECT_FALSE(step(a, 0.01));
  Deformer full(embed(c.lattice, c.Q));
  const Eigen::MatrixX3d reference = full.deform(c.lattice, c.Q);
  EXPECT_LT((deformer.points() - reference).cwiseAbs().maxCoeff(), 1e-13 * (1.0 + reference.cwiseAbs().maxCoeff()));
}

TEST(DeformerStepWeights, TheKeptWeightsAreTheControlPointsWeightsAtEveryPoint) {
  // What a drag's first step kept, in original point order with the blend weights applied, is
  // controlPointWeights evaluated independently (a scalar loop over the basis polynomials): equal
  // to the rounding of fused multiply-adds (a weight 0 on a knot plane may come out as 1e-19),
  // and exactly 0 outside the control point's support.
  std::mt19937 rng(41);
  DragCase c = dragCase(rng);
  Deformer deformer(embed(c.lattice, c.Q));
  deformer.deform(c.lattice, c.Q);
  Eigen::VectorXd kept;
  Eigen::Index blended = 0;
  for (const Eigen::Index moved : {c.lattice.index(2, 2, 3), c.lattice.index(0, 1, 2)}) {
    EXPECT_FALSE(deformer.keptControlWeights(c.lattice, moved, kept)) << "before a step of " << moved;
    c.lattice.setControlPoint(moved, c.lattice.controlPoints().row(moved).transpose() + Eigen::Vector3d(0.02, -0.01, 0.03));
    deformer.update(c.lattice);
    ASSERT_TRUE(deformer.keptControlWeights(c.lattice, moved, kept)) << moved;
    const Eigen::VectorXd reference = controlPointWeights(c.lattice, deformer.embedding(), moved);
    ASSERT_EQ(kept.size(), reference.size());
    Eigen::Index zeros = 0;
    for (Eigen::Index p = 0; p < kept.size(); ++p) {
      zeros += kept[p] == 0.0 && reference[p] == 0.0;
      blended += reference[p] != 0.0 && p % 10 == 0;  // dragCase pushes every tenth point outside
    }
    EXPECT_LT((kept - reference).cwiseAbs().maxCoeff(), 1e-15) << moved;
    EXPECT_GT(zeros, 1000) << moved;  // points outside the support
    EXPECT_FALSE(deformer.keptControlWeights(c.lattice, c.lattice.index(3, 3, 3), kept)) << "another control point";
  }
  EXPECT_GT(blended, 100);  // the second control point's: outside the box, blended
}

}  // namespace
}  // namespace ffdkit::ffd
