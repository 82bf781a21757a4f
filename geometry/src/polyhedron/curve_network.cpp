#include "ffdkit/geometry/polyhedron/curve_network.h"

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>

namespace ffdkit::geometry::polyhedron {
namespace {

Eigen::RowVector2d jacobian(const MeshTopology& topology, int he) {
  const double theta = ringAngle(topology, he);
  return {std::sin(theta), std::cos(theta)};
}

}  // namespace

double ringAngle(const MeshTopology& topology, int he) {
  const int v = topology.from(he);
  const int n = topology.valence(v);
  const int i = topology.ringIndex(he);
  if (topology.isBoundaryVertex(v)) return std::numbers::pi * i / (n - 1);
  return 2.0 * std::numbers::pi * i / n;
}

NetworkSystem assembleNetworkSystem(const PolygonMesh& mesh, const MeshTopology& topology,
                                    const ResolvedTensions& tensions) {
  const int n = topology.vertexCount();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(topology.edgeCount()) * 16 + topology.halfEdgeCount() * 4);
  NetworkSystem system;
  system.load = Eigen::MatrixX3d::Zero(2 * n, 3);
  auto addBlock = [&](int r, int c, const Eigen::Matrix2d& block) {
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        if (block(a, b) != 0.0) triplets.emplace_back(2 * r + a, 2 * c + b, block(a, b));
      }
    }
  };
  for (int e = 0; e < topology.edgeCount(); ++e) {
    const int he = topology.edgeHalfEdge(e);
    const int back = topology.twin(he);
    const int v = topology.from(he), w = topology.to(he);
    const double beta = tensions.beta[e];
    const Eigen::RowVector2d jv = jacobian(topology, he), jw = jacobian(topology, back);
    // Hessian of beta (|A|^2 + A.B + |B|^2) / 3 with A = d - 2 t_v + t_w, B = -d + t_v - 2 t_w.
    addBlock(v, v, 2.0 * beta * jv.transpose() * jv);
    addBlock(w, w, 2.0 * beta * jw.transpose() * jw);
    const Eigen::Matrix2d coupling = -beta * jv.transpose() * jw;
    addBlock(v, w, coupling);
    addBlock(w, v, coupling.transpose());
    const Eigen::RowVector3d d = mesh.vertices.row(w) - mesh.vertices.row(v);
    system.load.middleRows<2>(2 * v) += beta * jv.transpose() * d;
    system.load.middleRows<2>(2 * w) -= beta * jw.transpose() * d;
  }
  for (int he = 0; he < topology.halfEdgeCount(); ++he) {
    const double alpha = tensions.alpha[topology.from(he)];
    if (alpha == 0.0) continue;
    const Eigen::RowVector2d j = jacobian(topology, he);
    addBlock(topology.from(he), topology.from(he), 2.0 * alpha * j.transpose() * j);
  }
  system.stiffness.resize(2 * n, 2 * n);
  system.stiffness.setFromTriplets(triplets.begin(), triplets.end());
  return system;
}

Eigen::MatrixX3d legsFromFrames(const MeshTopology& topology, const std::vector<Frame>& frames) {
  Eigen::MatrixX3d legs(topology.halfEdgeCount(), 3);
  for (int he = 0; he < topology.halfEdgeCount(); ++he) {
    const double theta = ringAngle(topology, he);
    const Frame& f = frames[topology.from(he)];
    legs.row(he) = (f.ts * std::sin(theta) + f.tc * std::cos(theta)).transpose();
  }
  return legs;
}

