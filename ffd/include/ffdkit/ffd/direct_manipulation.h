#pragma once

#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/lattice.h"

namespace ffdkit::ffd {

/// One non-zero term of X(u,v,w) = sum_ijk B_i(u) B_j(v) B_k(w) P_ijk (Kuriyama 1996, eq. (6.1)):
/// the control point's flat index and its tensor-product weight B_i(u) B_j(v) B_k(w).
struct BasisWeight {
  Eigen::Index point = 0;  ///< flat index of the control point.
  double weight = 0.0;  ///< its basis weight B_ijk(u,v,w) at the point (rational lattice: w B / sum w B).
};

/// The non-zero weights of the lattice's basis at parameters `uvw`, (degree_u+1)(degree_v+1)
/// (degree_w+1) of them, in the order Lattice::evaluate sums them (periodic axes wrap; outside
/// the box the end pieces extend). evaluate(uvw) == sum weight * P[point]; on a rational lattice
/// the weights are R_ijk = w_ijk B_ijk / sum w B (Lamousin & Waggenspack 1994), so that this holds
/// and direct manipulation moves the weighted shape exactly (its weights held fixed).
std::vector<BasisWeight> basisWeights(const Lattice& lattice, const Eigen::Vector3d& uvw);

/// Direct manipulation of an FFD (Hsu, Hughes & Kaufman 1992, "Direct manipulation of
/// free-form deformations", eqs. (4)-(6)): the smallest change of the control points (least
/// squares over all of them) that moves the deformed points at parameters `uvw` (k x 3) by
/// `displacements` (k x 3, lattice-local: a world displacement d is frame().linear()^-1 d).
/// With B the k x N matrix of basis weights, dP = B^+ D = B^T (B B^T)^+ D. Independent
/// constraints are met exactly; dependent ones (two constraints at one parameter) in the least
/// squares sense. The lattice itself is not changed: add the result to its control points.
/// @return pointCount x 3.
/// @throws LatticeError for sizes that differ or non-finite input.
Eigen::MatrixX3d leastNormControlChange(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& uvw,
                                        const Eigen::Ref<const Eigen::MatrixX3d>& displacements);

}  // namespace ffdkit::ffd
