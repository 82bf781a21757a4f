#include "ffdkit/ffd/deformer.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "ffdkit/ffd/cylindrical_lattice.h"
#include "reference_ffd.h"
#include "test_lattices.h"

namespace ffdkit::ffd {
namespace {

reference::Axis referenceAxis(const AxisSpline& axis) {
  reference::Axis r;
  r.count = axis.count();
  r.degree = axis.degree();
  switch (axis.basis().kind) {
    case AxisBasis::Kind::Bernstein:
      r.kind = reference::Axis::Kind::Bernstein;
      break;
    case AxisBasis::Kind::BSpline:
      r.kind = reference::Axis::Kind::BSpline;
      r.knots = axis.basis().knots.size() ? std::vector<double>(axis.basis().knots.data(), axis.basis().knots.data() + axis.basis().knots.size())
                                          : reference::clampedUniform(axis.count(), axis.degree());
      break;
    case AxisBasis::Kind::PeriodicBSpline:
      r.kind = reference::Axis::Kind::Periodic;
      r.knots = reference::periodicUniform(axis.count(), axis.degree());
      break;
  }
  return r;
}

Eigen::MatrixX3d randomMove(const Lattice& lattice, double amount, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-amount, amount);
  Eigen::MatrixX3d P = lattice.controlPoints();
  for (Eigen::Index r = 0; r < P.rows(); ++r)
    for (int c = 0; c < 3; ++c) P(r, c) += U(rng);
  return P;
}

// count^3 control points, B-splines of `degree` on every axis, a random frame.
Lattice cubeOfBSplines(int count, int degree, std::mt19937& rng) {
  BoxLatticeOptions options;
  options.counts = {count, count, count};
  options.bases = {AxisBasis::bspline(degree), AxisBasis::bspline(degree), AxisBasis::bspline(degree)};
  options.frame = testing::randomFrame(rng);
  return makeBoxLattice(options);
}

double maxRowError(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  return (a - b).rowwise().norm().maxCoeff();
}

TEST(Deformer, RestLatticeReproducesEveryPointThroughEquation61) {
  std::mt19937 rng(1);
  std::vector<Lattice> lattices;
  for (int t = 0; t < 10; ++t) lattices.push_back(testing::randomLattice(rng, t % 2 ? 0.2 : 0.0));
  lattices.push_back(makeCylindricalLattice());
  for (const Lattice& lattice : lattices) {
    const Eigen::MatrixX3d Q = testing::restImages(lattice, testing::randomParameters(lattice, 200, rng));
    Deformer deformer(embed(lattice, Q));
    const Eigen::MatrixX3d out = deformer.deform(lattice, Q);
    // X(embed(Q)) with X evaluated from scratch by eq. (6.1) on the (unmoved) control points.
    const Eigen::MatrixX3d uvw = deformer.embedding().parameters();
    const double size = lattice.restSize() * lattice.frame().linear().norm();
    for (Eigen::Index r = 0; r < Q.rows(); ++r) {
      const Eigen::Vector3d x = lattice.frame() * lattice.evaluate(uvw.row(r).transpose());
      EXPECT_LT((x - Q.row(r).transpose()).norm(), 1e-12 * size);
    }
    EXPECT_LT(maxRowError(out, Q), 1e-12 * size);
  }
}

TEST(Deformer, AffineChangeOfAllControlPointsMovesEveryPointByTheSameMap) {
  std::mt19937 rng(2);
  for (int t = 0; t < 10; ++t) {
    Lattice lattice = t == 9 ? makeCylindricalLattice() : testing::randomLattice(rng, t % 2 ? 0.2 : 0.0);
    const Eigen::MatrixX3d Q = testing::restImages(lattice, testing::randomParameters(lattice, 200, rng));
    Deformer deformer(embed(lattice, Q));
    Eigen::Affine3d T = testing::randomFrame(rng);  // in lattice-local coordinates
    lattice.setControlPoints((lattice.restPoints() * T.linear().transpose()).rowwise() + T.translation().transpose());
    const Eigen::MatrixX3d out = deformer.deform(lattice, Q);
    const Eigen::Affine3d world = lattice.frame() * T * lattice.frame().inverse();
    const Eigen::MatrixX3d expected = (Q * world.linear().transpose()).rowwise() + world.translation().transpose();
    EXPECT_LT(maxRowError(out, expected), 1e-12 * (1.0 + expected.cwiseAbs().maxCoeff())) << "trial " << t;
  }
}

TEST(Deformer, MatchesReferenceEvaluatorOnRandomLattices) {
  std::mt19937 rng(3);
  for (int t = 0; t < 20; ++t) {
    Lattice lattice = t == 19 ? makeCylindricalLattice() : testing::randomLattice(rng, t % 2 ? 0.2 : 0.0, 7);
    const Eigen::MatrixX3d Q = testing::restImages(lattice, testing::randomParameters(lattice, 100, rng));
    Deformer deformer(embed(lattice, Q));
    lattice.setControlPoints(randomMove(lattice, 0.3, rng));
    const Eigen::MatrixX3d out = deformer.deform(lattice, Q);
    const reference::Axis axes[3] = {referenceAxis(lattice.axis(0)), referenceAxis(lattice.axis(1)),
                                     referenceAxis(lattice.axis(2))};
    const Eigen::MatrixX3d uvw = deformer.embedding().parameters();
    for (Eigen::Index r = 0; r < Q.rows(); ++r) {
      const Eigen::Vector3d expected = lattice.frame() * reference::evaluate(axes, lattice.controlPoints(), uvw.row(r).transpose());
      EXPECT_LT((out.row(r).transpose() - expected).norm(), 1e-12 * (1.0 + expected.norm())) << "trial " << t;
    }
  }
}

// Parameters for the reference comparison: random ones plus every distinct knot inside the
// domain (repeated knots, domain ends) on each axis, where span selection is easiest to get wrong.
Eigen::MatrixX3d parametersWithKnots(const Lattice& lattice, Eigen::Index n, std::mt19937& rng) {
  Eigen::MatrixX3d uvw = testing::randomParameters(lattice, n, rng);
  std::uniform_int_distribution<Eigen::Index> pick(0, n - 1);
  for (int a = 0; a < 3; ++a) {
    const AxisSpline& axis = lattice.axis(a);
    for (double t : axis.knots()) {
      if (t < axis.domainMin() || t > axis.domainMax() || (axis.periodic() && t >= axis.domainMax())) continue;
      uvw(pick(rng), a) = t;
    }
  }
  return uvw;
}

// Item 5 of issue 18: the deformer against the reference evaluator on repeated interior knots,
// unclamped knots, counts >= 8 and periodic axes, at the parameters the points were made from.
TEST(Deformer, MatchesReferenceOnRepeatedUnclampedLargeAndPeriodicBases) {
  std::mt19937 rng(18);
  const auto knots = [](const std::vector<double>& t) { return Eigen::VectorXd::Map(t.data(), static_cast<Eigen::Index>(t.size())); };
  struct Case {
    const char* name;
    Lattice lattice;
  };
  std::vector<Case> cases;
  const auto box = [&](const Eigen::Vector3i& counts, const std::array<AxisBasis, 3>& bases) {
    BoxLatticeOptions o;
    o.counts = counts;
    o.bases = bases;
    o.capDegreeToCount = false;
    o.boxMin = Eigen::Vector3d(-1.0, 0.0, 0.5);
    o.boxMax = Eigen::Vector3d(1.0, 0.7, 2.0);
    o.frame = testing::randomFrame(rng);
    return makeBoxLattice(o);
  };
  cases.push_back({"repeated knots, multiplicity 1 / 2 / 3 (C0) at 1/3 and 2/3",
                   box({6, 8, 10}, {AxisBasis::bsplineWithKnots(3, knots(reference::repeatedInterior(3, 1))),
                                    AxisBasis::bsplineWithKnots(3, knots(reference::repeatedInterior(3, 2))),
                                    AxisBasis::bsplineWithKnots(3, knots(reference::repeatedInterior(3, 3)))})});
  cases.push_back({"repeated knots, quadratic and linear",
                   box({7, 5, 4}, {AxisBasis::bsplineWithKnots(2, knots(reference::repeatedInterior(2, 2))),
                                   AxisBasis::bsplineWithKnots(2, knots(reference::repeatedInterior(2, 1))),
                                   AxisBasis::bsplineWithKnots(1, knots(reference::repeatedInterior(1, 1)))})});
  cases.push_back({"unclamped non-uniform knots",
                   box({5, 9, 4}, {AxisBasis::bsplineWithKnots(2, knots(reference::randomUnclamped(5, 2, rng))),
                                   AxisBasis::bsplineWithKnots(3, knots(reference::randomUnclamped(9, 3, rng))),
                                   AxisBasis::bsplineWithKnots(1, knots(reference::randomUnclamped(4, 1, rng)))})});
  cases.push_back({"counts 8 to 12", box({8, 12, 9}, {AxisBasis::bernstein(), AxisBasis::bspline(5),
                                                      AxisBasis::bsplineWithKnots(4, knots(reference::randomClamped(9, 4, rng)))})});
  for (int degree : {1, 2, 3, 4}) {
    CylindricalLatticeOptions o;
    o.counts = {3, degree == 2 ? 13 : 8, 4};
    o.bases = {AxisBasis::bspline(2), AxisBasis::periodic(degree), AxisBasis::bernstein()};
    o.innerRadius = 0.3;  // off the axis, where the angle parameter is unique
    o.frame = testing::randomFrame(rng);
    cases.push_back({"periodic angle", makeCylindricalLattice(o)});
  }
  for (Case& c : cases) {
    Lattice& lattice = c.lattice;
    const Eigen::MatrixX3d uvw = parametersWithKnots(lattice, 300, rng);
    const Eigen::MatrixX3d Q = testing::restImages(lattice, uvw);
    Deformer deformer(embed(lattice, Q));
    ASSERT_EQ(deformer.embedding().insideCount(), Q.rows()) << c.name;
    lattice.setControlPoints(randomMove(lattice, 0.3, rng));
    const Eigen::MatrixX3d out = deformer.deform(lattice, Q);
    const reference::Axis axes[3] = {referenceAxis(lattice.axis(0)), referenceAxis(lattice.axis(1)),
                                     referenceAxis(lattice.axis(2))};
    double worst = 0.0;
    for (Eigen::Index r = 0; r < Q.rows(); ++r) {
      const Eigen::Vector3d expected = lattice.frame() * reference::evaluate(axes, lattice.controlPoints(), uvw.row(r).transpose());
      worst = std::max(worst, (out.row(r).transpose() - expected).norm() / (1.0 + expected.norm()));
      // The rest lattice too: it reproduces the point the parameters were made from.
      const Eigen::Vector3d restExpected = lattice.frame() * reference::evaluate(axes, lattice.restPoints(), uvw.row(r).transpose());
      EXPECT_LT((Q.row(r).transpose() - restExpected).norm(), 1e-12 * (1.0 + restExpected.norm())) << c.name << " point " << r;
    }
    EXPECT_LT(worst, 1e-10) << c.name;
  }
}

TEST(Deformer, IncrementalUpdateEqualsFullEvaluation) {
  std::mt19937 rng(4);
  for (int t = 0; t < 12; ++t) {
    Lattice lattice = t == 11 ? makeCylindricalLattice() : testing::randomLattice(rng, t % 3 == 0 ? 0.2 : 0.0, 9);
    const Eigen::MatrixX3d Q = testing::restImages(lattice, testing::randomParameters(lattice, 3000, rng));
    Deformer incremental(embed(lattice, Q));
    Deformer exact(embed(lattice, Q));
    Deformer full(embed(lattice, Q));
    incremental.deform(lattice, Q);
    exact.deform(lattice, Q);
    for (int step = 0; step < 6; ++step) {
      Eigen::MatrixX3d P = lattice.controlPoints();
      std::uniform_int_distribution<Eigen::Index> pick(0, P.rows() - 1);
      // 1 point, a few points, then every point.
      const int moves = step < 2 ? 1 : step < 5 ? 4 : static_cast<int>(P.rows());
      for (int m = 0; m < moves; ++m) {
        const Eigen::Index f = step == 5 ? m : pick(rng);
        P.row(f) += Eigen::RowVector3d::Random() * 0.2;
      }
      lattice.setControlPoints(P);
      const Eigen::MatrixX3d inc = incremental.update(lattice);
      EXPECT_FALSE(incremental.lastStats().full);
      EXPECT_GT(incremental.lastStats().changedControlPoints, 0);
      const Eigen::MatrixX3d ref = full.deform(lattice, Q);
      const double scale = 1.0 + ref.cwiseAbs().maxCoeff();
      EXPECT_LT(maxRowError(inc, ref), 1e-12 * scale) << "trial " << t << " step " << step;
      // The exact variant re-evaluates the touched cells with the full-evaluation code: bit-identical.
      EXPECT_EQ(maxRowError(exact.update(lattice, Q), ref), 0.0) << "trial " << t << " step " << step;
    }
  }
}

TEST(Deformer, IncrementalUpdateTouchesOnlyInfluencedPoints) {
  BoxLatticeOptions options;
  options.counts = {8, 8, 8};
  Lattice lattice = makeBoxLattice(options);
  std::mt19937 rng(5);
  const Eigen::MatrixX3d Q = testing::restImages(lattice, testing::randomParameters(lattice, 20000, rng));
  Deformer deformer(embed(lattice, Q));
  deformer.deform(lattice, Q);
  Deformer exact(embed(lattice, Q));
  exact.deform(lattice, Q);
  lattice.setControlPoint(lattice.index(0, 0, 0), Eigen::Vector3d(-0.1, -0.1, -0.1));
  deformer.update(lattice);
  exact.update(lattice, Q);
  // The corner point's support is the first of 5 cells per axis: about 1/125 of the points.
  for (const Deformer* d : {&deformer, &exact}) {
    EXPECT_GT(d->lastStats().evaluatedPoints, 0);
    EXPECT_LT(d->lastStats().evaluatedPoints, 20000 / 50);
  }
  deformer.update(lattice);
  EXPECT_EQ(deformer.lastStats().changedControlPoints, 0);
  EXPECT_EQ(deformer.lastStats().evaluatedPoints, 0);
}

// The shape of the benchmark's exact update (docs/benchmarks.md): an interior control point of an
// 8x8x8 cubic lattice, points in random order over many tiles, so that the cells the update runs
// are short blocks separated by the cells it skips in every tile.
TEST(Deformer, ExactUpdateOfAnInteriorControlPointRunsItsSupportAcrossManyTiles) {
  BoxLatticeOptions options;
  options.counts = {8, 8, 8};
  Lattice lattice = makeBoxLattice(options);
  std::mt19937 rng(12);
  const Eigen::MatrixX3d uvw = testing::randomParameters(lattice, 60000, rng);
  const Eigen::MatrixX3d Q = testing::restImages(lattice, uvw);
  Deformer exact(embed(lattice, Q));
  exact.deform(lattice, Q);
  // Control index 3 lies in the windows of cells 0..3 of the 5 per axis (cubic: cell c holds c..c+3).
  Eigen::Index support = 0;
  for (Eigen::Index r = 0; r < uvw.rows(); ++r) {
    support += (uvw.row(r).array() * 5.0 < 4.0).all() ? 1 : 0;
  }
  const Eigen::Index flat = lattice.index(3, 3, 3);
  for (int step = 1; step <= 3; ++step) {
    lattice.setControlPoint(flat, lattice.restPoints().row(flat).transpose() + Eigen::Vector3d(0.05, -0.03, 0.02) * step);
    exact.update(lattice, Q);
    // Points on a cell boundary may be sorted into either cell: a few either way.
    EXPECT_NEAR(double(exact.lastStats().evaluatedPoints), double(support), 10.0) << "step " << step;
    Deformer full(embed(lattice, Q));
    EXPECT_EQ(maxRowError(exact.points(), full.deform(lattice, Q)), 0.0) << "step " << step;
  }
}

TEST(Deformer, ExactUpdatesDoNotDriftOverManySteps) {
  BoxLatticeOptions options;
  options.counts = {6, 6, 6};
  Lattice lattice = makeBoxLattice(options);
  std::mt19937 rng(8);
  const Eigen::MatrixX3d Q = testing::restImages(lattice, testing::randomParameters(lattice, 2000, rng));
  Deformer exact(embed(lattice, Q));
  exact.deform(lattice, Q);
  const Eigen::Index flat = lattice.index(2, 3, 1);
  for (int step = 1; step <= 3000; ++step) {
    lattice.setControlPoint(flat, lattice.restPoints().row(flat).transpose() + Eigen::Vector3d(1e-3, -2e-3, 1e-3) * step);
    exact.update(lattice, Q);
  }
  Deformer full(embed(lattice, Q));
  EXPECT_EQ(maxRowError(exact.points(), full.deform(lattice, Q)), 0.0);
}

TEST(Deformer, RequiresDeformBeforeUpdateAndAFreshEmbedding) {
  Lattice lattice = makeBoxLattice();
  const Eigen::MatrixX3d Q = Eigen::MatrixX3d::Constant(5, 3, 0.5);
  Deformer deformer(embed(lattice, Q));
  EXPECT_THROW(deformer.update(lattice), LatticeError);
  EXPECT_THROW(deformer.update(lattice, Q), LatticeError);
  EXPECT_THROW(deformer.deform(lattice, Eigen::MatrixX3d::Zero(4, 3)), LatticeError);
  deformer.deform(lattice, Q);
  EXPECT_THROW(deformer.update(lattice, Eigen::MatrixX3d::Zero(4, 3)), LatticeError);
  Eigen::Affine3d moved = Eigen::Affine3d::Identity();
  moved.translate(Eigen::Vector3d(1, 0, 0));
  lattice.setFrame(moved);
  EXPECT_THROW(deformer.deform(lattice, Q), LatticeError);
  EXPECT_THROW(deformer.update(lattice), LatticeError);
}

TEST(Deformer, ParallelAndSerialRunsAgree) {
  std::mt19937 rng(6);
  BoxLatticeOptions options;
  options.counts = {6, 5, 7};
  Lattice lattice = makeBoxLattice(options);
  const Eigen::MatrixX3d Q = testing::restImages(lattice, testing::randomParameters(lattice, 50000, rng));
  Deformer parallel(embed(lattice, Q));
  Deformer serial(embed(lattice, Q, EmbedOptions{.parallel = false}));
  serial.setParallel(false);
  lattice.setControlPoints(randomMove(lattice, 0.2, rng));
  EXPECT_EQ(maxRowError(parallel.deform(lattice, Q), serial.deform(lattice, Q)), 0.0);
}

TEST(Deformer, ManyPointsAndManyCellsMatchLatticeEvaluate) {
  std::mt19937 rng(7);
  // 64 cells; 24389 and 9261 cells (sorted by std::sort; more cells than the deformer keeps
  // per-cell coefficients for at once).
  for (auto [count, degree] : {std::pair{7, 3}, std::pair{30, 1}, std::pair{24, 3}}) {
    Lattice lattice = cubeOfBSplines(count, degree, rng);
    const Eigen::MatrixX3d Q = testing::restImages(lattice, testing::randomParameters(lattice, 40000, rng));
    Deformer deformer(embed(lattice, Q));
    EXPECT_FALSE(deformer.embedding().order().empty());
    lattice.setControlPoints(randomMove(lattice, 0.05, rng));
    const Eigen::MatrixX3d out = deformer.deform(lattice, Q);
    const Eigen::MatrixX3d uvw = deformer.embedding().parameters();
    for (Eigen::Index r = 0; r < Q.rows(); r += 7) {
      const Eigen::Vector3d expected = lattice.frame() * lattice.evaluate(uvw.row(r).transpose());
      ASSERT_LT((out.row(r).transpose() - expected).norm(), 1e-12 * (1.0 + expected.norm())) << r;
    }
    lattice.setControlPoint(lattice.index(count / 2, count / 2, count / 2), Eigen::Vector3d(0.5, 0.5, 0.5));
    const Eigen::MatrixX3d inc = deformer.update(lattice);
    Deformer full(embed(lattice, Q));
    EXPECT_LT(maxRowError(inc, full.deform(lattice, Q)), 1e-12 * (1.0 + Q.cwiseAbs().maxCoeff()));
  }
}

TEST(Deformer, HandlesAnEmptyPointSet) {
  Lattice lattice = makeBoxLattice();
  const Eigen::MatrixX3d none(0, 3);
  Deformer deformer(embed(lattice, none));
  EXPECT_EQ(deformer.deform(lattice, none).rows(), 0);
  lattice.setControlPoint(0, Eigen::Vector3d(-1, -1, -1));
  EXPECT_EQ(deformer.update(lattice).rows(), 0);
}

// --- outside policies ---------------------------------------------------------------

struct OutsideCase {
  Lattice lattice;
  Eigen::MatrixX3d Q;
};

OutsideCase outsideCase(OutsidePolicy policy, AxisBasis basis) {
  BoxLatticeOptions options;
  options.counts = {4, 4, 4};
  options.bases = {basis, basis, basis};
  options.outsidePolicy = policy;
  OutsideCase c{makeBoxLattice(options), Eigen::MatrixX3d(4, 3)};
  c.Q << 0.5, 0.5, 0.5,  // inside
      1.2, 0.5, 0.5,     // 0.2 beyond the +x face
      0.5, -0.05, 0.5,   // 0.05 beyond the -y face
      3.0, 3.0, 3.0;     // far away
  Eigen::MatrixX3d P = c.lattice.restPoints();
  P.col(1).array() += 0.1 * P.col(0).array().square();  // a bend that moves the +x face by 0.1 in y
  c.lattice.setControlPoints(P);
  return c;
}

// The ClampEdge image: X(clamp(uvw)) + (Q - Xbar(clamp(uvw))), evaluated through Lattice::evaluate.
Eigen::Vector3d clampEdgeImage(const Lattice& lattice, const Eigen::Vector3d& q) {
  const Eigen::Vector3d uc = q.cwiseMax(0.0).cwiseMin(1.0);  // unit box, identity frame
  return lattice.evaluate(uc) + (q - lattice.evaluateRest(uc));
}

TEST(Deformer, IdentityPolicyLeavesOutsidePointsUnchanged) {
  OutsideCase c = outsideCase(OutsidePolicy::identity(), AxisBasis::bspline(3));
  Deformer deformer(embed(c.lattice, c.Q));
  const Eigen::MatrixX3d out = deformer.deform(c.lattice, c.Q);
  EXPECT_EQ(deformer.embedding().outsideCount(), 3);
  for (int r = 1; r < 4; ++r) EXPECT_EQ(out.row(r), c.Q.row(r));
  EXPECT_LT((out.row(0).transpose() - c.lattice.evaluate(Eigen::Vector3d(0.5, 0.5, 0.5))).norm(), 1e-12);
}

TEST(Deformer, ClampEdgeKeepsTheOffsetFromTheClampedSurfacePoint) {
  OutsideCase c = outsideCase(OutsidePolicy::clampEdge(), AxisBasis::bspline(3));
  Deformer deformer(embed(c.lattice, c.Q));
  const Eigen::MatrixX3d out = deformer.deform(c.lattice, c.Q);
  for (int r = 0; r < 4; ++r) {
    EXPECT_LT((out.row(r).transpose() - clampEdgeImage(c.lattice, c.Q.row(r).transpose())).norm(), 1e-12) << r;
  }
  EXPECT_NEAR(out(1, 1), 0.5 + 0.1, 1e-12);  // follows the bent +x face
}

TEST(Deformer, ExtrapolateEvaluatesTheBernsteinPolynomialBeyondTheBox) {
  OutsideCase c = outsideCase(OutsidePolicy::extrapolate(), AxisBasis::bernstein());
  Deformer deformer(embed(c.lattice, c.Q));
  const Eigen::MatrixX3d out = deformer.deform(c.lattice, c.Q);
  for (int r = 0; r < 4; ++r) {
    const Eigen::Vector3d q = c.Q.row(r).transpose();
    const Eigen::Vector3d expected = c.lattice.evaluate(q);  // unit box: uvw == Q
    EXPECT_LT((out.row(r).transpose() - expected).norm(), 1e-12 * (1.0 + expected.norm())) << r;
  }
  // Control points (i/3)^2 give the cubic u^2 + u (1 - u) / 3, continued beyond u = 1.
  EXPECT_NEAR(out(1, 1), 0.5 + 0.1 * (1.2 * 1.2 + 1.2 * (1.0 - 1.2) / 3.0), 1e-12);
}

TEST(Deformer, FalloffBlendsFromClampEdgeToIdentity) {
  OutsideCase c = outsideCase(OutsidePolicy::falloff(0.4), AxisBasis::bspline(3));
  Deformer deformer(embed(c.lattice, c.Q));
  const Eigen::MatrixX3d out = deformer.deform(c.lattice, c.Q);
  // Far point: identity. Point 0.2 beyond +x: half way, smoothstep weight 0.5.
  EXPECT_EQ(out.row(3), c.Q.row(3));
  const Eigen::Vector3d clamp = clampEdgeImage(c.lattice, c.Q.row(1).transpose());
  const Eigen::Vector3d expected = c.Q.row(1).transpose() + 0.5 * (clamp - c.Q.row(1).transpose());
  EXPECT_LT((out.row(1).transpose() - expected).norm(), 1e-12);
  // Point 0.05 beyond -y: x = 0.125, weight 1 - x^2 (3 - 2x).
  const double x = 0.125;
  const double s = 1.0 - x * x * (3.0 - 2.0 * x);
  const Eigen::Vector3d clamp2 = clampEdgeImage(c.lattice, c.Q.row(2).transpose());
  EXPECT_LT((out.row(2).transpose() - (c.Q.row(2).transpose() + s * (clamp2 - c.Q.row(2).transpose()))).norm(), 1e-12);
  // Incremental updates respect the blend weights.
  Eigen::MatrixX3d P = c.lattice.controlPoints();
  P.row(c.lattice.index(3, 1, 1)) += Eigen::RowVector3d(0.0, 0.3, 0.1);
  c.lattice.setControlPoints(P);
  const Eigen::MatrixX3d inc = deformer.update(c.lattice);
  Deformer fresh(embed(c.lattice, c.Q));
  EXPECT_LT(maxRowError(inc, fresh.deform(c.lattice, c.Q)), 1e-12);
}

TEST(Deformer, ClampEdgeCarriesFarOutsidePointsOfUserShapedLatticesAlong) {
  // Points beyond the bounding box of a user-shaped lattice's rest points are outside for certain;
  // Newton on the polynomial extension often finds no preimage for them. ClampEdge must still keep
  // their offset from a surface point: translating every control point by t moves them by t
  // (affine invariance of the blend), where a point wrongly reported Failed would stay put.
  std::mt19937 rng(21);
  const Eigen::Vector3d t(0.3, -0.2, 0.1);
  for (int trial = 0; trial < 6; ++trial) {
    Lattice lattice = testing::randomLattice(rng, 0.2);
    lattice.setOutsidePolicy(OutsidePolicy::clampEdge());
    Eigen::MatrixX3d world(lattice.restPoints().rows(), 3);
    for (Eigen::Index r = 0; r < world.rows(); ++r)
      world.row(r) = (lattice.frame() * Eigen::Vector3d(lattice.restPoints().row(r).transpose())).transpose();
    const Eigen::Vector3d lo = world.colwise().minCoeff(), hi = world.colwise().maxCoeff();
    std::uniform_real_distribution<double> U(0.0, 1.0);
    Eigen::MatrixX3d Q(30, 3);
    for (Eigen::Index r = 0; r < Q.rows(); ++r) {
      Eigen::Vector3d x = lo + Eigen::Vector3d(U(rng), U(rng), U(rng)).cwiseProduct(hi - lo);
      const int axis = static_cast<int>(r % 3);
      x[axis] = r % 2 ? hi[axis] + (0.05 + 0.5 * U(rng)) * (hi - lo)[axis] : lo[axis] - (0.05 + 0.5 * U(rng)) * (hi - lo)[axis];
      Q.row(r) = x.transpose();
    }
    Deformer deformer(embed(lattice, Q));
    EXPECT_EQ(deformer.embedding().outsideCount(), Q.rows()) << "trial " << trial;
    const Eigen::Vector3d tLocal = lattice.frame().linear().inverse() * t;
    lattice.setControlPoints(lattice.restPoints().rowwise() + tLocal.transpose());
    const Eigen::MatrixX3d out = deformer.deform(lattice, Q);
    EXPECT_LT(maxRowError(out, Q.rowwise() + t.transpose()), 1e-12) << "trial " << trial;
  }
}

// Precision::Single: the displacement in float32. Its error is float rounding (2^-24 = 6e-8)
// of the cell's power-form coefficients, of the local parameters and of Horner's steps, so it
// scales with the displacement, not with the coordinates; held to 1e-6 of the largest
// control-point displacement (the worst measured on these lattices is printed: 1.2e-7 of it).
double largestDisplacement(const Lattice& lattice) {
  return ((lattice.controlPoints() - lattice.restPoints()) * lattice.frame().linear().transpose())
      .rowwise()
      .norm()
      .maxCoeff();
}

bool powerForm(const Lattice& lattice) {
  return lattice.axis(0).degree() <= 3 && lattice.axis(1).degree() <= 3 && lattice.axis(2).degree() <= 3;
}

TEST(DeformerPrecision, SingleStaysWithinFloatRoundingOfTheDisplacementOfTheReferenceEvaluator) {
  std::mt19937 rng(31);
  double worst = 0.0;
  int powerLattices = 0;
  for (int t = 0; t < 30; ++t) {
    Lattice lattice = testing::randomLattice(rng, t % 2 ? 0.2 : 0.0, 7);
    const Eigen::MatrixX3d Q = testing::restImages(lattice, testing::randomParameters(lattice, 1000, rng));
    Deformer single(embed(lattice, Q));
    single.setPrecision(Precision::Single);
    Deformer twice(embed(lattice, Q));
    lattice.setControlPoints(randomMove(lattice, 0.3, rng));
    const Eigen::MatrixX3d out = single.deform(lattice, Q);
    const Eigen::MatrixX3d ref = twice.deform(lattice, Q);
    const double D = largestDisplacement(lattice);
    const reference::Axis axes[3] = {referenceAxis(lattice.axis(0)), referenceAxis(lattice.axis(1)),
                                     referenceAxis(lattice.axis(2))};
    const Eigen::MatrixX3d uvw = single.embedding().parameters();
    for (Eigen::Index r = 0; r < Q.rows(); ++r) {
      const Eigen::Vector3d expected = lattice.frame() * reference::evaluate(axes, lattice.controlPoints(), uvw.row(r).transpose());
      const double error = (out.row(r).transpose() - expected).norm();
      ASSERT_LT(error, 1e-6 * D + 1e-12 * (1.0 + expected.norm())) << "trial " << t << " point " << r;
      worst = std::max(worst, error / D);
    }
    if (powerForm(lattice)) {
      ++powerLattices;
      EXPECT_GT(maxRowError(out, ref), 0.0) << "trial " << t << ": the single-precision kernel did not run";
    } else {
      EXPECT_EQ(maxRowError(out, ref), 0.0) << "trial " << t << ": degrees above 3 are evaluated in double";
    }
  }
  EXPECT_GE(powerLattices, 8);
  std::printf("single precision: worst error %.3g of the largest control-point displacement\n", worst);
}

TEST(DeformerPrecision, SingleExactUpdatesAreBitIdenticalToASingleDeformAndDeltasStayClose) {
  std::mt19937 rng(32);
  // One cell; 8 cells (blocks of ~500 points per tile: the float kernel, two passes per tile);
  // 125 cells (blocks of ~33 points per tile: the double kernel, see kSingleBlockPoints).
  for (auto [count, degree] : {std::pair{4, 3}, std::pair{5, 3}, std::pair{4, 2}, std::pair{8, 3}}) {
    Lattice lattice = cubeOfBSplines(count, degree, rng);
    // Enough points for the threaded two-pass tiles of a random point order.
    const Eigen::MatrixX3d Q = testing::restImages(lattice, testing::randomParameters(lattice, 50000, rng));
    Deformer exact(embed(lattice, Q)), delta(embed(lattice, Q)), full(embed(lattice, Q)), twice(embed(lattice, Q));
    for (Deformer* d : {&exact, &delta, &full}) d->setPrecision(Precision::Single);
    exact.deform(lattice, Q);
    delta.deform(lattice, Q);
    for (int step = 0; step < 4; ++step) {
      Eigen::MatrixX3d P = lattice.controlPoints();
      P.row(lattice.index(count / 2, count / 2 - step % 2, count / 2)) += Eigen::RowVector3d(0.05, -0.03, 0.02);
      lattice.setControlPoints(P);
      const Eigen::MatrixX3d ref = full.deform(lattice, Q);
      EXPECT_EQ(maxRowError(exact.update(lattice, Q), ref), 0.0) << count << " step " << step;
      const double fromDouble = maxRowError(ref, twice.deform(lattice, Q));
      if (count < 8) {
        EXPECT_GT(fromDouble, 0.0) << count << ": the float kernel did not run";
      } else {
        EXPECT_EQ(fromDouble, 0.0) << "short blocks keep the double kernel";
        EXPECT_LT(exact.lastStats().evaluatedPoints, Q.rows()) << count;  // the others: every cell
      }
      EXPECT_LT(maxRowError(delta.update(lattice), ref), 1e-6 * largestDisplacement(lattice)) << count << " step " << step;
    }
  }
}

TEST(DeformerPrecision, SingleBlendsOutsidePointsAsDoubleDoes) {
  for (OutsidePolicy policy : {OutsidePolicy::clampEdge(), OutsidePolicy::falloff(0.3)}) {
    OutsideCase c = outsideCase(policy, AxisBasis::bspline(3));
    Deformer single(embed(c.lattice, c.Q)), twice(embed(c.lattice, c.Q));
    single.setPrecision(Precision::Single);
    const double error = maxRowError(single.deform(c.lattice, c.Q), twice.deform(c.lattice, c.Q));
    EXPECT_LT(error, 1e-6 * largestDisplacement(c.lattice));
  }
}

}  // namespace
}  // namespace ffdkit::ffd
