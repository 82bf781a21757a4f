// Shape constraints: the engine's least-norm control change against an independent dense
// computation (the deformation's matrix built from Lattice::evaluate, a KKT solve by SVD), the
// volume and centroid after Newton against the divergence theorem on the deformed mesh, and
// the errors for open surfaces and constraints that cannot be met.
#include "ffdkit/ffd/shape_constraints.h"

#include <random>

#include <Eigen/SVD>
#include <gtest/gtest.h>

#include "closed_surfaces.h"
#include "test_lattices.h"

namespace ffdkit::ffd {
namespace {

// The deformed world points through the reference evaluator: F * X(uvw) for every point.
Eigen::MatrixX3d evaluated(const Lattice& lattice, const Eigen::MatrixX3d& uvw) {
  Eigen::MatrixX3d x(uvw.rows(), 3);
  for (Eigen::Index p = 0; p < uvw.rows(); ++p)
    x.row(p) = (lattice.frame() * lattice.evaluate(uvw.row(p).transpose())).transpose();
  return x;
}

// M (3 #points x 3 #controls): d x' / d P, flattened row-major on both sides, column by column
// from unit moves of one control coordinate through Lattice::evaluate (x' is linear in P).
Eigen::MatrixXd deformationMatrix(const Lattice& lattice, const Eigen::MatrixX3d& uvw) {
  const Eigen::Index n = uvw.rows(), N = lattice.pointCount();
  Eigen::MatrixXd M(3 * n, 3 * N);
  const Eigen::MatrixX3d base = evaluated(lattice, uvw);
  for (Eigen::Index i = 0; i < N; ++i)
    for (int c = 0; c < 3; ++c) {
      Lattice moved = lattice;
      moved.setControlPoint(i, lattice.controlPoints().row(i).transpose() + Eigen::Vector3d::Unit(c));
      const Eigen::MatrixX3d x = evaluated(moved, uvw) - base;
      for (Eigen::Index p = 0; p < n; ++p)
        for (int d = 0; d < 3; ++d) M(3 * p + d, 3 * i + c) = x(p, d);
    }
  return M;
}

Eigen::VectorXd flat(const Eigen::MatrixX3d& m) {
  Eigen::VectorXd v(3 * m.rows());
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (int c = 0; c < 3; ++c) v[3 * r + c] = m(r, c);
  return v;
}

struct PointsSetup {
  Lattice lattice;
  Eigen::MatrixX3d uvw, points;
};

PointsSetup randomSetup(std::mt19937& rng, Eigen::Index n) {
  Lattice lattice = testing::randomLattice(rng, 0.0, 5);
  // Some control points already moved, so constraints are solved from a deformed state.
  lattice.setControlPoints(lattice.controlPoints() + 0.05 * Eigen::MatrixX3d::Random(lattice.pointCount(), 3));
  Eigen::MatrixX3d uvw = testing::randomParameters(lattice, n, rng);
  // Keep the parameters off the box faces so every point embeds as Inside.
  const Eigen::Vector3d lo = lattice.parameterMin(), hi = lattice.parameterMax();
  for (Eigen::Index r = 0; r < n; ++r)
    for (int a = 0; a < 3; ++a) uvw(r, a) = lo[a] + (0.05 + 0.9 * (uvw(r, a) - lo[a]) / (hi[a] - lo[a])) * (hi[a] - lo[a]);
  Eigen::MatrixX3d points = testing::restImages(lattice, uvw);
  return {lattice, uvw, points};
}

TEST(ShapeConstraints, LinearRowsGiveTheLeastNormChangeOfADenseKktSolve) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 12; ++trial) {
    PointsSetup s = randomSetup(rng, 30);
    const Eigen::Index n = s.points.rows(), N = s.lattice.pointCount();
    const int m = std::uniform_int_distribution<int>(1, 5)(rng);
    Eigen::MatrixXd A = Eigen::MatrixXd::Random(m, 3 * n);
    // A sparse row too: one coordinate of one point pinned.
    A.row(0).setZero();
    A(0, 3 * 4 + 1) = 1.0;
    const Eigen::VectorXd b = A * flat(evaluated(s.lattice, s.uvw)) + 0.1 * Eigen::VectorXd::Random(m);
    ControlMask free = ControlMask::Constant(N, 3, true);
    if (trial % 2 == 1)  // half the trials with some control coordinates fixed
      for (Eigen::Index i = 0; i < N; ++i)
        for (int c = 0; c < 3; ++c) free(i, c) = (i + c) % 3 != 0;

    ShapeConstraints constraints(s.lattice, s.points);
    constraints.setFreeControls(free);
    constraints.addLinear(A.sparseView(), b);
    const ShapeSolveResult result = constraints.solve(s.lattice);

    // Independent: J = A M restricted to the free columns, least-norm delta = J^+ (b - A x0).
    const Eigen::MatrixXd M = deformationMatrix(s.lattice, s.uvw);
    std::vector<Eigen::Index> cols;
    for (Eigen::Index k = 0; k < 3 * N; ++k)
      if (free(k / 3, k % 3)) cols.push_back(k);
    Eigen::MatrixXd J(m, Eigen::Index(cols.size()));
    const Eigen::MatrixXd AM = A * M;
    for (std::size_t k = 0; k < cols.size(); ++k) J.col(Eigen::Index(k)) = AM.col(cols[k]);
    const Eigen::VectorXd rhs = b - A * flat(evaluated(s.lattice, s.uvw));
    const Eigen::VectorXd y = J.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(rhs);
    Eigen::VectorXd expected = Eigen::VectorXd::Zero(3 * N);
    for (std::size_t k = 0; k < cols.size(); ++k) expected[cols[k]] = y[Eigen::Index(k)];
    EXPECT_LT((flat(result.change) - expected).cwiseAbs().maxCoeff(), 1e-9 * (1 + expected.cwiseAbs().maxCoeff()))
        << "trial " << trial;
    // The constraints hold on the reference evaluator's points.
    Lattice after = s.lattice;
    after.setControlPoints(s.lattice.controlPoints() + result.change);
    EXPECT_LT((A * flat(evaluated(after, s.uvw)) - b).cwiseAbs().maxCoeff(), 1e-11) << "trial " << trial;
    EXPECT_LE(result.iterations, 2);
  }
}

