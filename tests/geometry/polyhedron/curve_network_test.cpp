#include "ffdkit/geometry/polyhedron/curve_network.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "ffdkit/geometry/polyhedron/builtin_meshes.h"
#include "test_support.h"

namespace ffdkit::geometry::polyhedron {
namespace {

struct Solved {
  PolygonMesh mesh;
  MeshTopology topology;
  ResolvedTensions tensions;
  CurveNetworkResult network;
};

Solved solve(const PolygonMesh& mesh, const Tensions& tensions = {}) {
  Solved s{mesh, validatePolygonMesh(mesh), {}, {}};
  s.tensions = resolveTensions(tensions, s.topology);
  s.network = solveCurveNetwork(mesh, s.topology, s.tensions);
  EXPECT_TRUE(s.network.converged) << s.network.message;
  return s;
}

// Kuriyama 1996, sec. 4.2.1: t_{v->w} = c Pi_v (P_w - P_v), with Pi_v the projection onto the plane normal to P_v.
void expectProjectedLegs(const Solved& s, double factor, double tolerance) {
  for (int he = 0; he < s.topology.halfEdgeCount(); ++he) {
    const Eigen::Vector3d pv = s.mesh.vertices.row(s.topology.from(he)).transpose();
    const Eigen::Vector3d pw = s.mesh.vertices.row(s.topology.to(he)).transpose();
    const Eigen::Vector3d expected = factor * testing::projectOntoPlane(pw - pv, pv);
    EXPECT_LT((s.network.legs.row(he).transpose() - expected).norm(), tolerance) << "half-edge " << he;
  }
}

TEST(CurveNetwork, TetrahedronReproducesReferenceLegsAndPseudoNorm) {
  const Solved s = solve(tetrahedronMesh());
  expectProjectedLegs(s, 3.0 / 5.0, 1e-12);
  EXPECT_NEAR(s.network.legs.row(0).norm(), 0.979796, 1e-6);
  EXPECT_NEAR(pseudoNorm(s.mesh, s.topology, s.tensions, s.network.legs), 6.4, 1e-12);
}

TEST(CurveNetwork, CubeReproducesReferenceLegsAndPseudoNorm) {
  const Solved s = solve(cubeMesh());
  expectProjectedLegs(s, 3.0 / 7.0, 1e-12);
  EXPECT_NEAR(s.network.legs.row(0).norm(), 0.699854, 1e-6);
  EXPECT_NEAR(pseudoNorm(s.mesh, s.topology, s.tensions, s.network.legs), 16.0 / 7.0, 1e-12);
}

TEST(CurveNetwork, OctahedronReproducesReferenceLegsAndPseudoNorm) {
  const Solved s = solve(octahedronMesh());
  expectProjectedLegs(s, 0.5, 1e-12);
  EXPECT_NEAR(pseudoNorm(s.mesh, s.topology, s.tensions, s.network.legs), 2.0, 1e-12);
}

TEST(CurveNetwork, SolvesSymmetricSystemToSmallResidual) {
  for (const PolygonMesh& mesh : {cubeMesh(), hexagonalPrismMesh(), openHexagonalPrismMesh(), torusMesh(12, 6)}) {
    const Solved s = solve(mesh);
    const NetworkSystem system = assembleNetworkSystem(s.mesh, s.topology, s.tensions);
    const Eigen::SparseMatrix<double> transposed = system.stiffness.transpose();
    EXPECT_EQ((system.stiffness - transposed).norm(), 0.0);
    Eigen::MatrixX3d x(2 * s.topology.vertexCount(), 3);
    for (int v = 0; v < s.topology.vertexCount(); ++v) {
      x.row(2 * v) = s.network.frames[v].ts.transpose();
      x.row(2 * v + 1) = s.network.frames[v].tc.transpose();
    }
    EXPECT_LE((system.stiffness * x - system.load).norm(), 1e-10 * system.load.norm());
    EXPECT_LE(s.network.relativeResidual, 1e-10);
    EXPECT_EQ(s.network.iterations, 1);
  }
}

TEST(CurveNetwork, SolutionMinimisesThePseudoNorm) {
  Tensions tensions;
  tensions.vertexAlpha[3] = 0.7;
  tensions.edgeBeta[{6, 7}] = 4.0;
  const Solved s = solve(hexagonalPrismMesh(), tensions);
  const double best = pseudoNorm(s.mesh, s.topology, s.tensions, s.network.legs);
  std::mt19937 random(7);
  std::normal_distribution<double> gauss(0.0, 1e-3);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Frame> frames = s.network.frames;
    for (Frame& f : frames) {
      f.ts += Eigen::Vector3d(gauss(random), gauss(random), gauss(random));
      f.tc += Eigen::Vector3d(gauss(random), gauss(random), gauss(random));
    }
    EXPECT_GT(pseudoNorm(s.mesh, s.topology, s.tensions, legsFromFrames(s.topology, frames)), best);
  }
}

TEST(CurveNetwork, LegsAtAVertexAreCoplanar) {
  const Solved s = solve(torusMesh(8, 5));
  for (int v = 0; v < s.topology.vertexCount(); ++v) {
    const Eigen::Vector3d n = s.network.frames[v].ts.cross(s.network.frames[v].tc).normalized();
    for (int he : s.topology.ringHalfEdges(v)) {
      EXPECT_LE(std::abs(n.dot(s.network.legs.row(he).transpose())), 1e-12 * s.network.legs.row(he).norm());
    }
  }
}

TEST(CurveNetwork, VertexTensionMonotonicallyShortensLegs) {
  // Property 9: cube vertex, alpha = 0, 0.5, 1, ..., 100, 1e4.
  const std::vector<double> alphas = {0.0, 0.5, 1.0, 2.0, 5.0, 10.0, 100.0, 1e4};
  std::vector<double> sums;
  for (double alpha : alphas) {
    Tensions t;
    t.vertexAlpha[0] = alpha;
    const Solved s = solve(cubeMesh(), t);
    double sum = 0.0;
    for (int he : s.topology.ringHalfEdges(0)) sum += s.network.legs.row(he).squaredNorm();
    sums.push_back(sum);
  }
  EXPECT_NEAR(sums[0], 1.469, 1e-3);
  EXPECT_NEAR(sums[1], 0.567, 1e-3);
  EXPECT_NEAR(sums[2], 0.298, 1e-3);
  EXPECT_NEAR(sums[6], 9.7e-5, 1e-6);
  EXPECT_LT(sums.back(), 1e-6);
  for (std::size_t i = 1; i < sums.size(); ++i) EXPECT_LE(sums[i], sums[i - 1] * (1.0 + 1e-12)) << alphas[i];
}

TEST(CurveNetwork, EdgeTensionMonotonicallyLowersEdgePseudoNorm) {
  const std::vector<double> betas = {0.0, 0.5, 1.0, 2.0, 5.0, 10.0, 100.0};
  std::vector<double> norms;
  for (double beta : betas) {
    Tensions t;
    t.edgeBeta[{0, 1}] = beta;
    const Solved s = solve(cubeMesh(), t);
    norms.push_back(edgePseudoNorm(s.mesh, s.topology, s.network.legs, s.topology.edge(s.topology.findHalfEdge(0, 1))));
  }
  EXPECT_NEAR(norms.front(), 1.382, 1e-3);
  EXPECT_NEAR(norms[2], 0.190, 1e-3);
  EXPECT_NEAR(norms.back(), 5.7e-5, 1e-6);
  for (std::size_t i = 1; i < norms.size(); ++i) EXPECT_LE(norms[i], norms[i - 1] * (1.0 + 1e-12)) << betas[i];
}

TEST(CurveNetwork, LargeEdgeTensionStraightensTheCurve) {
  // Property 10 (prototype values): cube, beta = 100: (0.6655, -0.0051, -0.0051) vs (2/3, 0, 0).
  Tensions t;
  t.edgeBeta[{0, 1}] = 100.0;
  const Solved s = solve(cubeMesh(), t);
  const Eigen::Vector3d leg = s.network.legs.row(s.topology.findHalfEdge(0, 1)).transpose();
  EXPECT_NEAR(leg.x(), 0.6655, 1e-4);
  EXPECT_NEAR(leg.y(), -0.0051, 1e-4);
  EXPECT_NEAR(leg.z(), -0.0051, 1e-4);
}

TEST(CurveNetwork, LegsAreInvariantUnderTensionScalingRingRotationAndReversal) {
  Tensions base;
  base.vertexAlpha[2] = 0.3;
  base.edgeBeta[{0, 6}] = 3.0;
  const Solved reference = solve(hexagonalPrismMesh(), base);
  auto expectSameLegs = [&](const Solved& other) {
    for (int he = 0; he < reference.topology.halfEdgeCount(); ++he) {
      const int a = reference.topology.from(he), b = reference.topology.to(he);
      const Eigen::Vector3d legOther = other.network.legs.row(other.topology.findHalfEdge(a, b)).transpose();
      EXPECT_LE((legOther - reference.network.legs.row(he).transpose()).norm(), 1e-12) << a << "->" << b;
    }
  };
  Tensions scaled = base;
  scaled.defaultBeta *= 2.5;
  scaled.vertexAlpha[2] *= 2.5;
  scaled.edgeBeta[{0, 6}] *= 2.5;
  expectSameLegs(solve(hexagonalPrismMesh(), scaled));

  PolygonMesh rotated = hexagonalPrismMesh();  // other face order and corner starts: other ring starts
  std::reverse(rotated.faces.begin(), rotated.faces.end());
  for (auto& f : rotated.faces) std::rotate(f.begin(), f.begin() + 1, f.end());
  expectSameLegs(solve(rotated, base));

  PolygonMesh reversed = hexagonalPrismMesh();  // reversed orientation of every ring
  for (auto& f : reversed.faces) std::reverse(f.begin(), f.end());
  expectSameLegs(solve(reversed, base));
}

TEST(CurveNetwork, CommutesWithRigidMotionAndUniformScaling) {
  const Eigen::Matrix3d rotation = testing::someRotation();
  const Eigen::Vector3d shift(0.3, -1.0, 2.0);
  const double scale = 1.7;
  const Solved a = solve(lShapedPrismMesh());
  const Solved b = solve(testing::transformed(lShapedPrismMesh(), rotation, scale, shift));
  const double diagonal = boundingBoxDiagonal(b.mesh.vertices);
  for (int he = 0; he < a.topology.halfEdgeCount(); ++he) {
    const Eigen::Vector3d expected = scale * rotation * a.network.legs.row(he).transpose();
    EXPECT_LE((b.network.legs.row(he).transpose() - expected).norm(), 1e-10 * diagonal);
  }
}

TEST(CurveNetwork, OpenBoundaryRimLegsAreOppositeWithReferenceLength) {
  const Solved s = solve(openHexagonalPrismMesh());
  for (int v = 6; v < 12; ++v) {
    const auto& ring = s.topology.ringHalfEdges(v);
    ASSERT_TRUE(s.topology.isBoundaryVertex(v));
    const Eigen::Vector3d first = s.network.legs.row(ring.front()).transpose();
    const Eigen::Vector3d last = s.network.legs.row(ring.back()).transpose();
    EXPECT_LE((first + last).norm(), 1e-12);
    EXPECT_NEAR(first.norm(), std::sqrt(3.0) / 5.0, 1e-6);
  }
}

TEST(CurveNetwork, UniformRimTensionDoesNotChangeTheOpenPrism) {
  Tensions rim;
  for (int k = 0; k < 6; ++k) rim.edgeBeta[{6 + k, 6 + (k + 1) % 6}] = 7.0;
  const Solved a = solve(openHexagonalPrismMesh());
  const Solved b = solve(openHexagonalPrismMesh(), rim);
  EXPECT_LE((a.network.legs - b.network.legs).norm(), 1e-12);
}

TEST(CurveNetwork, FrameOverridesAreKeptAndTheRestIsSolved) {
  const Solved free = solve(cubeMesh());
  CurveNetworkOptions options;
  options.frameOverrides[0] = free.network.frames[0];
  options.frameOverrides[0].ts *= 0.5;
  const CurveNetworkResult fixed = solveCurveNetwork(free.mesh, free.topology, free.tensions, options);
  ASSERT_TRUE(fixed.converged) << fixed.message;
  EXPECT_EQ(fixed.frames[0].ts, options.frameOverrides[0].ts);
  EXPECT_GT((fixed.frames[1].ts - free.network.frames[1].ts).norm() + (fixed.frames[1].tc - free.network.frames[1].tc).norm(), 1e-6);
}

TEST(CurveNetwork, ReportsCollapsedFrameInsteadOfReturningIt) {
  // Kuriyama 1996, sec. 4.2.1: alpha > 0 with beta = 0 on all but one edge collapses the frame to rank 1.
  Tensions t;
  t.vertexAlpha[0] = 10.0;
  const PolygonMesh mesh = cubeMesh();
  const MeshTopology topology = validatePolygonMesh(mesh);
  const auto& ring = topology.ringHalfEdges(0);
  for (std::size_t i = 1; i < ring.size(); ++i) t.edgeBeta[{0, topology.to(ring[i])}] = 0.0;
  const CurveNetworkResult result = solveCurveNetwork(mesh, topology, resolveTensions(t, topology));
  EXPECT_FALSE(result.converged);
  EXPECT_NE(result.message.find("vertex 0"), std::string::npos) << result.message;
}

}  // namespace
}  // namespace ffdkit::geometry::polyhedron
