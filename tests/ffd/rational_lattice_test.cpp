// Rational lattices (NURBS-based FFD, Lamousin & Waggenspack 1994): a weight per control point,
// X = sum B w P / sum B w. Checked against an independent evaluator of that formula in long
// double (Bernstein by the binomial formula, B-splines by the recursive Cox-de Boor definition),
// against the closed form of a quarter circle, and against the polynomial lattice bit for bit.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "ffdkit/ffd/control_weights.h"
#include "ffdkit/ffd/deformer.h"
#include "ffdkit/ffd/direct_manipulation.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/fold_check.h"
#include "ffdkit/ffd/lattice.h"
#include "ffdkit/ffd/pipeline.h"

namespace ffdkit::ffd {
namespace {

using Real = long double;

// ---- the reference: the rational formula, term by term, in long double -------------------------
struct RefAxis {
  bool bernstein = true;
  int count = 4;
  int degree = 3;
  std::vector<Real> knots;  // B-spline: clamped uniform on [0, 1]
};

Real referenceBinomial(int n, int k) {
  Real c = 1;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

Real coxDeBoor(const std::vector<Real>& t, int i, int p, Real u) {
  if (p == 0) {
    if (u == 1) return t[i] < t[i + 1] && t[i + 1] == 1 ? 1 : 0;
    return t[i] <= u && u < t[i + 1] ? 1 : 0;
  }
  Real value = 0;
  if (t[i + p] > t[i]) value += (u - t[i]) / (t[i + p] - t[i]) * coxDeBoor(t, i, p - 1, u);
  if (t[i + p + 1] > t[i + 1]) value += (t[i + p + 1] - u) / (t[i + p + 1] - t[i + 1]) * coxDeBoor(t, i + 1, p - 1, u);
  return value;
}

Real refBasis(const RefAxis& a, int i, Real u) {
  if (a.bernstein) return referenceBinomial(a.count - 1, i) * std::pow(u, Real(i)) * std::pow(1 - u, Real(a.count - 1 - i));
  return coxDeBoor(a.knots, i, a.degree, u);
}

RefAxis refBSpline(int count, int degree) {
  RefAxis a{false, count, degree, {}};
  for (int i = 0; i <= degree; ++i) a.knots.push_back(0);
  for (int i = 1; i < count - degree; ++i) a.knots.push_back(Real(i) / (count - degree));
  for (int i = 0; i <= degree; ++i) a.knots.push_back(1);
  return a;
}

// X(u,v,w) = sum B_ijk w_ijk P_ijk / sum B_ijk w_ijk over every control point.
Eigen::Vector3d refEvaluate(const RefAxis (&axes)[3], const Eigen::MatrixX3d& P, const Eigen::VectorXd& w,
                            const Eigen::Vector3d& uvw) {
  Real num[3] = {0, 0, 0}, den = 0;
  for (int k = 0; k < axes[2].count; ++k)
    for (int j = 0; j < axes[1].count; ++j)
      for (int i = 0; i < axes[0].count; ++i) {
        const Eigen::Index f = i + axes[0].count * (j + axes[1].count * k);
        const Real b = refBasis(axes[0], i, uvw[0]) * refBasis(axes[1], j, uvw[1]) * refBasis(axes[2], k, uvw[2]) * w[f];
        for (int c = 0; c < 3; ++c) num[c] += b * P(f, c);
        den += b;
      }
  return Eigen::Vector3d(double(num[0] / den), double(num[1] / den), double(num[2] / den));
}

// ---- lattices --------------------------------------------------------------------------------
Lattice boxLattice(const Eigen::Vector3i& counts, AxisBasis basis) {
  BoxLatticeOptions options;
  options.counts = counts;
  options.bases = {basis, basis, basis};
  return makeBoxLattice(options);
}

Eigen::MatrixX3d jiggled(const Eigen::MatrixX3d& P, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-amount, amount);
  Eigen::MatrixX3d Q = P;
  for (Eigen::Index r = 0; r < Q.rows(); ++r)
    for (int c = 0; c < 3; ++c) Q(r, c) += U(rng);
  return Q;
}

Eigen::VectorXd randomWeights(Eigen::Index n, double lo, double hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(lo, hi);
  Eigen::VectorXd w(n);
  for (Eigen::Index i = 0; i < n; ++i) w[i] = U(rng);
  return w;
}

Eigen::MatrixX3d randomPoints(Eigen::Index n, double lo, double hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(lo, hi);
  Eigen::MatrixX3d Q(n, 3);
  for (Eigen::Index r = 0; r < n; ++r) Q.row(r) << U(rng), U(rng), U(rng);
  return Q;
}

// ---- tests -----------------------------------------------------------------------------------

TEST(RationalLattice, UnitWeightsAreThePolynomialLatticeBitForBit) {
  for (AxisBasis basis : {AxisBasis::bspline(3), AxisBasis::bernstein(), AxisBasis::bspline(2)}) {
    Lattice plain = boxLattice({5, 4, 4}, basis);
    plain.setControlPoints(jiggled(plain.controlPoints(), 0.1, 1));
    Lattice weighted = plain;
    weighted.setWeights(randomWeights(plain.pointCount(), 0.5, 2.0, 2));
    EXPECT_TRUE(weighted.isRational());
    weighted.setWeights(Eigen::VectorXd::Ones(plain.pointCount()));  // back to 1: polynomial again
    EXPECT_FALSE(weighted.isRational());
    const Eigen::MatrixX3d Q = randomPoints(20000, -0.1, 1.1, 3);  // some points outside
    Deformer a(embed(plain, Q)), b(embed(weighted, Q));
    const Eigen::MatrixX3d pa = a.deform(plain, Q), pb = b.deform(weighted, Q);
    EXPECT_EQ(0, std::memcmp(pa.data(), pb.data(), sizeof(double) * pa.size()));
    const Eigen::Vector3d uvw(0.3, 0.7, 0.2);
    EXPECT_EQ(plain.evaluate(uvw), weighted.evaluate(uvw));
    EXPECT_EQ(plain.jacobian(uvw), weighted.jacobian(uvw));
  }
}

TEST(RationalLattice, EvaluationAgreesWithTheReferenceFormula) {
  struct Case {
    Eigen::Vector3i counts;
    AxisBasis basis;
    RefAxis ref[3];
  };
  const Case cases[] = {
      {{4, 3, 5}, AxisBasis::bernstein(), {{true, 4, 3, {}}, {true, 3, 2, {}}, {true, 5, 4, {}}}},
      {{6, 5, 4}, AxisBasis::bspline(3), {refBSpline(6, 3), refBSpline(5, 3), refBSpline(4, 3)}},
      {{5, 5, 5}, AxisBasis::bspline(2), {refBSpline(5, 2), refBSpline(5, 2), refBSpline(5, 2)}},
  };
  for (const Case& c : cases) {
    Lattice lattice = boxLattice(c.counts, c.basis);
    lattice.setControlPoints(jiggled(lattice.controlPoints(), 0.15, 4));
    const Eigen::VectorXd w = randomWeights(lattice.pointCount(), 0.2, 5.0, 5);
    lattice.setWeights(w);
    const Eigen::MatrixX3d uvw = randomPoints(200, 0.0, 1.0, 6);
    for (Eigen::Index r = 0; r < uvw.rows(); ++r) {
      const Eigen::Vector3d t = uvw.row(r).transpose();
      const Eigen::Vector3d expected = refEvaluate(c.ref, lattice.controlPoints(), w, t);
      EXPECT_LT((lattice.evaluate(t) - expected).norm(), 1e-14) << "at " << t.transpose();
      // The Jacobian against central differences of the reference (step 1e-5: error ~1e-10).
      Eigen::Matrix3d J;
      const Eigen::Matrix3d analytic = lattice.jacobian(t);
      for (int a = 0; a < 3; ++a) {
        Eigen::Vector3d lo = t, hi = t;
        const double h = 1e-5;
        lo[a] = std::max(0.0, t[a] - h);
        hi[a] = std::min(1.0, t[a] + h);
        J.col(a) = (refEvaluate(c.ref, lattice.controlPoints(), w, hi) - refEvaluate(c.ref, lattice.controlPoints(), w, lo)) /
                   (hi[a] - lo[a]);
      }
      EXPECT_LT((analytic - J).norm(), 1e-8 * (1.0 + J.norm())) << "at " << t.transpose();
    }
    // The deformer: out = F X(u,v,w) at the embedded parameters.
    const Eigen::MatrixX3d Q = randomPoints(30000, 0.0, 1.0, 7);
    Deformer deformer(embed(lattice, Q));
    const Eigen::MatrixX3d& out = deformer.deform(lattice, Q);
    const Eigen::MatrixX3d params = deformer.embedding().parameters();
    for (Eigen::Index r = 0; r < Q.rows(); r += 97) {
      const Eigen::Vector3d expected = refEvaluate(c.ref, lattice.controlPoints(), w, params.row(r).transpose());
      EXPECT_LT((out.row(r).transpose() - expected).norm(), 1e-14) << "point " << r;
    }
  }
}

// A quadratic Bernstein axis with control points (1, 0), (1, 1), (0, 1) and weights 1, 1/sqrt(2),
// 1 is the quarter circle of radius 1 exactly (the conic of Lamousin & Waggenspack 1994); the
// second axis, linear, scales it to radius 1 + v.
TEST(RationalLattice, AQuarterCircleWeightMapsASegmentOntoAQuarterCircle) {
  Lattice lattice = boxLattice({3, 2, 2}, AxisBasis::bernstein());
  Eigen::MatrixX3d P = lattice.controlPoints();
  Eigen::VectorXd w = Eigen::VectorXd::Ones(lattice.pointCount());
  const double corner[3][2] = {{1, 0}, {1, 1}, {0, 1}};
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) {
        const Eigen::Index f = lattice.index(i, j, k);
        P.row(f) << (1.0 + j) * corner[i][0], (1.0 + j) * corner[i][1], double(k);
        if (i == 1) w[f] = 1.0 / std::numbers::sqrt2;
      }
  lattice.setControlPoints(P);
  lattice.setWeights(w);
  double worst = 0.0;
  for (int s = 0; s <= 1000; ++s) {
    const Eigen::Vector3d x = lattice.evaluate({s / 1000.0, 0.0, 0.5});
    worst = std::max(worst, std::abs(std::hypot(x.x(), x.y()) - 1.0));
    const Eigen::Vector3d y = lattice.evaluate({s / 1000.0, 1.0, 0.0});
    worst = std::max(worst, std::abs(std::hypot(y.x(), y.y()) - 2.0) / 2.0);
  }
  EXPECT_LE(worst, 1e-15);
  // Through the deformer: a straight segment of object points along the lattice's u axis.
  Eigen::MatrixX3d Q(1001, 3);
  for (int s = 0; s <= 1000; ++s) Q.row(s) << s / 1000.0, 0.0, 0.25;
  Deformer deformer(embed(lattice, Q));
  const Eigen::MatrixX3d& out = deformer.deform(lattice, Q);
  double radius = 0.0;
  for (Eigen::Index r = 0; r < out.rows(); ++r)
    radius = std::max(radius, std::abs(std::hypot(out(r, 0), out(r, 1)) - 1.0));
  EXPECT_LE(radius, 1e-15);
  EXPECT_NEAR(out(0, 0), 1.0, 1e-15);
  EXPECT_NEAR(out(1000, 1), 1.0, 1e-15);
  // The midpoint u = 1/2 is at 45 degrees.
  EXPECT_NEAR(out(500, 0), std::numbers::sqrt2 / 2, 1e-15);
  EXPECT_NEAR(out(500, 1), std::numbers::sqrt2 / 2, 1e-15);
}

TEST(RationalLattice, EmbeddingInvertsTheWeightedRestMap) {
  for (AxisBasis basis : {AxisBasis::bspline(3), AxisBasis::bernstein()}) {
    Lattice lattice = boxLattice({4, 4, 4}, basis);
    lattice.setRestPoints(jiggled(lattice.restPoints(), 0.04, 8));
    lattice.setRestWeights(randomWeights(lattice.pointCount(), 0.5, 2.0, 9));
    lattice.setFrame(Eigen::Affine3d(Eigen::Translation3d(1.0, -2.0, 0.5)) *
                     Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized()) * Eigen::Scaling(2.0));
    EXPECT_FALSE(lattice.restIsAffine());
    EXPECT_TRUE(lattice.restIsRational());
    const Eigen::MatrixX3d uvw = randomPoints(20000, 0.02, 0.98, 10);
    Eigen::MatrixX3d Q(uvw.rows(), 3);
    for (Eigen::Index r = 0; r < uvw.rows(); ++r)
      Q.row(r) = (lattice.frame() * lattice.evaluateRest(uvw.row(r).transpose())).transpose();
    const Embedding e = embed(lattice, Q);
    EXPECT_EQ(e.insideCount(), Q.rows());
    const Eigen::MatrixX3d found = e.parameters();
    EXPECT_LT((found - uvw).cwiseAbs().maxCoeff(), 1e-10);
    // At rest the deformer gives the points back; with weights and points moved, F X(u,v,w).
    Deformer deformer(e);
    EXPECT_LT((deformer.deform(lattice, Q) - Q).cwiseAbs().maxCoeff(), 1e-12);
    lattice.setControlPoints(jiggled(lattice.restPoints(), 0.1, 11));
    lattice.setWeight(lattice.index(1, 2, 1), 3.0);
    const Eigen::MatrixX3d& out = deformer.deform(lattice, Q);
    for (Eigen::Index r = 0; r < Q.rows(); r += 101) {
      const Eigen::Vector3d expected = lattice.frame() * lattice.evaluate(found.row(r).transpose());
      EXPECT_LT((out.row(r).transpose() - expected).norm(), 1e-12) << "point " << r;
    }
  }
}