TEST(ShapeConstraints, BarycentreIsMovedExactlyToItsTarget) {
  std::mt19937 rng(8);
  PointsSetup s = randomSetup(rng, 200);
  ShapeConstraints constraints(s.lattice, s.points);
  const Eigen::Vector3d target = evaluated(s.lattice, s.uvw).colwise().mean().transpose() + Eigen::Vector3d(0.05, -0.02, 0.03);
  constraints.keepBarycentre(target);
  const ShapeSolveResult result = constraints.solve(s.lattice);
  Lattice after = s.lattice;
  after.setControlPoints(s.lattice.controlPoints() + result.change);
  EXPECT_LT((evaluated(after, s.uvw).colwise().mean().transpose() - target).norm(), 1e-13);
  // Least norm: the change lies in the row space of the three mean rows, i.e. dP_i = M_i^T y.
  const Eigen::MatrixXd M = deformationMatrix(s.lattice, s.uvw);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(3, M.cols());
  for (Eigen::Index p = 0; p < s.points.rows(); ++p) R += M.middleRows(3 * p, 3) / double(s.points.rows());
  // Rt as a column-major matrix, so that the SVD is the one the test above instantiates (the
  // transpose's own plain type is row-major: a second JacobiSVD to compile).
  const Eigen::MatrixXd Rt = R.transpose();
  const Eigen::VectorXd projected = Rt * Rt.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(flat(result.change));
  EXPECT_LT((projected - flat(result.change)).norm(), 1e-10 * flat(result.change).norm());
}

struct VolumeSetup {
  Lattice lattice;
  testing::TestMesh mesh;
};

// A sphere inside a 4x4x4 cubic lattice over [-1, 1]^3 under a random frame, the lattice dragged.
VolumeSetup volumeSetup(std::mt19937& rng, int rings, double drag) {
  BoxLatticeOptions options;
  options.boxMin = Eigen::Vector3d::Constant(-1.0);
  options.boxMax = Eigen::Vector3d::Constant(1.0);
  options.frame = testing::randomFrame(rng);
  Lattice lattice = makeBoxLattice(options);
  testing::TestMesh mesh = testing::sphereMesh({0.1, -0.05, 0.0}, 0.7, rings, 2 * rings);
  for (Eigen::Index r = 0; r < mesh.points.rows(); ++r)
    mesh.points.row(r) = (options.frame * mesh.points.row(r).transpose()).transpose();
  Eigen::MatrixX3d p = lattice.controlPoints();
  p.row(lattice.index(3, 1, 2)) += drag * Eigen::RowVector3d(1.0, 0.4, -0.2);
  p.row(lattice.index(0, 2, 1)) += drag * Eigen::RowVector3d(-0.5, 0.8, 0.3);
  lattice.setControlPoints(p);
  return {lattice, mesh};
}

