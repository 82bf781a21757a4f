#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "ffdkit/ffd/closed_surface.h"
#include "ffdkit/ffd/deformer.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"

namespace ffdkit::ffd {

/// Which control-point coordinates a constraint solve may change: #controlPoints x 3 (row =
/// Lattice::index, column = lattice-LOCAL axis), true = free. Default: all free.
using ControlMask = Eigen::Matrix<bool, Eigen::Dynamic, 3, Eigen::RowMajor>;

namespace detail {
class VolumePolynomial;
}

/// How a kept volume is evaluated in each Newton step of ShapeConstraints::solve.
enum class VolumeEvaluation {
  /// Polynomial when at most 128 control points move the surface (a 4x4x4 cubic lattice moves
  /// 64, a 5x5x5 one 125), else PerVertex.
  Automatic,
  /// The volume as a cubic polynomial in the control displacements, precomputed by keepVolume()
  /// (one pass over the vertices: about 54,000 multiply-adds per vertex for a cubic cell, a few
  /// seconds for 10^6 vertices); each Newton step then costs O(a^3/6) for the a control points
  /// that move the surface, whatever the number of vertices: the choice for a drag.
  /// @throws ConstraintError from keepVolume() when more than 128 control points move the surface.
  Polynomial,
  /// No precompute: each Newton step deforms the points and sums over the triangles (O(vertices)):
  /// the choice for a single solve (the CLI's deform, PyGeM's VFFD).
  PerVertex
};

/// How often ShapeConstraints::solve computes the rows of its Jacobian that need a pass over the
/// points (the centroid's, and the volume's when it is summed per vertex; linear rows are
/// constant and the volume polynomial's gradient comes with its value).
enum class JacobianUpdate {
  /// At every Newton step: the solve ends at the Lagrange point, the least-norm change.
  EveryStep,
  /// At the first step, then kept (a chord method) while each step cuts the largest scaled
  /// residual at least tenfold; a step that does not computes them again. Each later step costs
  /// one deformation of the points and one pass over the triangles instead of also a pass over
  /// the vertices' gradients and an adjoint pass. The constraints are met to the same tolerance,
  /// and the change is the least-norm one along the constraints' gradients at the start, which
  /// differs from the Lagrange point's by about |change|^2 / the lattice's size: for a drag step
  /// (ShapeGuard's Keep Centre), where the change is small.
  FirstStep
};

/// Options of ShapeConstraints::solve.
struct ShapeSolveOptions {
  /// Stop when every constraint's residual is <= tolerance times its scale: |V - V*| / |V*| for
  /// the volume, |a . x' - b| / (sum |a_j x'_j| + |b|) for a linear row, the same with the
  /// surface's size for the centroid.
  double tolerance = 1e-12;
  /// With a volume or centroid: also stop only when the last step changed the control change by
  /// <= stationarity times its norm (the Lagrange condition: the change is parallel to the
  /// constraints' gradients; it converges linearly, the constraint residual quadratically), or
  /// by <= 1000 machine epsilons times the lattice's rest size (a change at the rounding level of
  /// the control coordinates, e.g. after a drag that barely changed the volume).
  double stationarity = 1e-10;
  int maxIterations = 40;  ///< Newton steps before giving up (ConstraintError).
  /// When the rows of the Jacobian that need a pass over the points are computed.
  JacobianUpdate jacobian = JacobianUpdate::EveryStep;
};

/// What ShapeConstraints::solve did.
struct ShapeSolveResult {
  Eigen::MatrixX3d change;    ///< #controlPoints x 3 lattice-local: add to lattice.controlPoints().
  int iterations = 0;         ///< Newton steps taken (0: the constraints already held).
  double volume = 0.0;        ///< enclosed volume after the change (world), when a volume is kept
  double volumeRelativeError = 0.0;  ///< |V - V*| / |V*| after the change (0 without a volume)
  double largestRelativeResidual = 0.0;  ///< the largest scaled residual over all constraints
  double lastStep = 0.0;  ///< |change after the last step - change before it| / |change|
  /// Passes over the points that computed the Jacobian's per-vertex rows (centroid, volume summed
  /// per vertex): `iterations` with JacobianUpdate::EveryStep, usually 1 with FirstStep.
  int jacobianPasses = 0;
};

/// Constraints on the deformed shape of one set of points embedded in one lattice, and the
/// smallest control change (least norm over the free control coordinates, lattice-local) that
/// meets them: the direct-manipulation machinery (Hsu, Hughes & Kaufman 1992, eqs. (4)-(6))
/// with general constraints.
/// - linear:     A x' = b over the deformed WORLD points x' (flattened, column 3p + c is
///               coordinate c of point p): points pinned, weighted sums, any linear functional;
/// - barycentre: the mean of the deformed points (linear);
/// - centroid:   the centroid of the solid a closed surface bounds (quartic / cubic);
/// - volume:     the volume a closed surface bounds, a cubic polynomial in the control points
///               (each deformed vertex is linear in them, Sederberg & Parry 1986, eq. (1), and the
///               volume is sum det[a, b, c] / 6 over triangles).
/// The deformed points are x' = x + F.linear() sum_i s B_i (dP_i) (deformer.h), so linear
/// constraints are linear in the control change dP. solve() runs Newton on the Lagrange system
/// of   min |dP|^2  subject to  c(P + dP) = 0  in its minimum-norm form: each step solves the
/// linearised constraints J (dP_new - dP) = -c for the dP_new of least norm,
///   dP_new = J^T (J J^T)^+ (J dP - c),
/// whose fixed points are exactly the Lagrange points (dP parallel to the rows of J); linear
/// constraints hold after the first step, the volume's error falls quadratically.
///
/// Weights (Lamousin & Waggenspack 1994): a linear row's coefficients R = w B / sum w B and the
/// volume polynomial depend on the lattice's weights. solve() and keptVolume() compare the weights
/// of the lattice they are given with those the rows were built for: after a weight edit the
/// rows are rebuilt for the new weights (one adjoint pass per row, at the next solve()), and the
/// volume polynomial, which holds only while the weights equal the rest weights, is set aside
/// for the per-vertex sum (used again when the weights return to the rest weights). Asked for
/// explicitly (VolumeEvaluation::Polynomial), a weight that differs from its rest weight is a
/// LatticeError instead.
///
/// Precompute (constructor, add*, keep*): the embedding, the rows of J of the linear constraints
/// (constant: a linear row's residual is a . x + J (P + dP - Pbar)), the surface's
/// vertex-to-triangle table, and (VolumeEvaluation::Polynomial) the volume's coefficients. Each
/// Newton step: with the volume polynomial and no centroid, O(lattice) work only; otherwise one
/// deformation of the points and one pass over the triangles for the residuals (volume and
/// centroid together), and, when another step follows and its rows are due (JacobianUpdate), one
/// pass over the vertices that carries their gradients to the control points (the transpose of
/// the deformation, every per-vertex row at once).
class ShapeConstraints {
 public:
  /// @param lattice the lattice whose control points will change (its rest lattice and frame fix
  ///                the embedding; solve() checks it is still the same).
  /// @param points  #points x 3 WORLD points before deformation (the object's rest points).
  /// @throws LatticeError like embed().
  ShapeConstraints(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& points,
                   const EmbedOptions& embedOptions = {});