CurveNetworkResult solveCurveNetwork(const PolygonMesh& mesh, const MeshTopology& topology,
                                     const ResolvedTensions& tensions, const CurveNetworkOptions& options) {
  CurveNetworkResult result;
  const int n = topology.vertexCount();
  for (const auto& [v, frame] : options.frameOverrides) {
    if (v < 0 || v >= n || !frame.ts.allFinite() || !frame.tc.allFinite()) {
      result.message = "frame override of vertex " + std::to_string(v) + ": expected an existing vertex and finite vectors";
      return result;
    }
  }
  const NetworkSystem system = assembleNetworkSystem(mesh, topology, tensions);
  // Fixed frames are eliminated: their columns move to the right-hand side.
  std::vector<int> reduced(2 * n, -1);
  Eigen::MatrixX3d fixedValues = Eigen::MatrixX3d::Zero(2 * n, 3);
  int unknowns = 0;
  for (int v = 0; v < n; ++v) {
    const auto it = options.frameOverrides.find(v);
    if (it != options.frameOverrides.end()) {
      fixedValues.row(2 * v) = it->second.ts.transpose();
      fixedValues.row(2 * v + 1) = it->second.tc.transpose();
    } else {
      reduced[2 * v] = unknowns++;
      reduced[2 * v + 1] = unknowns++;
    }
  }
  Eigen::MatrixX3d solution = fixedValues;
  if (unknowns > 0) {
    std::vector<Eigen::Triplet<double>> triplets;
    Eigen::MatrixX3d rhs(unknowns, 3);
    for (int r = 0; r < 2 * n; ++r) {
      if (reduced[r] >= 0) rhs.row(reduced[r]) = system.load.row(r);
    }
    for (int c = 0; c < system.stiffness.outerSize(); ++c) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(system.stiffness, c); it; ++it) {
        const int r = static_cast<int>(it.row());
        if (reduced[r] < 0) continue;
        if (reduced[c] >= 0) {
          triplets.emplace_back(reduced[r], reduced[c], it.value());
        } else {
          rhs.row(reduced[r]) -= it.value() * fixedValues.row(c);
        }
      }
    }
    Eigen::SparseMatrix<double> k(unknowns, unknowns);
    k.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(k);
    result.iterations = 1;
    const double pivotFloor = 1e-13 * std::max(1.0, solver.info() == Eigen::Success
                                                        ? solver.vectorD().cwiseAbs().maxCoeff()
                                                        : 1.0);
    if (solver.info() != Eigen::Success || solver.vectorD().minCoeff() <= pivotFloor) {
      result.message = "curve network: the tension system is singular or indefinite "
                       "(expected alpha_v > 0 or edge tensions beta > 0 that pin both frame vectors at every vertex)";
      return result;
    }
    const Eigen::MatrixX3d x = solver.solve(rhs);
    const double scale = std::max(rhs.norm(), 1e-300);
    result.relativeResidual = (k * x - rhs).norm() / scale;
    if (!x.allFinite() || !(result.relativeResidual <= options.residualTolerance)) {
      result.message = "curve network: relative residual " + std::to_string(result.relativeResidual) +
                       " above tolerance " + std::to_string(options.residualTolerance);
      return result;
    }
    for (int r = 0; r < 2 * n; ++r) {
      if (reduced[r] >= 0) solution.row(r) = x.row(reduced[r]);
    }
  }
  result.frames.resize(n);
  for (int v = 0; v < n; ++v) {
    Frame& f = result.frames[v];
    f.ts = solution.row(2 * v).transpose();
    f.tc = solution.row(2 * v + 1).transpose();
    const double lengths = f.ts.norm() * f.tc.norm();
    if (!(lengths > 0.0) || !(f.ts.cross(f.tc).norm() > options.degenerateFrameTolerance * lengths)) {
      result.message = "vertex " + std::to_string(v) +
                       ": tangent frame collapsed (T^s and T^c parallel or zero); expected a plane of legs. "
                       "Check its tensions (e.g. alpha > 0 with beta = 0, Kuriyama 1996, sec. 4.3.4)";
      result.frames.clear();
      return result;
    }
  }
  result.legs = legsFromFrames(topology, result.frames);
  result.converged = true;
  return result;
}

double edgePseudoNorm(const PolygonMesh& mesh, const MeshTopology& topology, const Eigen::MatrixX3d& legs, int edge) {
  const int he = topology.edgeHalfEdge(edge);
  const Eigen::RowVector3d d = mesh.vertices.row(topology.to(he)) - mesh.vertices.row(topology.from(he));
  const Eigen::RowVector3d tv = legs.row(he), tw = legs.row(topology.twin(he));
  const Eigen::RowVector3d a = d + tw - 2.0 * tv;
  const Eigen::RowVector3d b = -d + tv - 2.0 * tw;
  return (a.squaredNorm() + a.dot(b) + b.squaredNorm()) / 3.0;
}

double pseudoNorm(const PolygonMesh& mesh, const MeshTopology& topology, const ResolvedTensions& tensions,
                  const Eigen::MatrixX3d& legs) {
  double sigma = 0.0;
  for (int e = 0; e < topology.edgeCount(); ++e) sigma += tensions.beta[e] * edgePseudoNorm(mesh, topology, legs, e);
  for (int he = 0; he < topology.halfEdgeCount(); ++he) {
    sigma += tensions.alpha[topology.from(he)] * legs.row(he).squaredNorm();
  }
  return sigma;
}

}  // namespace ffdkit::geometry::polyhedron