TEST(ShapeConstraints, VolumeIsKeptToOnePartIn1e12AtALagrangePoint) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 4; ++trial) {
    VolumeSetup s = volumeSetup(rng, 24, 0.3 + 0.2 * trial);
    const ClosedSurface surface(s.mesh.triangles, s.mesh.points.rows());
    const double rest = enclosedVolume(s.mesh.points, surface);
    ShapeConstraints constraints(s.lattice, s.mesh.points);
    constraints.keepVolume(surface, rest);
    const ShapeSolveResult result = constraints.solve(s.lattice);
    EXPECT_GE(result.iterations, 2);
    EXPECT_LE(result.volumeRelativeError, 1e-12);
    // Independent: the divergence-theorem volume of the mesh deformed by Lattice::evaluate.
    Lattice after = s.lattice;
    after.setControlPoints(s.lattice.controlPoints() + result.change);
    const Eigen::MatrixX3d uvw = constraints.embedding().parameters();
    const Eigen::MatrixX3d x = evaluated(after, uvw);
    EXPECT_LT(std::abs(enclosedVolume(x, surface) - rest) / rest, 1e-12) << "trial " << trial;
    // Lagrange: the change is parallel to the volume's gradient with respect to the control
    // points at the solution, M^T g (g: the per-vertex gradient of the divergence sum).
    Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
    for (Eigen::Index t = 0; t < s.mesh.triangles.rows(); ++t) {
      const int a = s.mesh.triangles(t, 0), b = s.mesh.triangles(t, 1), c = s.mesh.triangles(t, 2);
      const Eigen::Vector3d xa = x.row(a), xb = x.row(b), xc = x.row(c);
      g.row(a) += xb.cross(xc).transpose() / 6;
      g.row(b) += xc.cross(xa).transpose() / 6;
      g.row(c) += xa.cross(xb).transpose() / 6;
    }
    const Eigen::VectorXd grad = deformationMatrix(after, uvw).transpose() * flat(g);
    const Eigen::VectorXd d = flat(result.change);
    const Eigen::VectorXd along = grad.normalized() * grad.normalized().dot(d);
    EXPECT_LT((d - along).norm(), 1e-9 * d.norm()) << "trial " << trial;
  }
}

