// Internal to ffd/: the enclosed volume of an FFD'd closed surface as a cubic polynomial in the
// control displacements, precomputed once so that Keep Volume's Newton steps cost O(lattice).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/closed_surface.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"

namespace ffdkit::ffd::detail {

/// The volume a closed surface over FFD'd points encloses, as a polynomial in the WORLD control
/// displacements D_i = F.linear() (P_i - Pbar_i). Each deformed vertex is affine in them,
/// x'_v = x_v + sum_i w_vi D_i with w_vi = s_v B_i(u_v) (deformer.h; Sederberg & Parry 1986,
/// eq. (1)), and V = sum over triangles det[x'_a, x'_b, x'_c] / 6 expands into
///
///   V(D) = V0 + sum_i R_i . D_i + sum_{j<k} q_jk . (D_j x D_k) + sum_{i<j<k} K_ijk det[D_i, D_j, D_k].
///
/// With y_v = x_v - origin, d_x = w_x - w_v (the weights of a neighbour x minus v's) and the
/// pairs (b, c) of the triangles (v, b, c) around v (ClosedSurface::pairs):
///   g_v  = sum (y_b - y_v) x (y_c - y_v) / 6          the rest gradient at v,
///   A_v  = sum (d_b ^ d_c) / 6                         (the wedge: j<k entry d_bj d_ck - d_bk d_cj),
///   V0 = sum_v y_v . g_v / 3,  R_i = sum_v w_vi g_v,  q_jk = sum_v y_v A_v[jk],  K_ijk = sum_v w_vi A_v[jk].
/// (The differences are exact rewrites on a closed surface, where the b's and c's around v are
/// the same vertices, and keep the digits the ring sums would cancel.) K is fully antisymmetric
/// (each triangle contributes through its three rotations: the alternating sum), so only i<j<k is
/// kept: 41,664 coefficients for the 64 control points of a cubic cell.
///
/// Precompute: per vertex one ring wedge (about 2,000 multiply-adds per neighbour for a cubic
/// cell) and one rank-one update of K (41,664), vertices in batches of 8 so that K streams
/// through the cache once per batch. Evaluate: O(a^3 / 6) for the a control points that move
/// some vertex, independent of the number of vertices.
class VolumePolynomial {
 public:
  /// The most control points that may move the surface (K grows as a^3 / 6: 341,376 values, 2.7 MB
  /// at 128; a 4x4x4 cubic lattice has 64, a 5x5x5 one 125).
  static constexpr Eigen::Index kMaxActiveControls = 128;

  /// Builds the coefficients, or nullopt when more than kMaxActiveControls control points move
  /// some vertex of the surface.
  /// @param lattice   the lattice `embedding` was built for (its bases and frame).
  /// @param points    #points x 3 rest WORLD points, the surface's vertices (#points = surface.vertexCount()).
  /// @param origin    the volume is measured about it (translation invariant; keeps digits).
  static std::optional<VolumePolynomial> build(const Lattice& lattice, const Embedding& embedding,
                                               const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                               const Eigen::Vector3d& origin, const ClosedSurface& surface);

  /// V(D) for displacements D (#controlPoints x 3, WORLD), and dV/dD into `gradient` (same shape).
  double evaluate(const Eigen::Ref<const Eigen::MatrixX3d>& displacement, Eigen::MatrixX3d& gradient) const;

  /// The control points that move some vertex (flat Lattice::index, ascending).
  const std::vector<Eigen::Index>& activeControls() const { return active_; }

 private:
  using Rows3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  std::vector<Eigen::Index> active_;
  double constant_ = 0.0;
  Rows3 linear_;          // a x 3: R_i
  Rows3 quadratic_;       // a(a-1)/2 x 3: q_jk at k(k-1)/2 + j
  std::vector<double> cubic_;  // a(a-1)(a-2)/6: K_ijk at k(k-1)(k-2)/6 + j(j-1)/2 + i
};

}  // namespace ffdkit::ffd::detail
