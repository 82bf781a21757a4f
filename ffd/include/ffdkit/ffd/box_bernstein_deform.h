#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/ffd/lattice.h"

namespace ffdkit::ffd {

/// N x 3 points, one per row, with any row and column strides (in doubles): a C-ordered numpy
/// (N, 3) array (strides 3, 1), a Fortran-ordered one or a column-major Eigen::MatrixX3d
/// (strides 1, N), a slice of either. Map such storage with Eigen::Map<..., Eigen::Stride<...>>.
using PointRows = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using PointRowsStride = Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>;
using StridedPoints = Eigen::Ref<const PointRows, 0, PointRowsStride>;
using StridedPointsOut = Eigen::Ref<PointRows, 0, PointRowsStride>;

/// A Bernstein lattice on an oriented box, given by its control-point displacements: the FFD of
/// Sederberg & Parry 1986 (and PyGeM's `FFD`) in the form it takes when the rest lattice is the
/// regular grid of a parallelepiped.
struct BoxBernsteinLattice {
  Eigen::Vector3i counts{2, 2, 2};  ///< (l, m, n) control points per axis, each in [2, 33].
  /// world = frame * s for box coordinates s in [0, 1]^3: frame * 0 is the box corner of control
  /// point (0, 0, 0), the columns of frame.linear() are the box's edge vectors (PyGeM: R diag(L)).
  Eigen::Affine3d frame = Eigen::Affine3d::Identity();
  /// l*m*n x 3: the displacement of control point ijk (row i + l*(j + m*k)) from its rest place
  /// (i/(l-1), j/(m-1), k/(n-1)), in box coordinates (fractions of each edge). Empty: all zero.
  Eigen::MatrixX3d displacements;
};

/// The same deformation as a general Lattice: Bernstein bases on the box, control points at
/// their rest places plus the displacements (what embed() + Deformer::deform() evaluate, and
/// what boxBernsteinDeform() equals inside the box). @throws LatticeError as makeBoxLattice.
Lattice toLattice(const BoxBernsteinLattice& box);

/// Options of boxBernsteinDeform().
struct BoxBernsteinDeformOptions {
  /// Box coordinates within this distance of [0, 1] count as inside (so that the rounding of the
  /// world -> box map never decides whether a point on a face moves). >= 0.
  double faceTolerance = 1e-12;
  /// Run on all OpenMP threads (from 16,384 points up) or on the calling thread only.
  bool parallel = true;
};

/// What boxBernsteinDeform() did.
struct BoxBernsteinDeformResult {
  Eigen::Index insidePoints = 0;  ///< points inside the box (to faceTolerance), the ones moved
};

/// Free-form deformation of points by a Bernstein lattice on a box, in one pass with nothing
/// stored per point: for each point q (world),
///   s   = frame^-1 q                                         (box coordinates)
///   out = q + frame.linear() * sum_ijk B_i^(l-1)(s_x) B_j^(m-1)(s_y) B_k^(n-1)(s_z) d_ijk
/// if s lies in [0, 1]^3 (to faceTolerance), else out = q bit for bit (NaN coordinates count as
/// outside). With the rest lattice X_ijk = (i/(l-1), j/(m-1), k/(n-1)) the Bernstein sum of
/// the rest points is s itself (linear precision), so this is Sederberg & Parry 1986, eq. 1
/// (X_ffd = sum_ijk B_i B_j B_k P_ijk with P_ijk = X_ijk + d_ijk) mapped back to the world; it
/// equals embed() + Deformer::deform() on the same box lattice with the Identity outside policy.
/// B_i^n(t) = C(n,i) t^i (1-t)^(n-i) (bernsteinBasis()) is evaluated with de Casteljau's
/// triangle; the sum runs over the (j, k) rows of the lattice that hold a non-zero displacement
/// only (PyGeM lattices are mostly zero), contracting i first.
///
/// Cost: one pass over the points, reading q and writing out once each (no embedding, no
/// intermediate arrays); OpenMP over chunks of points, so that the first touch of a fresh `out`
/// happens in the parallel loop.
///
/// @param points  N x 3 world points, one per row (any strides).
/// @param out     N x 3, written; may be `points` itself (same data and strides: in place), must
///                not overlap it otherwise.
/// @throws LatticeError if a count is outside [2, 33], displacements is neither empty nor
///         l*m*n x 3, a displacement or the frame is not finite, the frame is singular,
///         faceTolerance is negative or not finite, or out has another number of rows.
BoxBernsteinDeformResult boxBernsteinDeform(const BoxBernsteinLattice& lattice, const StridedPoints& points,
                                            StridedPointsOut out, const BoxBernsteinDeformOptions& options = {});

}  // namespace ffdkit::ffd