// The deformer's homogeneous form (the power-form kernels on (w P, w), one division per point;
// Cox-de Boor sums above cubic) against the formula out = Q + F.linear (X(u,v,w) - Xbar(u,v,w)) in
// long double, with a frame, rest weights, and points moved with their weights kept (the
// numerator-only delta step) and with a weight changed (the re-evaluation step): 1e-14 relative.
TEST(RationalLattice, HomogeneousEvaluationAgreesWithTheFormulaToRoundoff) {
  struct Case {
    Eigen::Vector3i counts;
    AxisBasis basis;
    RefAxis ref[3];
  };
  const Case cases[] = {
      {{4, 4, 4}, AxisBasis::bspline(3), {refBSpline(4, 3), refBSpline(4, 3), refBSpline(4, 3)}},
      {{7, 5, 6}, AxisBasis::bspline(2), {refBSpline(7, 2), refBSpline(5, 2), refBSpline(6, 2)}},
      {{5, 2, 3}, AxisBasis::bernstein(), {{true, 5, 4, {}}, {true, 2, 1, {}}, {true, 3, 2, {}}}},
  };
  for (const Case& c : cases) {
    Lattice lattice = boxLattice(c.counts, c.basis);
    lattice.setRestWeights(randomWeights(lattice.pointCount(), 0.5, 2.0, 31));
    lattice.setFrame(Eigen::Affine3d(Eigen::Translation3d(3.0, -1.0, 2.0)) *
                     Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 1).normalized()) * Eigen::Scaling(1.5, 2.0, 0.75));
    const Eigen::MatrixX3d Q = randomPoints(20000, 0.02, 0.98, 32);
    Eigen::MatrixX3d world(Q.rows(), 3);
    for (Eigen::Index r = 0; r < Q.rows(); ++r) world.row(r) = (lattice.frame() * Q.row(r).transpose()).transpose();
    Deformer full(embed(lattice, world)), delta(embed(lattice, world));
    const Eigen::MatrixX3d params = full.embedding().parameters();
    const Eigen::Matrix3d L = lattice.frame().linear();
    auto check = [&](const Eigen::MatrixX3d& out, const char* what) {
      double worst = 0.0;
      for (Eigen::Index r = 0; r < Q.rows(); r += 37) {
        const Eigen::Vector3d t = params.row(r).transpose();
        const Eigen::Vector3d X = refEvaluate(c.ref, lattice.controlPoints(), lattice.weights(), t);
        const Eigen::Vector3d Xbar = refEvaluate(c.ref, lattice.restPoints(), lattice.restWeights(), t);
        const Eigen::Vector3d expected = world.row(r).transpose() + L * (X - Xbar);
        worst = std::max(worst, (out.row(r).transpose() - expected).cwiseAbs().maxCoeff() / (1.0 + expected.norm()));
      }
      EXPECT_LT(worst, 1e-14) << what << ", lattice " << c.counts.transpose();
    };
    lattice.setControlPoints(jiggled(lattice.restPoints(), 0.1, 33));
    lattice.setWeights(randomWeights(lattice.pointCount(), 0.3, 3.0, 34));
    check(full.deform(lattice, world), "deform");
    delta.deform(lattice, world);
    lattice.setControlPoint(7, lattice.controlPoints().row(7).transpose() + Eigen::Vector3d(0.05, -0.02, 0.03));
    lattice.setControlPoint(9, lattice.controlPoints().row(9).transpose() + Eigen::Vector3d(-0.01, 0.04, 0.02));
    check(delta.update(lattice), "delta step, weights kept");
    EXPECT_EQ(delta.lastStats().changedControlPoints, 2);
    lattice.setWeight(9, 2.5);
    check(delta.update(lattice), "delta step, a weight changed");
    check(full.update(lattice, world), "exact update");
  }
}

