#pragma once

#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/curvenet/curve_network.h"

namespace ffdkit::geometry::curvenet {

/// Options of the affine-matrix fairing (Kuriyama 1996, sec. 5.2.1).
struct FairingOptions {
  int quadraturePoints = 16;  ///< Gauss-Legendre points per direction on [0, 1]^2 (>= 4)
};

/// Per run: the thin-plate energy E + E-bar of the normalised sub-surfaces on both sides at
/// c = 0 and at the optimum.
struct RunFairing {
  int run = -1;  ///< the run's index in the network
  double energyBefore = 0.0;  ///< energy at c = 0
  double energyAfter = 0.0;  ///< energy at the optimum
  int sides = 0;  ///< faces (0..2) whose sub-surface entered the energy
};

/// What fairRunSweeps did: the energy per run and in total.
struct FairingResult {
  std::vector<RunFairing> runs;  ///< one entry per run
  double totalBefore = 0.0;  ///< sum of the energies at c = 0
  double totalAfter = 0.0;  ///< sum of the energies at the optimum
};

/// Switches every run with two transversals to the affine-matrix sweep of Kuriyama 1996, sec. 5.2.1
/// and chooses its 18 coefficients c-+ (shared by the faces on both sides, so G^n is kept) by
/// minimising E_i + E-bar_i (sec. 5.2.1): three 6 x 6 systems with one shared matrix, solved with a
/// complete orthogonal decomposition (minimum norm when a transversal coordinate vanishes).
/// Runs seen by no face, or ending at a free end, keep the parallel sweep.
/// The energy uses the face's own adjacent side lengths Delta_-+ as in S~_i (A8: for the
/// energy only). Quadrature: Gauss-Legendre on [0, 1]^2 (an approximation across knots).
/// @throws std::invalid_argument if options.quadraturePoints < 4.
FairingResult fairRunSweeps(CurveNetwork& network, const FairingOptions& options = {});

/// E + E-bar of run `run` for given coefficients (what fairRunSweeps minimises).
double runFairingEnergy(const CurveNetwork& network, int run, const Eigen::Matrix3d& cStart,
                        const Eigen::Matrix3d& cEnd, const FairingOptions& options = {});

}  // namespace ffdkit::geometry::curvenet
