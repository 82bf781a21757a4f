#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"

namespace ffdkit::ffd {

/// The FFD of each embedded point as a weighted sum of control-point displacements, pruned to
/// the k largest weights. Deformer writes  out = Q + s * F.linear() * sum_ijk B_i(u) B_j(v) B_k(w) (P_ijk - Pbar_ijk)
/// (Kuriyama 1996, eq. (6.1) with the partition of unity, see deformer.h): for a fixed embedding
/// the output is linear in the control points, with weight w_ijk = s * B_i(u) B_j(v) B_k(w) on the
/// world displacement F.linear() (P_ijk - Pbar_ijk). That is a linear-blend skin whose joints are
/// the control points (translation only); glTF export prunes it to 4 or 8 joints per vertex.
struct ControlWeights {
  int k = 0;  ///< weights kept per point
  /// #points x k flat control-point indices (Lattice::index), by decreasing weight; -1 pads a
  /// point with fewer than k non-zero weights (a point left unchanged has none).
  Eigen::Matrix<std::int32_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> indices;
  /// #points x k weights s * B_ijk matching `indices` (0 where the index is -1). Negative only
  /// for Extrapolate outside points (Bernstein / B-spline pieces continued past the box).
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> weights;
  /// #points: s, the sum of ALL the point's weights (kept or not): 1 for inside and Extrapolate
  /// points (partition of unity), the blend weight for ClampEdge / Falloff outside points, 0 for
  /// points left unchanged (Identity outside, Failed, beyond the Falloff distance).
  Eigen::VectorXd total;
  /// #points: sum of |w| over the weights NOT kept (0 when k covers the whole window).
  Eigen::VectorXd dropped;
};

/// The k largest weights (by value) of every point of `embedding` in `lattice`'s basis: the
/// window of (degree_u+1)(degree_v+1)(degree_w+1) products B_i(u) B_j(v) B_k(w) of the point's
/// cell, times its blend weight. Memory: 12 k + 16 bytes per point; the window itself is never stored.
/// @param lattice the lattice the embedding was built for (same counts; its basis and knots).
/// @param k       >= 1.
/// A rational lattice (Lamousin & Waggenspack 1994) gives s R_ijk = s w B / sum w B, exact while
/// its weights equal its rest weights.
/// @throws LatticeError if k < 1, the embedding is stale for `lattice` (Embedding::checkLattice),
///   or the lattice's weights differ from its rest weights.
ControlWeights largestControlWeights(const Lattice& lattice, const Embedding& embedding, int k);

/// The weight of one control point for every point of `embedding`: s * B_i(u) B_j(v) B_k(w) for
/// control point `flat` = Lattice::index(i, j, k) (summed over the window positions a periodic
/// axis wraps onto it), 0 for points outside its support and for points left unchanged. Since
/// the output is linear in the control points (see ControlWeights), moving that control point by
/// dP (lattice-local) moves point p by weight[p] * F.linear() dP, and nothing else changes: the
/// motion of a gesture that drags one control point (the view's vertex normals follow it without
/// recomputing them, app/render/src/gesture_normals.h). Memory: 8 bytes per point.
/// On a rational lattice the weight is s R_ijk = s w_ijk B_ijk / sum w B (Lamousin & Waggenspack
/// 1994), the derivative of the output with respect to that control point, its weights held fixed.
/// @throws LatticeError if `flat` is out of range or the embedding is stale for `lattice`.
Eigen::VectorXd controlPointWeights(const Lattice& lattice, const Embedding& embedding, Eigen::Index flat);

/// controlPointWeights() into `weights`, resized to the embedding's point count only when its size
/// differs: a caller that asks again (the first step of every drag) reuses its memory instead of
/// faulting in 8 fresh bytes per point. Every entry is written (the same bits as the returning form).
/// @throws LatticeError as controlPointWeights(), before `weights` is touched.
void controlPointWeights(const Lattice& lattice, const Embedding& embedding, Eigen::Index flat,
                         Eigen::VectorXd& weights);

}  // namespace ffdkit::ffd