TEST(RationalLattice, DeltaAndExactUpdatesFollowAFullEvaluation) {
  Lattice lattice = boxLattice({6, 6, 6}, AxisBasis::bspline(3));
  lattice.setOutsidePolicy(OutsidePolicy{OutsidePolicy::Kind::Falloff, 0.2});
  const Eigen::MatrixX3d Q = randomPoints(50000, -0.15, 1.15, 12);
  Deformer delta(embed(lattice, Q)), exact(embed(lattice, Q));
  delta.deform(lattice, Q);  // polynomial first: the delta step builds its sums when weights appear
  exact.deform(lattice, Q);
  std::mt19937 rng(13);
  std::uniform_int_distribution<Eigen::Index> pick(0, lattice.pointCount() - 1);
  std::uniform_real_distribution<double> U(-0.05, 0.05), W(0.3, 3.0);
  for (int step = 0; step < 40; ++step) {
    const Eigen::Index f = pick(rng);
    if (step % 3 == 0) {
      lattice.setWeight(f, W(rng));
    } else {
      lattice.setControlPoint(f, lattice.controlPoints().row(f).transpose() + Eigen::Vector3d(U(rng), U(rng), U(rng)));
    }
    delta.update(lattice);
    exact.update(lattice, Q);
    Deformer full(embed(lattice, Q));
    const Eigen::MatrixX3d& reference = full.deform(lattice, Q);
    EXPECT_LT((delta.points() - reference).cwiseAbs().maxCoeff(), 1e-13) << "step " << step;
    EXPECT_EQ(0, std::memcmp(exact.points().data(), reference.data(), sizeof(double) * reference.size())) << "step " << step;
    EXPECT_GT(exact.lastStats().evaluatedPoints, 0);
    EXPECT_LT(exact.lastStats().evaluatedPoints, Q.rows());
  }
  // Weights back to 1: the exact update lands on the polynomial deform() bit for bit.
  lattice.setWeights(Eigen::VectorXd::Ones(lattice.pointCount()));
  exact.update(lattice, Q);
  delta.update(lattice);
  Deformer full(embed(lattice, Q));
  const Eigen::MatrixX3d& reference = full.deform(lattice, Q);
  EXPECT_EQ(0, std::memcmp(exact.points().data(), reference.data(), sizeof(double) * reference.size()));
  EXPECT_LT((delta.points() - reference).cwiseAbs().maxCoeff(), 1e-13);
}