  /// Number of object points.
  Eigen::Index pointCount() const { return points_.rows(); }
  /// The points' embedding in the rest lattice.
  const Embedding& embedding() const { return deformer_.embedding(); }

  /// Restricts the solve to the free control coordinates (#controlPoints x 3, lattice-local).
  /// @throws ConstraintError on a wrong row count.
  void setFreeControls(const ControlMask& free);
  /// The control coordinates the solve may change (#controlPoints x 3).
  const ControlMask& freeControls() const { return free_; }

  /// Adds the rows A x' = b. @param A  m x 3*#points; @param b  m.
  /// @throws ConstraintError on sizes that differ or non-finite entries.
  void addLinear(const Eigen::SparseMatrix<double, Eigen::RowMajor>& A, const Eigen::Ref<const Eigen::VectorXd>& b);
  /// Keeps the mean of the deformed points at `target` (world); three linear rows.
  void keepBarycentre(const Eigen::Vector3d& target);
  /// Keeps the volume the closed surface over these points bounds at `target` (world units^3),
  /// evaluated per Newton step as `evaluation` says (Polynomial precomputes here).
  /// @throws ConstraintError when the surface is open or its vertex count is not pointCount(),
  ///         the target is not finite and non-zero, or Polynomial is asked for with more than 128
  ///         control points moving the surface.
  void keepVolume(const ClosedSurface& surface, double target,
                  VolumeEvaluation evaluation = VolumeEvaluation::Automatic);
  /// The volume the kept surface encloses once deformed by `lattice`'s current control points
  /// and weights (world units^3): the precomputed polynomial (O(lattice)) while the weights equal
  /// the rest weights, else a deformation and a sum over the triangles. A drag's status line (the
  /// volume change) costs nothing more than its solve.
  /// @throws ConstraintError without keepVolume(); LatticeError if `lattice` is not the one
  ///         embedded, or its weights differ from the rest weights with VolumeEvaluation::Polynomial.
  double keptVolume(const Lattice& lattice) const;
  /// True when the kept volume has its precomputed polynomial (see VolumeEvaluation); it is
  /// used while the lattice's weights equal its rest weights.
  bool volumeIsPolynomial() const { return volumePolynomial_ != nullptr; }
  /// The weights the linear rows are built for (one per control point); solve() rebuilds the
  /// rows when its lattice's weights differ.
  const Eigen::VectorXd& rowWeights() const { return rowWeights_; }
  /// Keeps the centroid of the solid the closed surface bounds at `target` (world).
  void keepCentroid(const ClosedSurface& surface, const Eigen::Vector3d& target);