// The precomputed volume polynomial (VolumeEvaluation::Polynomial) against the divergence-theorem
// volume of the mesh deformed by Lattice::evaluate, at random control displacements: a single
// Bernstein cell under a random frame, a 5x5x5 cubic B-spline lattice whose cells the sphere
// crosses (stars across cell boundaries), and points outside the lattice (Falloff: blended
// weights; Identity: frozen), where the deformer's output is the reference.
TEST(ShapeConstraints, VolumePolynomialEqualsTheDivergenceTheoremVolumeOfTheDeformedMesh) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  struct Case {
    const char* name;
    BoxLatticeOptions options;
    double radius;
    bool insideOnly;
  };
  std::vector<Case> cases;
  {
    Case c{"bernstein 4x4x4, random frame", {}, 0.7, true};
    c.options.bases = {AxisBasis::bernstein(), AxisBasis::bernstein(), AxisBasis::bernstein()};
    c.options.frame = testing::randomFrame(rng);
    cases.push_back(c);
  }
  {
    Case c{"cubic B-spline 5x5x5 (8 cells)", {}, 0.7, true};
    c.options.counts = Eigen::Vector3i(5, 5, 5);
    c.options.frame = testing::randomFrame(rng);
    cases.push_back(c);
  }
  {
    Case c{"cubic B-spline 4x4x4, sphere half outside, falloff", {}, 1.3, false};
    c.options.outsidePolicy = OutsidePolicy::falloff(0.5);
    cases.push_back(c);
  }
  {
    Case c{"cubic B-spline 4x4x4, sphere half outside, identity", {}, 1.3, false};
    cases.push_back(c);
  }
  for (Case& c : cases) {
    c.options.boxMin = Eigen::Vector3d::Constant(-1.0);
    c.options.boxMax = Eigen::Vector3d::Constant(1.0);
    Lattice lattice = makeBoxLattice(c.options);
    testing::TestMesh mesh = testing::sphereMesh({0.1, -0.05, 0.02}, c.radius, 20, 40);
    for (Eigen::Index r = 0; r < mesh.points.rows(); ++r)
      mesh.points.row(r) = (c.options.frame * mesh.points.row(r).transpose()).transpose();
    const ClosedSurface surface(mesh.triangles, mesh.points.rows());
    const double rest = enclosedVolume(mesh.points, surface);
    ShapeConstraints constraints(lattice, mesh.points);
    constraints.keepVolume(surface, rest, VolumeEvaluation::Polynomial);
    ASSERT_TRUE(constraints.volumeIsPolynomial()) << c.name;
    EXPECT_NEAR(constraints.keptVolume(lattice), rest, 1e-13 * rest) << c.name;
    const Eigen::MatrixX3d uvw = constraints.embedding().parameters();
    Deformer deformer(embed(lattice, mesh.points));
    for (int trial = 0; trial < 5; ++trial) {
      Eigen::MatrixX3d p = lattice.restPoints();
      for (Eigen::Index r = 0; r < p.rows(); ++r)
        for (int k = 0; k < 3; ++k) p(r, k) += 0.15 * (trial + 1) / 3.0 * U(rng);
      lattice.setControlPoints(p);
      const Eigen::MatrixX3d x = c.insideOnly ? evaluated(lattice, uvw) : Eigen::MatrixX3d(deformer.deform(lattice, mesh.points));
      const double expected = enclosedVolume(x, surface);
      EXPECT_LT(std::abs(constraints.keptVolume(lattice) - expected) / std::abs(expected), 1e-12)
          << c.name << ", trial " << trial << ": " << constraints.keptVolume(lattice) << " vs " << expected;
    }
    // The same Newton solve through the polynomial and per vertex.
    ShapeConstraints perVertex(lattice, mesh.points);
    perVertex.keepVolume(surface, rest, VolumeEvaluation::PerVertex);
    EXPECT_FALSE(perVertex.volumeIsPolynomial());
    const ShapeSolveResult fast = constraints.solve(lattice), slow = perVertex.solve(lattice);
    EXPECT_LE(fast.volumeRelativeError, 1e-12) << c.name;
    EXPECT_LT((fast.change - slow.change).norm(), 1e-9 * slow.change.norm()) << c.name;
    EXPECT_NEAR(enclosedVolume(constraints.deformedPoints(), surface), rest, 1e-12 * rest) << c.name;
  }
}

// More than 128 control points moving the surface: Polynomial is refused with the limit named,
// Automatic solves per vertex.
TEST(ShapeConstraints, VolumePolynomialNeedsAtMost128MovingControlPoints) {
  BoxLatticeOptions options;
  options.counts = Eigen::Vector3i(6, 6, 6);  // 216 control points, 27 cubic cells
  options.boxMin = Eigen::Vector3d::Constant(-1.0);
  options.boxMax = Eigen::Vector3d::Constant(1.0);
  Lattice lattice = makeBoxLattice(options);
  const testing::TestMesh mesh = testing::sphereMesh({0.0, 0.0, 0.0}, 0.8, 12, 24);
  const ClosedSurface surface(mesh.triangles, mesh.points.rows());
  const double rest = enclosedVolume(mesh.points, surface);
  ShapeConstraints constraints(lattice, mesh.points);
  try {
    constraints.keepVolume(surface, rest, VolumeEvaluation::Polynomial);
    ADD_FAILURE() << "216 moving control points accepted";
  } catch (const ConstraintError& e) {
    EXPECT_NE(std::string(e.what()).find("at most 128 control points"), std::string::npos) << e.what();
  }
  constraints.keepVolume(surface, rest);
  EXPECT_FALSE(constraints.volumeIsPolynomial());
  Eigen::MatrixX3d p = lattice.controlPoints();
  p.row(lattice.index(2, 3, 2)) += Eigen::RowVector3d(0.2, -0.1, 0.1);
  lattice.setControlPoints(p);
  const ShapeSolveResult result = constraints.solve(lattice);
  EXPECT_LE(result.volumeRelativeError, 1e-12);
  EXPECT_NEAR(enclosedVolume(constraints.deformedPoints(), surface), rest, 1e-12 * rest);
}

