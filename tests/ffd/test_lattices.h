#pragma once

// Random lattices and points shared by the ffd tests.

#include <random>

#include <Eigen/Geometry>

#include "ffdkit/ffd/lattice.h"

namespace ffdkit::ffd::testing {

inline Eigen::Affine3d randomFrame(std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::Affine3d frame = Eigen::Affine3d::Identity();
  frame.translate(Eigen::Vector3d(3 * U(rng), 3 * U(rng), 3 * U(rng)));
  frame.rotate(Eigen::AngleAxisd(3.0 * U(rng), Eigen::Vector3d(U(rng), U(rng), 1.0).normalized()));
  frame.scale(Eigen::Vector3d(1.5 + U(rng), 1.5 + U(rng), 1.5 + U(rng)));
  return frame;
}

inline AxisBasis randomBasis(int count, std::mt19937& rng) {
  const int degree = std::uniform_int_distribution<int>(1, count - 1)(rng);
  switch (std::uniform_int_distribution<int>(0, 2)(rng)) {
    case 0:
      return AxisBasis::bernstein();
    case 1:
      return AxisBasis::bspline(degree);
    default: {
      // Clamped non-uniform knots on [0, 1].
      std::uniform_real_distribution<double> U(0.3, 1.0);
      Eigen::VectorXd knots(count + degree + 1);
      knots.head(degree + 1).setZero();
      knots.tail(degree + 1).setOnes();
      double acc = 0.0;
      Eigen::VectorXd gaps(count - degree);
      for (int i = 0; i < gaps.size(); ++i) gaps[i] = U(rng);
      gaps /= gaps.sum();
      for (int i = 0; i + 1 < gaps.size(); ++i) knots[degree + 1 + i] = (acc += gaps[i]);
      return AxisBasis::bsplineWithKnots(degree, knots);
    }
  }
}

/// A box lattice with random counts (2..6), random non-periodic bases and a random frame; with
/// `jitter` > 0 its rest points are moved by up to jitter * (box size / count) in each coordinate,
/// which makes a user-shaped (non-affine) rest lattice.
inline Lattice randomLattice(std::mt19937& rng, double jitter, int maxCount = 6) {
  std::uniform_int_distribution<int> countDist(2, maxCount);
  BoxLatticeOptions options;
  options.capDegreeToCount = false;
  for (int a = 0; a < 3; ++a) {
    options.counts[a] = countDist(rng);
    options.bases[a] = randomBasis(options.counts[a], rng);
  }
  options.boxMin = Eigen::Vector3d(-1.0, -0.5, 0.0);
  options.boxMax = Eigen::Vector3d(1.0, 1.5, 0.5);
  options.frame = randomFrame(rng);
  Lattice lattice = makeBoxLattice(options);
  if (jitter > 0.0) {
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    Eigen::MatrixX3d rest = lattice.restPoints();
    const Eigen::Vector3d size = options.boxMax - options.boxMin;
    for (Eigen::Index r = 0; r < rest.rows(); ++r)
      for (int c = 0; c < 3; ++c) rest(r, c) += jitter * size[c] / options.counts[c] * U(rng);
    lattice.setRestPoints(rest);
  }
  return lattice;
}

/// n points drawn uniformly from the unit box [0, 1]^3, #n x 3 (reproducible per seed).
inline Eigen::MatrixX3d uniformPointsInUnitBox(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Eigen::MatrixX3d Q(n, 3);
  for (Eigen::Index r = 0; r < n; ++r) Q.row(r) << U(rng), U(rng), U(rng);
  return Q;
}

/// Random parameters in the lattice's parameter box, #n x 3.
inline Eigen::MatrixX3d randomParameters(const Lattice& lattice, Eigen::Index n, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Eigen::MatrixX3d uvw(n, 3);
  const Eigen::Vector3d lo = lattice.parameterMin();
  const Eigen::Vector3d hi = lattice.parameterMax();
  for (Eigen::Index r = 0; r < n; ++r)
    for (int a = 0; a < 3; ++a) uvw(r, a) = lo[a] + (hi[a] - lo[a]) * U(rng);
  return uvw;
}

/// World points frame * Xbar(uvw), one per row of uvw: points known to be inside the rest lattice.
inline Eigen::MatrixX3d restImages(const Lattice& lattice, const Eigen::MatrixX3d& uvw) {
  Eigen::MatrixX3d Q(uvw.rows(), 3);
  for (Eigen::Index r = 0; r < uvw.rows(); ++r) {
    Q.row(r) = (lattice.frame() * lattice.evaluateRest(uvw.row(r).transpose())).transpose();
  }
  return Q;
}

}  // namespace ffdkit::ffd::testing