  /// The least-norm control change meeting every constraint from `lattice`'s current control
  /// points (the lattice is not changed). Also callable with no constraint (change 0).
  /// @throws LatticeError if `lattice` is not the one embedded (Embedding::checkLattice), or its
  ///         weights differ from the rest weights while the volume asks for
  ///         VolumeEvaluation::Polynomial.
  /// @throws ConstraintError when the constraints cannot be met with the free controls (the
  ///         linearised system is inconsistent: e.g. a volume with no free control that changes
  ///         it, two contradicting rows) or Newton has not converged after maxIterations.
  ShapeSolveResult solve(const Lattice& lattice, const ShapeSolveOptions& options = {});

  /// The deformed points of the last solve() (world, #points x 3), after its change (deformed
  /// on the first call after a solve that did not need them).
  /// @throws ConstraintError before any solve().
  const Eigen::MatrixX3d& deformedPoints() const;

 private:
  // The polynomial applies to `lattice` (its weights equal the rest weights); with
  // VolumeEvaluation::Polynomial asked for, a LatticeError when they do not.
  bool polynomialApplies(const Lattice& lattice, const char* what) const;
  // Rebuilds the linear rows when `lattice`'s weights differ from rowWeights_.
  void adoptWeights(const Lattice& lattice);
  // A linear row's J row: the adjoint of the deformation applied to the row a (flattened 3 #points).
  Eigen::VectorXd rowOf(const Eigen::SparseVector<double>& a) const;

  Lattice lattice_;  // the embedded lattice (bases, frame, the rows' weights; its control points are not used)
  Eigen::VectorXd rowWeights_;  // lattice_'s weights, the linear rows' weights
  Eigen::MatrixX3d points_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();  // mean of points_: volumes are measured about it
  mutable Deformer deformer_;
  std::optional<Lattice> solved_;     // the lattice of the last solve(), its change applied
  mutable bool deformedStale_ = true;  // deformer_.points() is not yet that lattice's
  ControlMask free_;
  // Linear rows: J rows (flattened #controlPoints*3, local), right sides, the A rows kept for
  // their residual.
  std::vector<Eigen::VectorXd> linearRows_;
  std::vector<Eigen::SparseVector<double>> linearA_;
  std::vector<double> linearB_;
  std::vector<double> linearRest_;       // a . x of each row at the rest points
  std::vector<double> linearRestScale_;  // sum |a_j x_j| of each row at the rest points
  std::shared_ptr<const ClosedSurface> volumeSurface_;
  double volumeTarget_ = 0.0;
  std::shared_ptr<const detail::VolumePolynomial> volumePolynomial_;
  VolumeEvaluation volumeEvaluation_ = VolumeEvaluation::Automatic;  // as keepVolume() was asked
  std::shared_ptr<const ClosedSurface> centroidSurface_;
  Eigen::Vector3d centroidTarget_ = Eigen::Vector3d::Zero();
};

}  // namespace ffdkit::ffd