TEST(ShapeConstraints, VolumeWithFixedControlsMovesOnlyTheFreeOnes) {
  std::mt19937 rng(10);
  VolumeSetup s = volumeSetup(rng, 16, 0.4);
  const ClosedSurface surface(s.mesh.triangles, s.mesh.points.rows());
  ShapeConstraints constraints(s.lattice, s.mesh.points);
  ControlMask free = ControlMask::Constant(s.lattice.pointCount(), 3, false);
  free.col(2).setConstant(true);  // only the local z coordinates may move
  constraints.setFreeControls(free);
  const double rest = enclosedVolume(s.mesh.points, surface);
  constraints.keepVolume(surface, 0.9 * rest);
  const ShapeSolveResult result = constraints.solve(s.lattice);
  EXPECT_EQ(result.change.leftCols(2).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LE(result.volumeRelativeError, 1e-12);
  EXPECT_NEAR(enclosedVolume(constraints.deformedPoints(), surface), 0.9 * rest, 1e-12 * rest);
}

TEST(ShapeConstraints, VolumeAndBarycentreTogether) {
  std::mt19937 rng(11);
  VolumeSetup s = volumeSetup(rng, 16, 0.5);
  const ClosedSurface surface(s.mesh.triangles, s.mesh.points.rows());
  ShapeConstraints constraints(s.lattice, s.mesh.points);
  const double rest = enclosedVolume(s.mesh.points, surface);
  const Eigen::Vector3d mean = s.mesh.points.colwise().mean().transpose();
  constraints.keepVolume(surface, rest);
  constraints.keepBarycentre(mean);
  const ShapeSolveResult result = constraints.solve(s.lattice);
  EXPECT_NEAR(enclosedVolume(constraints.deformedPoints(), surface), rest, 1e-12 * rest);
  EXPECT_LT((constraints.deformedPoints().colwise().mean().transpose() - mean).norm(), 1e-12);
  EXPECT_LE(result.largestRelativeResidual, 1e-12);
}

TEST(ShapeConstraints, CentroidOfTheSolidIsKept) {
  std::mt19937 rng(12);
  VolumeSetup s = volumeSetup(rng, 16, 0.4);
  const ClosedSurface surface(s.mesh.triangles, s.mesh.points.rows());
  const Eigen::Vector3d centroid = enclosedCentroid(s.mesh.points, surface);
  ShapeConstraints constraints(s.lattice, s.mesh.points);
  constraints.keepCentroid(surface, centroid);
  const ShapeSolveResult result = constraints.solve(s.lattice);
  EXPECT_GE(result.iterations, 1);
  EXPECT_LT((enclosedCentroid(constraints.deformedPoints(), surface) - centroid).norm(), 1e-11);
}

// The centroid held by the fast passes (one pass over the triangles per Newton step, the three
// rows' gradients carried to the control points in one adjoint pass, in parallel above 16,384
// points) against the test's own centroid: the sphere deformed point by point through
// Lattice::evaluate, then sum det[a, b, c] (a + b + c) / (4 sum det[a, b, c]) over its triangles.
// A 6x6x6 cubic lattice (27 cells: the adjoint's point order is not the points' order) under a
// random frame; both Jacobian updates, and the chord's change close to the Lagrange point's.
TEST(ShapeConstraints, CentroidHeldByTheFastPassesEqualsAPlainPerVertexEvaluation) {
  std::mt19937 rng(31);
  BoxLatticeOptions options;
  options.counts = Eigen::Vector3i::Constant(6);
  options.boxMin = Eigen::Vector3d::Constant(-1.0);
  options.boxMax = Eigen::Vector3d::Constant(1.0);
  options.frame = testing::randomFrame(rng);
  Lattice lattice = makeBoxLattice(options);
  testing::TestMesh mesh = testing::sphereMesh({0.1, -0.05, 0.02}, 0.7, 100, 200);  // 19,802 vertices
  for (Eigen::Index r = 0; r < mesh.points.rows(); ++r)
    mesh.points.row(r) = (options.frame * mesh.points.row(r).transpose()).transpose();
  ASSERT_GT(mesh.points.rows(), 16384);
  const ClosedSurface surface(mesh.triangles, mesh.points.rows());
  const auto centroidOf = [&mesh](const Eigen::MatrixX3d& x) {
    double volume6 = 0.0;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
      const Eigen::Vector3d a = x.row(mesh.triangles(t, 0)), b = x.row(mesh.triangles(t, 1)),
                            c = x.row(mesh.triangles(t, 2));
      const double det = a.dot(b.cross(c));
      volume6 += det;
      moment += det * (a + b + c);
    }
    return Eigen::Vector3d(moment / (4.0 * volume6));
  };
  const Eigen::Vector3d target = centroidOf(mesh.points);
  Eigen::MatrixX3d p = lattice.controlPoints();
  p.row(lattice.index(4, 2, 3)) += 0.05 * Eigen::RowVector3d(1.0, 0.4, -0.2);
  p.row(lattice.index(1, 3, 2)) += 0.03 * Eigen::RowVector3d(-0.5, 0.8, 0.3);
  lattice.setControlPoints(p);
  ShapeConstraints constraints(lattice, mesh.points);
  constraints.keepCentroid(surface, target);
  const Eigen::MatrixX3d uvw = constraints.embedding().parameters();
  ASSERT_GT((centroidOf(evaluated(lattice, uvw)) - target).norm(), 1e-4);  // the drag moved it
  Eigen::MatrixX3d changes[2];
  for (JacobianUpdate jacobian : {JacobianUpdate::EveryStep, JacobianUpdate::FirstStep}) {
    ShapeSolveOptions solveOptions;
    solveOptions.jacobian = jacobian;
    const ShapeSolveResult result = constraints.solve(lattice, solveOptions);
    const bool chord = jacobian == JacobianUpdate::FirstStep;
    EXPECT_LE(result.largestRelativeResidual, 1e-12);
    EXPECT_EQ(result.jacobianPasses, chord ? 1 : result.iterations);
    Lattice after = lattice;
    after.setControlPoints(lattice.controlPoints() + result.change);
    EXPECT_LT((centroidOf(evaluated(after, uvw)) - target).norm(), 1e-12 * lattice.restSize()) << "chord " << chord;
    changes[chord ? 1 : 0] = result.change;
  }
  // The chord's change is the least-norm one along the gradients at the start: within about
  // |change|^2 / size of the Lagrange point's.
  const double norm = changes[0].norm();
  EXPECT_LT((changes[1] - changes[0]).norm(), 10.0 * norm * norm / lattice.restSize() + 1e-12);
}