TEST(RationalLattice, AWeightEditReachesThePipelineOutput) {
  Lattice lattice = boxLattice({4, 4, 4}, AxisBasis::bspline(3));
  const Eigen::MatrixX3d Q = randomPoints(5000, 0.0, 1.0, 14);
  Pipeline pipeline(Q);
  const LatticeId id = pipeline.addLattice(lattice);
  const Eigen::MatrixX3d before = pipeline.update();
  pipeline.lattice(id).setWeight(lattice.index(1, 1, 1), 4.0);
  const Eigen::MatrixX3d after = pipeline.update();
  EXPECT_GT((after - before).cwiseAbs().maxCoeff(), 1e-3);
  Deformer full(embed(pipeline.lattice(id), Q));
  EXPECT_LT((after - full.deform(pipeline.lattice(id), Q)).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(RationalLattice, BadWeightsAreErrorsNamingThePoint) {
  Lattice lattice = boxLattice({3, 3, 3}, AxisBasis::bernstein());
  const Eigen::Index n = lattice.pointCount();
  auto message = [&](auto&& call) -> std::string {
    try {
      call();
    } catch (const LatticeError& e) {
      return e.what();
    }
    return "no error";
  };
  Eigen::VectorXd w = Eigen::VectorXd::Ones(n);
  w[5] = 0.0;
  EXPECT_NE(message([&] { lattice.setWeights(w); }).find("weight 5 must be finite and > 0, got 0"), std::string::npos);
  w[5] = -2.0;
  EXPECT_NE(message([&] { lattice.setRestWeights(w); }).find("weight 5"), std::string::npos);
  w[5] = std::nan("");
  EXPECT_NE(message([&] { lattice.setWeights(w); }).find("weight 5"), std::string::npos);
  EXPECT_NE(message([&] { lattice.setWeights(Eigen::VectorXd::Ones(n - 1)); }).find("expected 27 weights"), std::string::npos);
  EXPECT_NE(message([&] { lattice.setWeight(27, 1.0); }).find("out of range"), std::string::npos);
  EXPECT_NE(message([&] { lattice.setWeight(3, std::numeric_limits<double>::infinity()); }).find("weight 3"), std::string::npos);
  EXPECT_FALSE(lattice.isRational());  // nothing was changed by the failed calls
}

TEST(RationalLattice, RestWeightsAreKeptApartFromTheCurrentOnes) {
  Lattice lattice = boxLattice({3, 3, 3}, AxisBasis::bernstein());
  const std::uint64_t rest = lattice.restRevision();
  lattice.setWeight(4, 2.0);
  EXPECT_EQ(lattice.restRevision(), rest);  // a weight edit deforms, it does not re-embed
  EXPECT_EQ(lattice.weight(4), 2.0);
  EXPECT_EQ(lattice.restWeights()[4], 1.0);
  lattice.resetToRest();
  EXPECT_EQ(lattice.weight(4), 1.0);
  EXPECT_FALSE(lattice.isRational());
  const Eigen::MatrixX3d moved = jiggled(lattice.controlPoints(), 0.05, 15);
  lattice.setControlPoints(moved);
  lattice.setRestWeights(Eigen::VectorXd::Constant(27, 0.5).cwiseMax(randomWeights(27, 0.5, 1.5, 16)));
  EXPECT_NE(lattice.restRevision(), rest);
  EXPECT_EQ(lattice.controlPoints(), moved);  // the control points are kept
  EXPECT_EQ(lattice.weights(), lattice.restWeights());
  EXPECT_FALSE(lattice.restIsAffine());
}

// With its weights held fixed a rational lattice is linear in its control points, with the
// coefficients R = w B / sum w B: direct manipulation and the per-control-point weights use them.
TEST(RationalLattice, DirectManipulationAndControlWeightsUseTheRationalBasis) {
  Lattice lattice = boxLattice({5, 5, 5}, AxisBasis::bspline(2));
  lattice.setControlPoints(jiggled(lattice.controlPoints(), 0.05, 17));
  lattice.setWeights(randomWeights(lattice.pointCount(), 0.3, 3.0, 18));
  const Eigen::MatrixX3d uvw = (Eigen::MatrixX3d(2, 3) << 0.3, 0.4, 0.5, 0.8, 0.1, 0.6).finished();
  const Eigen::MatrixX3d move = (Eigen::MatrixX3d(2, 3) << 0.05, -0.02, 0.01, 0.0, 0.03, -0.04).finished();
  Eigen::MatrixX3d before(2, 3);
  for (int r = 0; r < 2; ++r) before.row(r) = lattice.evaluate(uvw.row(r).transpose()).transpose();
  lattice.setControlPoints(lattice.controlPoints() + leastNormControlChange(lattice, uvw, move));
  for (int r = 0; r < 2; ++r)
    EXPECT_LT((lattice.evaluate(uvw.row(r).transpose()).transpose() - before.row(r) - move.row(r)).norm(), 1e-14);

  const Eigen::MatrixX3d Q = randomPoints(3000, 0.0, 1.0, 19);
  Deformer deformer(embed(lattice, Q));
  const Eigen::MatrixX3d start = deformer.deform(lattice, Q);
  const Eigen::Index flat = lattice.index(2, 1, 3);
  const Eigen::VectorXd weight = controlPointWeights(lattice, deformer.embedding(), flat);
  const Eigen::Vector3d dP(0.01, -0.02, 0.015);
  lattice.setControlPoint(flat, lattice.controlPoints().row(flat).transpose() + dP);
  const Eigen::MatrixX3d& moved = deformer.deform(lattice, Q);
  for (Eigen::Index p = 0; p < Q.rows(); ++p)
    EXPECT_LT((moved.row(p) - start.row(p) - weight[p] * dP.transpose()).norm(), 1e-15) << "point " << p;
  EXPECT_GT(weight.maxCoeff(), 0.1);
  // A skin of control displacements exists only while the weights equal the rest weights.
  EXPECT_THROW(largestControlWeights(lattice, deformer.embedding(), 4), LatticeError);
}

// checkFolding on a rational lattice finds folds by sampling and certifies nothing.
// det of the central-difference Jacobian of the rational map X = sum B w P / sum B w (the
// long-double reference formula, not the library), lattice-local, at an interior point.
double referenceDeterminant(const RefAxis (&axes)[3], const Lattice& lattice, const Eigen::Vector3d& uvw) {
  const double h = 1e-6;
  Eigen::Matrix3d J;
  for (int a = 0; a < 3; ++a) {
    Eigen::Vector3d lo = uvw, hi = uvw;
    lo[a] = std::max(0.0, uvw[a] - h);
    hi[a] = std::min(1.0, uvw[a] + h);
    J.col(a) = (refEvaluate(axes, lattice.controlPoints(), lattice.weights(), hi) -
                refEvaluate(axes, lattice.controlPoints(), lattice.weights(), lo)) /
               (hi[a] - lo[a]);
  }
  return J.determinant();
}

// The certified bound of a rational lattice (det J = det[H_u, H_v, H_w, H] / D^4 with H = (w P, w),
// in Bernstein form) against dense sampling of det J by finite differences of the reference
// formula: every cell's lowerBound is below every sample of it, Positive cells sample > 0, Folds
// witnesses sample <= 0.
void expectBoundAgreesWithSampling(const RefAxis (&axes)[3], const Lattice& lattice, const FoldCheckResult& result) {
  constexpr int kSamples = 7;
  for (int cw = 0; cw < result.cellCounts[2]; ++cw)
    for (int cv = 0; cv < result.cellCounts[1]; ++cv)
      for (int cu = 0; cu < result.cellCounts[0]; ++cu) {
        const int cell[3] = {cu, cv, cw};
        const std::size_t flat = cu + result.cellCounts[0] * (cv + std::size_t(result.cellCounts[1]) * cw);
        double smallest = std::numeric_limits<double>::infinity();
        for (int k = 0; k < kSamples; ++k)
          for (int j = 0; j < kSamples; ++j)
            for (int i = 0; i < kSamples; ++i) {
              const int at[3] = {i, j, k};
              Eigen::Vector3d uvw;
              for (int a = 0; a < 3; ++a) {
                const AxisSpline& axis = lattice.axis(a);
                uvw[a] = axis.cellMin(cell[a]) + (axis.cellMax(cell[a]) - axis.cellMin(cell[a])) * (at[a] + 0.5) / kSamples;
              }
              smallest = std::min(smallest, result.orientation * referenceDeterminant(axes, lattice, uvw));
            }
        EXPECT_LE(result.lowerBound[flat], smallest + 1e-7 * (1.0 + std::abs(smallest))) << "cell " << flat;
        if (result.cells[flat] == CellFolding::Positive) {
          EXPECT_GT(smallest, 0.0) << "cell " << flat;
        }
        if (result.cells[flat] == CellFolding::Folds) {
          ASSERT_TRUE(result.witness[flat].allFinite());
          EXPECT_LE(result.orientation * lattice.jacobian(result.witness[flat]).determinant(), 1e-9);
        }
      }
}

TEST(RationalLattice, FoldBoundCertifiesALatticeThatDoesNotFold) {
  struct Case {
    Eigen::Vector3i counts;
    AxisBasis basis;
    RefAxis ref[3];
  };
  const Case cases[] = {
      {{4, 4, 4}, AxisBasis::bspline(2), {refBSpline(4, 2), refBSpline(4, 2), refBSpline(4, 2)}},
      {{5, 5, 5}, AxisBasis::bspline(3), {refBSpline(5, 3), refBSpline(5, 3), refBSpline(5, 3)}},
      // Unequal degrees (3, 1, 2): the general product path.
      {{4, 2, 3}, AxisBasis::bernstein(), {{true, 4, 3, {}}, {true, 2, 1, {}}, {true, 3, 2, {}}}},
  };
  for (const Case& c : cases) {
    Lattice lattice = boxLattice(c.counts, c.basis);
    lattice.setControlPoints(jiggled(lattice.controlPoints(), 0.03, 41));
    lattice.setWeights(randomWeights(lattice.pointCount(), 0.4, 2.5, 42));
    const FoldCheckResult result = checkFolding(lattice);
    EXPECT_TRUE(result.certifiedPositive()) << result.foldsCount << " fold, " << result.unknownCount << " unknown";
    EXPECT_EQ(result.positiveCount, Eigen::Index(result.cells.size()));
    expectBoundAgreesWithSampling(c.ref, lattice, result);
  }
}

TEST(RationalLattice, FoldBoundCatchesALatticeBuiltToFold) {
  const RefAxis axes[3] = {refBSpline(4, 2), refBSpline(4, 2), refBSpline(4, 2)};
  Lattice lattice = boxLattice({4, 4, 4}, AxisBasis::bspline(2));
  lattice.setWeight(lattice.index(1, 1, 1), 2.0);
  EXPECT_TRUE(checkFolding(lattice).certifiedPositive());
  // Push an inner point through the face opposite: the first cell turns inside out; its weight
  // pulls the map towards it, a heavier weight folds more of the cell.
  lattice.setControlPoint(lattice.index(1, 1, 1), Eigen::Vector3d(-0.6, -0.6, -0.6));
  lattice.setWeight(lattice.index(1, 1, 1), 5.0);
  const FoldCheckResult folded = checkFolding(lattice);
  ASSERT_GT(folded.foldsCount, 0);
  EXPECT_EQ(folded.cells[0], CellFolding::Folds);
  EXPECT_FALSE(folded.certifiedPositive());
  expectBoundAgreesWithSampling(axes, lattice, folded);
  // A cell far from the pushed point stays certified.
  EXPECT_EQ(folded.cells.back(), CellFolding::Positive);
}

// Equal weights (any value) give the polynomial map: the rational lattice's check gives the
// polynomial path's verdicts and bounds (a cell whose window has equal weights takes det J's own
// bound). One weight changed in a corner: the cells away from it keep their polynomial verdicts.
TEST(RationalLattice, FoldBoundWithEqualWeightsGivesThePolynomialVerdicts) {
  for (double push : {0.0, 0.5, 1.5, 3.0}) {
    Lattice lattice = boxLattice({5, 5, 5}, AxisBasis::bspline(3));
    Eigen::MatrixX3d p = jiggled(lattice.controlPoints(), 0.02, 43);
    for (int j = 1; j <= 2; ++j)
      for (int k = 1; k <= 2; ++k) p(lattice.index(1, j, k), 0) += push;
    lattice.setControlPoints(p);
    const FoldCheckResult polynomial = checkFolding(lattice);
    ASSERT_FALSE(lattice.isRational());
    lattice.setWeights(Eigen::VectorXd::Constant(lattice.pointCount(), 2.0));
    ASSERT_TRUE(lattice.isRational());
    const FoldCheckResult rational = checkFolding(lattice);
    EXPECT_EQ(rational.cells, polynomial.cells) << "push " << push;
    EXPECT_EQ(rational.lowerBound, polynomial.lowerBound) << "push " << push;
    EXPECT_EQ(rational.positiveCount, polynomial.positiveCount);
    lattice.setWeight(lattice.index(4, 4, 4), 3.0);  // the window of the last cell only
    const FoldCheckResult corner = checkFolding(lattice);
    for (std::size_t c = 0; c + 1 < polynomial.cells.size(); ++c) EXPECT_EQ(corner.cells[c], polynomial.cells[c]);
  }
}

}  // namespace
}  // namespace ffdkit::ffd
