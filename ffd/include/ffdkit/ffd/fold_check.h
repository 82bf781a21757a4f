#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/lattice.h"

namespace ffdkit::ffd {

/// det J of the lattice map X(u,v,w) (Kuriyama 1996, eq. (6.1)) on one cell, as a trivariate
/// polynomial in Bernstein form: on a cell each coordinate of X is a tensor polynomial of degree
/// (p, q, r); its partial derivatives have degrees (p-1, q, r), (p, q-1, r), (p, q, r-1), and
/// det [X_u, X_v, X_w] = X_u . (X_v x X_w) has degree (3p-1, 3q-1, 3r-1). Its Bernstein
/// coefficients bound it (convex hull property: min coefficient <= det J <= max coefficient on
/// the cell) and equal it at the cell's corners (Farin, Curves and Surfaces for CAGD, sec. 15.3).
/// Units: derivatives with respect to the lattice parameters (u,v,w), lattice-local coordinates.
struct JacobianDeterminantPatch {
  std::array<int, 3> degrees{};  ///< (3p-1, 3q-1, 3r-1)
  Eigen::Vector3d parameterMin = Eigen::Vector3d::Zero();  ///< the cell's parameter box
  Eigen::Vector3d parameterMax = Eigen::Vector3d::Ones();  ///< upper corner of the cell's parameter box
  /// (d0+1)(d1+1)(d2+1) Bernstein coefficients, index i + (d0+1) (j + (d1+1) k).
  Eigen::VectorXd coefficients;

  /// det(dX/d(u,v,w)) at uvw (inside the cell's box; outside, the cell's polynomial continued).
  double value(const Eigen::Vector3d& uvw) const;
};

/// The largest axis degree the fold-over bound handles: det J then has degree 29 per axis (27,000
/// Bernstein coefficients per cell, 64,000 for a rational cell's det[H_u, H_v, H_w, H]).
constexpr int kFoldCheckMaxDegree = 10;

/// The det J patch of cell (cu, cv, cw) (cells per axis: Lattice::axis(a).cellCount()), of the
/// polynomial map of the control points (a rational lattice's weights are not part of it;
/// checkFolding bounds a rational lattice's det J), by the general product of nets.
/// @throws LatticeError on a cell out of range, or an axis of degree above kFoldCheckMaxDegree.
JacobianDeterminantPatch jacobianDeterminantPatch(const Lattice& lattice, const std::array<int, 3>& cell);

/// Verdict on one lattice cell.
enum class CellFolding : std::uint8_t {
  Positive,  ///< certified: det J has the rest lattice's sign everywhere on the closed cell
  Folds,     ///< a point was found where det J is zero or of the opposite sign (the space folds)
  Unknown    ///< neither, after subdividing to FoldCheckOptions::maxDepth
};

/// Options of checkFolding.
struct FoldCheckOptions {
  /// Halvings of each cell (along all three axes at once) where the coefficients' bound is
  /// inconclusive: a cell is split into at most 8^maxDepth boxes.
  int maxDepth = 4;
  /// Compute every cell's coefficients one cell at a time by the general product of nets (the
  /// path of any degrees, jacobianDeterminantPatch's) instead of the batched products of lattices
  /// whose axes share a degree 1 to 3. Slower; the coefficients agree to rounding (so do the
  /// verdicts, unless a coefficient is within rounding of 0): the reference the fast path is
  /// tested against.
  bool referenceExpansion = false;
};

/// The fold-over verdict of every cell of a lattice.
struct FoldCheckResult {
  std::array<int, 3> cellCounts{};  ///< cells along u, v, w
  /// One verdict per cell, flat index cu + cellCounts[0] (cv + cellCounts[1] cw).
  std::vector<CellFolding> cells;
  /// Per cell, the smallest Bernstein coefficient of det J times the rest orientation's sign
  /// (a lower bound of sign * det J on the cell; > 0 means certified Positive at once; for a
  /// rational lattice's cell with unequal weights, that of G scaled by a weight^-4, see checkFolding).
  std::vector<double> lowerBound;
  /// Per cell, a parameter point where sign * det J <= 0 (Folds cells; NaN otherwise).
  std::vector<Eigen::Vector3d> witness;
  ///@{
  /// Cells certified Positive, found to fold, and left Unknown.
  Eigen::Index positiveCount = 0, foldsCount = 0, unknownCount = 0;
  ///@}
  /// Sign of det J of the rest lattice at the centre of its parameter box (+1 or -1): folding is
  /// measured against the rest lattice's orientation (a mirrored frame is not a fold).
  int orientation = 1;

  /// True when every cell is certified Positive (no fold anywhere in the lattice).
  bool certifiedPositive() const { return foldsCount == 0 && unknownCount == 0; }
};

/// A certified fold-over bound of the lattice map's current control points: per cell, the
/// Bernstein coefficients of det J (jacobianDeterminantPatch); min > 0 certifies Positive, a
/// corner coefficient <= 0 (an exact value of det J) proves Folds; otherwise the patch is split
/// at its midpoints by de Casteljau and each part is checked again, down to options.maxDepth,
/// and what is still inconclusive is Unknown. Cost: one product of Bernstein nets per cell
/// (degree (3p-1)^3: 729 coefficients for cubic axes) plus any subdivisions.
/// Rational lattices (Lamousin & Waggenspack 1994): with H = (sum B w P, sum B w) = (N, D) the
/// homogeneous map and X = N / D, det J = det[H_u, H_v, H_w, H] / D^4 (subtract D_a / D times
/// the column H from each derivative column: H_a - (D_a / D) H = D (X_a, 0)). The weights are > 0,
/// so D > 0 and det J has the sign of the polynomial G = det[H_u, H_v, H_w, H] of degree
/// (4p-1, 4q-1, 4r-1) (1331 coefficients for cubic axes), whose Bernstein coefficients are bounded
/// and subdivided exactly as det J's are; lowerBound is min G / D^4 with D the largest window
/// weight when min G > 0, the smallest otherwise. A cell whose window has equal weights is a
/// polynomial map, and takes det J's own bound.
/// Axes of one degree 1 to 3 compute their cells' coefficients several at a time (one SIMD lane
/// per cell); cells run in parallel (OpenMP), with the same verdicts and bounds whatever the
/// thread count.
/// @throws LatticeError on maxDepth outside [0, 10], or an axis of degree above
///         kFoldCheckMaxDegree (a Bernstein axis of more than 11 control points): "checkFolding:
///         axis 0 has degree 11; the fold-over bound handles degrees up to 10".
FoldCheckResult checkFolding(const Lattice& lattice, const FoldCheckOptions& options = {});

}  // namespace ffdkit::ffd