// A rational lattice whose current weights differ from its rest weights (1): the deformed points
// are x' = Q + s F (sum R P - Xbar) with R = w B / sum w B, affine in P for the weights held fixed
// but with a constant s F (sum R Pbar - Xbar) beside R P. Barycentre and volume kept against the
// reference evaluator (Lattice::evaluate, the weights included); the volume is summed per vertex
// (Automatic), and the polynomial, built in P - Pbar alone, is refused.
TEST(ShapeConstraints, HoldOnARationalLatticeWhoseWeightsDifferFromTheRest) {
  std::mt19937 rng(21);
  for (VolumeEvaluation evaluation : {VolumeEvaluation::PerVertex, VolumeEvaluation::Automatic}) {
    VolumeSetup s = volumeSetup(rng, 24, 0.4);
    Eigen::VectorXd w(s.lattice.pointCount());
    std::uniform_real_distribution<double> W(0.5, 2.0);
    for (Eigen::Index i = 0; i < w.size(); ++i) w[i] = W(rng);
    s.lattice.setWeights(w);
    ASSERT_TRUE(s.lattice.isRational());
    ASSERT_FALSE(s.lattice.restIsRational());
    const ClosedSurface surface(s.mesh.triangles, s.mesh.points.rows());
    const double rest = enclosedVolume(s.mesh.points, surface);
    ShapeConstraints constraints(s.lattice, s.mesh.points);
    EXPECT_THROW(constraints.keepVolume(surface, rest, VolumeEvaluation::Polynomial), ConstraintError);
    const Eigen::MatrixX3d uvw = constraints.embedding().parameters();
    const Eigen::Vector3d centre = evaluated(s.lattice, uvw).colwise().mean().transpose() + Eigen::Vector3d(0.02, 0.0, -0.01);
    constraints.keepVolume(surface, rest, evaluation);
    EXPECT_FALSE(constraints.volumeIsPolynomial());
    constraints.keepBarycentre(centre);
    const ShapeSolveResult result = constraints.solve(s.lattice);
    Lattice after = s.lattice;
    after.setControlPoints(s.lattice.controlPoints() + result.change);
    const Eigen::MatrixX3d x = evaluated(after, uvw);
    EXPECT_LT(std::abs(enclosedVolume(x, surface) - rest) / rest, 1e-12);
    EXPECT_LT((x.colwise().mean().transpose() - centre).norm(), 1e-12);
    EXPECT_LT((constraints.deformedPoints() - x).cwiseAbs().maxCoeff(), 1e-12);
  }
}

