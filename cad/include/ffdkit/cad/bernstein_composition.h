#pragma once

#include <Eigen/Core>

#include "ffdkit/ffd/lattice.h"

namespace ffdkit::cad {

/// A tensor-product Bezier patch, polynomial or rational: (degreeU+1) x (degreeV+1) poles,
/// row a + (degreeU+1)*b holding pole (a, b). A Bezier curve is a patch with degreeV = 0.
struct BezierPatch {
  int degreeU = 0;          ///< >= 0
  int degreeV = 0;          ///< >= 0 (0: a curve)
  Eigen::MatrixX3d poles;   ///< (degreeU+1)*(degreeV+1) x 3, Cartesian (not multiplied by the weights)
  Eigen::VectorXd weights;  ///< same count, all > 0; empty = polynomial (all weights 1)

  /// Number of poles, (degreeU+1)*(degreeV+1).
  Eigen::Index poleCount() const { return static_cast<Eigen::Index>(degreeU + 1) * (degreeV + 1); }
  /// The point at (s, t) in [0, 1]^2, by de Casteljau on the homogeneous poles.
  Eigen::Vector3d evaluate(double s, double t = 0.0) const;
};

/// A Bernstein lattice as one polynomial map of world space (Sederberg & Parry 1986, eq. 1):
///   X(q) = sum_ijk B_i^L(u) B_j^M(v) B_k^N(w) P_ijk,   (u, v, w) = toParameter * q,
/// with P_ijk the world control points. What composeBezierPatch() composes with.
struct BernsteinVolume {
  Eigen::Vector3i degrees{1, 1, 1};  ///< (L, M, N) = counts - 1
  Eigen::MatrixX3d points;           ///< (L+1)(M+1)(N+1) x 3 world control points, i fastest
  Eigen::Affine3d toParameter = Eigen::Affine3d::Identity();  ///< world -> (u, v, w)

  /// Sum of the degrees, L+M+N: a patch of degree (p, q) composes to degree (D p, D q).
  int totalDegree() const { return degrees.sum(); }
  /// X(q), by de Casteljau along each axis (a second evaluation path, for checks).
  Eigen::Vector3d evaluate(const Eigen::Vector3d& world) const;

  /// The map of a lattice whose three axes are Bernstein and whose rest map is affine
  /// (makeBoxLattice): control points carried to the world by the lattice's frame.
  /// @throws CadError if an axis is not Bernstein or the rest lattice is not affine.
  static BernsteinVolume fromLattice(const ffd::Lattice& lattice);
  /// The map of one cell of a box lattice with clamped B-spline (or Bernstein) axes: on the cell,
  /// the FFD is one trivariate polynomial of degrees (p_u, p_v, p_w), here in Bernstein form over
  /// the cell (Bezier extraction of each axis's basis functions), with `toParameter` mapping the
  /// cell's parameter box onto [0, 1]^3. Beyond the lattice's end cells it is their polynomial
  /// continued (what the Extrapolate policy evaluates).
  /// @throws CadError if an axis is periodic, the rest lattice is not affine or `cell` is out of range.
  static BernsteinVolume fromLatticeCell(const ffd::Lattice& lattice, const Eigen::Vector3i& cell);
};

/// The exact composition X(S(s, t)) of a Bernstein volume with a (rational) Bezier patch, as a
/// (rational) Bezier patch of degree (D p, D q), D = L+M+N (DeRose, Goldman, Hagen & Mann 1993,
/// "Functional composition algorithms via blossoming": the composition of polynomials in the
/// Bernstein basis). With S = Sh / W (homogeneous numerator Sh, weight W), (u, v, w) = Uh / W
/// with Uh affine in Sh, and
///   X(S) = sum_ijk P_ijk C(L,i) Uh^i (W-Uh)^(L-i) C(M,j) ... / W^D,
/// every product formed exactly in the scaled Bernstein basis (coefficient times binomial, where a
/// product is a convolution of the coefficient arrays). A polynomial patch gives a polynomial one.
/// Cost: O((D p)^2 (D q)^2) per lattice row pair; a bicubic patch in a 3 x 3 x 3 lattice takes
/// microseconds.
/// @throws CadError if a weight is not > 0 or a pole is not finite.
BezierPatch composeBezierPatch(const BernsteinVolume& volume, const BezierPatch& patch);

}  // namespace ffdkit::cad