// The volume a closed triangle mesh bounds, by the divergence theorem (the test's own sum).
double divergenceVolume(const Eigen::MatrixX3d& x, const TriangleMatrix& triangles) {
  double sum = 0.0;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const Eigen::Vector3d a = x.row(triangles(t, 0)), b = x.row(triangles(t, 1)), c = x.row(triangles(t, 2));
    sum += a.dot(b.cross(c));
  }
  return sum / 6.0;
}

// Constraints built before a weight edit follow it: solve() sees that its lattice's weights are
// not those the rows were built for and rebuilds them (the change equals that of constraints
// built after the edit), and the volume polynomial, built at the rest weights, gives way to the
// per-vertex sum while the weights differ. Volume and barycentre against the mesh deformed by
// Lattice::evaluate (the weights included), the volume by the divergence theorem.
TEST(ShapeConstraints, FollowAWeightEditMadeAfterTheyWereBuilt) {
  std::mt19937 rng(22);
  for (int trial = 0; trial < 3; ++trial) {
    VolumeSetup s = volumeSetup(rng, 20, 0.3);
    const ClosedSurface surface(s.mesh.triangles, s.mesh.points.rows());
    const double rest = divergenceVolume(s.mesh.points, s.mesh.triangles);
    ShapeConstraints constraints(s.lattice, s.mesh.points);
    constraints.keepVolume(surface, rest);  // Automatic: the polynomial (64 control points)
    ASSERT_TRUE(constraints.volumeIsPolynomial());
    const Eigen::MatrixX3d uvw = constraints.embedding().parameters();
    const Eigen::Vector3d centre = evaluated(s.lattice, uvw).colwise().mean().transpose() + Eigen::Vector3d(0.01, 0.0, -0.02);
    constraints.keepBarycentre(centre);
    (void)constraints.solve(s.lattice);  // a solve before the edit, at weights 1
    ASSERT_EQ(constraints.rowWeights(), Eigen::VectorXd::Ones(s.lattice.pointCount()));

    // Edit weights after the constraints were built (one, then several).
    Lattice edited = s.lattice;
    edited.setWeight(edited.index(1, 2, 1), 2.5);
    if (trial > 0)
      for (int i = 0; i < 6; ++i)
        edited.setWeight(std::uniform_int_distribution<Eigen::Index>(0, edited.pointCount() - 1)(rng),
                         std::uniform_real_distribution<double>(0.5, 2.0)(rng));
    // The polynomial would give the volume at the rest weights: keptVolume sums per vertex.
    EXPECT_NEAR(constraints.keptVolume(edited), divergenceVolume(evaluated(edited, uvw), s.mesh.triangles),
                1e-12 * rest);
    const ShapeSolveResult result = constraints.solve(edited);
    EXPECT_EQ(constraints.rowWeights(), edited.weights());  // detected and rebuilt
    Lattice after = edited;
    after.setControlPoints(edited.controlPoints() + result.change);
    const Eigen::MatrixX3d x = evaluated(after, uvw);
    EXPECT_LT(std::abs(divergenceVolume(x, s.mesh.triangles) - rest) / rest, 1e-12) << "trial " << trial;
    EXPECT_LT((x.colwise().mean().transpose() - centre).norm(), 1e-12) << "trial " << trial;
    // The same least-norm change as constraints built after the edit.
    ShapeConstraints fresh(edited, s.mesh.points);
    fresh.keepVolume(surface, rest);
    fresh.keepBarycentre(centre);
    const ShapeSolveResult expected = fresh.solve(edited);
    EXPECT_LT((result.change - expected.change).norm(), 1e-9 * expected.change.norm()) << "trial " << trial;

    // Back at the rest weights, the polynomial holds again.
    const ShapeSolveResult back = constraints.solve(s.lattice);
    after = s.lattice;
    after.setControlPoints(s.lattice.controlPoints() + back.change);
    EXPECT_LT(std::abs(divergenceVolume(evaluated(after, uvw), s.mesh.triangles) - rest) / rest, 1e-12);
    EXPECT_NEAR(constraints.keptVolume(after), rest, 1e-12 * rest);
  }
}

// With the polynomial asked for explicitly, a lattice whose weights left the rest weights is refused
// (it would be the per-vertex sum's cost, not the polynomial's), naming the control point.
TEST(ShapeConstraints, AnExplicitVolumePolynomialRefusesAWeightEdit) {
  std::mt19937 rng(23);
  VolumeSetup s = volumeSetup(rng, 16, 0.2);
  const ClosedSurface surface(s.mesh.triangles, s.mesh.points.rows());
  const double rest = divergenceVolume(s.mesh.points, s.mesh.triangles);
  ShapeConstraints constraints(s.lattice, s.mesh.points);
  constraints.keepVolume(surface, rest, VolumeEvaluation::Polynomial);
  Lattice edited = s.lattice;
  edited.setWeight(edited.index(2, 1, 3), 1.5);
  const std::string expected = "the volume polynomial (VolumeEvaluation::Polynomial) holds while the weights equal the "
                               "rest weights; control point " + std::to_string(edited.index(2, 1, 3)) +
                               " has weight 1.500000, rest weight 1.000000";
  for (int call = 0; call < 2; ++call) {
    try {
      if (call == 0) (void)constraints.solve(edited);
      else (void)constraints.keptVolume(edited);
      ADD_FAILURE() << "a weight edit was not refused";
    } catch (const LatticeError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
  const ShapeSolveResult result = constraints.solve(s.lattice);  // the rest weights: fine
  EXPECT_LE(result.volumeRelativeError, 1e-12);
}

TEST(ShapeConstraints, RefusesOpenSurfacesAndConstraintsThatCannotBeMet) {
  std::mt19937 rng(13);
  VolumeSetup s = volumeSetup(rng, 8, 0.3);
  ShapeConstraints constraints(s.lattice, s.mesh.points);
  // Open: a sphere without its last triangle.
  EXPECT_THROW(ClosedSurface(s.mesh.triangles.topRows(s.mesh.triangles.rows() - 1), s.mesh.points.rows()),
               ConstraintError);
  const ClosedSurface surface(s.mesh.triangles, s.mesh.points.rows());
  // No free control point: the volume cannot change.
  constraints.setFreeControls(ControlMask::Constant(s.lattice.pointCount(), 3, false));
  constraints.keepVolume(surface, 2.0 * enclosedVolume(s.mesh.points, surface));
  try {
    constraints.solve(s.lattice);
    FAIL() << "no error";
  } catch (const ConstraintError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be met"), std::string::npos) << e.what();
  }
  // Two contradicting rows.
  ShapeConstraints contradicting(s.lattice, s.mesh.points);
  Eigen::SparseMatrix<double, Eigen::RowMajor> A(2, 3 * s.mesh.points.rows());
  A.insert(0, 0) = 1.0;
  A.insert(1, 0) = 1.0;
  contradicting.addLinear(A, Eigen::Vector2d(0.0, 1.0));
  EXPECT_THROW(contradicting.solve(s.lattice), ConstraintError);
  // Sizes.
  EXPECT_THROW(contradicting.addLinear(A, Eigen::Vector3d::Zero()), ConstraintError);
  EXPECT_THROW(contradicting.keepVolume(ClosedSurface(testing::boxMesh({0, 0, 0}, {1, 1, 1}).triangles, 8), 1.0),
               ConstraintError);
  // A stale lattice.
  Lattice moved = s.lattice;
  moved.setFrame(Eigen::Affine3d(Eigen::Translation3d(1, 0, 0)));
  EXPECT_THROW(constraints.solve(moved), LatticeError);
}

}  // namespace
}  // namespace ffdkit::ffd
