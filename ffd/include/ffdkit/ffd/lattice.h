#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/ffd/axis_basis.h"
#include "ffdkit/ffd/box_lattice_options.h"
#include "ffdkit/ffd/lattice_error.h"
#include "ffdkit/ffd/outside_policy.h"
#include "ffdkit/ffd/rest_shape.h"

namespace ffdkit::ffd {

/// The most control points a lattice may have (l*m*n): the constructors refuse more, and the
/// file readers check a count against it before allocating.
inline constexpr std::uint64_t kMaxLatticeControlPoints = 100'000'000;

/// An FFD lattice: l x m x n control points P_ijk (Kuriyama 1996, sec. 6.3.2), a basis per axis,
/// the rest lattice Pbar (the control points before any edit, eq. (6.2)), a frame placing the
/// lattice-local coordinates in the world, and the outside-point policy.
///
/// Rational lattices (NURBS-based FFD, Lamousin & Waggenspack 1994): a weight w_ijk > 0 per
/// control point makes the map the ratio X = sum B_ijk w_ijk P_ijk / sum B_ijk w_ijk; the rest
/// lattice has its own weights wbar_ijk. All weights 1 (the default) is the polynomial lattice
/// of eq. (6.1), evaluated by the polynomial code everywhere (the same bits as before weights).
///
/// Layout: control points are stored one per row of a pointCount x 3 matrix in lattice-LOCAL
/// coordinates, flat index = i + l*(j + m*k) (i fastest). World = frame() * local.
/// Value semantics: copyable, comparable by revision only through revision()/restRevision().
/// Revisions are process-wide unique counters, so a copy that is edited never collides with
/// the original's revision.
class Lattice {
 public:
  /// A user-shaped lattice.
  /// @param counts     (l, m, n), each >= 2.
  /// @param bases      per-axis basis (resolved for the count of that axis).
  /// @param restPoints l*m*n x 3, lattice-local, i fastest. Becomes both Pbar and P.
  /// @param frame      world = frame * local; must be invertible and finite.
  /// @throws LatticeError on counts < 2, a bad basis (degree, knots), wrong row count,
  ///         non-finite points or frame, or a degenerate (zero-volume) rest lattice.
  Lattice(const Eigen::Vector3i& counts, const std::array<AxisBasis, 3>& bases,
          const Eigen::Ref<const Eigen::MatrixX3d>& restPoints,
          const Eigen::Affine3d& frame = Eigen::Affine3d::Identity());

  /// Control points per axis (l, m, n).
  Eigen::Vector3i counts() const { return counts_; }
  /// Number of control points, l*m*n.
  Eigen::Index pointCount() const { return static_cast<Eigen::Index>(counts_.prod()); }
  /// Flat index = i + l*(j + m*k). No range check (use gridIndex / setControlPoint for checked access).
  Eigen::Index index(int i, int j, int k) const {
    return i + static_cast<Eigen::Index>(counts_[0]) * (j + static_cast<Eigen::Index>(counts_[1]) * k);
  }
  /// Inverse of index(). @throws LatticeError if flat is out of [0, pointCount()).
  Eigen::Vector3i gridIndex(Eigen::Index flat) const;

  /// Per-axis basis, as given and as resolved (knots, cells, Greville abscissae).
  const AxisBasis& basis(int axis) const { return axes_[axis].basis(); }
  /// The resolved spline of axis `axis` (0, 1, 2).
  const AxisSpline& axis(int axis) const { return axes_[axis]; }
  /// Parameter box: per axis [domainMin, domainMax] ([0, 1] for default bases).
  Eigen::Vector3d parameterMin() const;
  /// Upper corner of the parameter box (see parameterMin()).
  Eigen::Vector3d parameterMax() const;

  /// Current control points P, pointCount x 3, lattice-local.
  const Eigen::MatrixX3d& controlPoints() const { return control_; }
  /// Rest control points Pbar, same layout.
  const Eigen::MatrixX3d& restPoints() const { return rest_; }
  /// @throws LatticeError on a wrong row count or non-finite values. Bumps revision().
  void setControlPoints(const Eigen::Ref<const Eigen::MatrixX3d>& points);
  /// @throws LatticeError on flat out of range or non-finite p. Bumps revision().
  void setControlPoint(Eigen::Index flat, const Eigen::Vector3d& p);
  /// P = Pbar and w = wbar. Bumps revision().
  void resetToRest();
  /// Replaces the rest lattice (and resets P to it): the "points moved before attaching" case.
  /// @throws LatticeError like the constructor. Bumps revision() and restRevision().
  void setRestPoints(const Eigen::Ref<const Eigen::MatrixX3d>& restPoints);

  /// Current weights w_ijk, pointCount entries (i fastest, like the points), all > 0.
  Eigen::VectorXd weights() const;
  /// Weight of control point `flat` (1 for a polynomial lattice). @throws LatticeError on a bad index.
  double weight(Eigen::Index flat) const;
  /// Rest weights wbar_ijk, the weights of the rest map Xbar that embedding inverts.
  Eigen::VectorXd restWeights() const;
  /// True when some current or rest weight is not 1: the map is a ratio (Lamousin & Waggenspack 1994).
  bool isRational() const { return weights_.size() > 0 || restWeights_.size() > 0; }
  /// True when some rest weight is not 1: embedding solves the rational rest map by Newton.
  bool restIsRational() const { return restWeights_.size() > 0; }
  /// Sets every current weight (pointCount entries).
  /// @throws LatticeError on a wrong count or a weight that is not finite and > 0 (naming it).
  /// Bumps revision(): like a control-point edit, a weight edit deforms without re-embedding.
  void setWeights(const Eigen::Ref<const Eigen::VectorXd>& weights);
  /// Sets one current weight. @throws LatticeError on a bad index or a weight not finite and > 0.
  /// Bumps revision().
  void setWeight(Eigen::Index flat, double weight);
  /// Sets the rest weights and resets the current weights to them (the control points are kept).
  /// @throws LatticeError like setWeights. Bumps revision() and restRevision() (re-embed).
  void setRestWeights(const Eigen::Ref<const Eigen::VectorXd>& weights);

  /// World placement of the lattice: world = frame * local.
  const Eigen::Affine3d& frame() const { return frame_; }
  /// Moves the whole lattice (rest and current) in the world; local coordinates are unchanged.
  /// @throws LatticeError on a non-finite or singular frame. Bumps restRevision().
  void setFrame(const Eigen::Affine3d& frame);

  /// What happens to points outside the rest lattice.
  const OutsidePolicy& outsidePolicy() const { return policy_; }
  /// @throws LatticeError for Falloff with distance <= 0 or non-finite. Bumps restRevision()
  /// (embeddings carry the policy's precomputed data).
  void setOutsidePolicy(const OutsidePolicy& policy);

  /// Changes on every control-point change (setControlPoint(s), resetToRest, setRestPoints).
  std::uint64_t revision() const { return revision_; }
  /// Changes when the rest lattice, the frame or the outside policy changes: embeddings built
  /// for an older restRevision are stale.
  std::uint64_t restRevision() const { return restRevision_; }

  /// X(u,v,w) = sum_ijk B_i(u) B_j(v) B_k(w) P_ijk, lattice-local (Kuriyama 1996, eq. (6.1));
  /// with weights the ratio sum B w P / sum B w (Lamousin & Waggenspack 1994).
  /// Parameters outside the box evaluate the end polynomial pieces; periodic axes wrap.
  Eigen::Vector3d evaluate(const Eigen::Vector3d& uvw) const;
  /// Xbar(u,v,w): eq. (6.1) on the rest lattice (the left side of eq. (6.2)).
  Eigen::Vector3d evaluateRest(const Eigen::Vector3d& uvw) const;
  /// dX/d(u,v,w) (column a = derivative along parameter a) and, optionally, X itself. With
  /// weights, the quotient rule: (dN - X dW^T) / W with N = sum B w P and W = sum B w.
  Eigen::Matrix3d jacobian(const Eigen::Vector3d& uvw, Eigen::Vector3d* value = nullptr) const;
  /// dXbar/d(u,v,w) on the rest lattice and, optionally, Xbar itself (used by Newton embedding).
  Eigen::Matrix3d restJacobian(const Eigen::Vector3d& uvw, Eigen::Vector3d* value = nullptr) const;

  /// True when Xbar is an affine function of (u,v,w): Xbar = A*uvw + b (box lattices on the
  /// Greville grid with rest weights 1). Then embedding is the closed form A^-1 (Q - b).
  bool restIsAffine() const { return restAffine_; }
  /// A and b of the affine rest map (meaningful only if restIsAffine()).
  const Eigen::Matrix3d& restAffineLinear() const { return restA_; }
  /// b of the affine rest map (see restAffineLinear()).
  const Eigen::Vector3d& restAffineOffset() const { return restB_; }
  /// Diagonal of the rest lattice's bounding box (> 0): the length scale for tolerances.
  double restSize() const { return restSize_; }

  /// Set by makeCylindricalLattice: the cylinder the rest lattice was built from, used only as the
  /// Newton initial guess. Cleared by setRestPoints(). Does not change restRevision().
  const std::optional<CylinderRestShape>& cylinderRestShape() const { return cylinder_; }
  /// Sets or clears the cylinder of cylinderRestShape().
  void setCylinderRestShape(const std::optional<CylinderRestShape>& shape) { cylinder_ = shape; }

 private:
  Eigen::Vector3d evaluateOn(const Eigen::MatrixX3d& points, const Eigen::VectorXd& weights,
                             const Eigen::Vector3d& uvw, Eigen::Matrix3d* jac) const;
  void setRestInternal(const Eigen::Ref<const Eigen::MatrixX3d>& restPoints);
  Eigen::VectorXd checkedWeights(const Eigen::Ref<const Eigen::VectorXd>& weights, const char* what) const;

  Eigen::Vector3i counts_;
  std::array<AxisSpline, 3> axes_;
  Eigen::MatrixX3d control_;
  Eigen::MatrixX3d rest_;
  Eigen::VectorXd weights_;      // empty: every weight 1
  Eigen::VectorXd restWeights_;  // empty: every rest weight 1
  Eigen::Affine3d frame_ = Eigen::Affine3d::Identity();
  OutsidePolicy policy_{};
  std::uint64_t revision_ = 0;
  std::uint64_t restRevision_ = 0;
  bool restAffine_ = false;
  Eigen::Matrix3d restA_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d restB_ = Eigen::Vector3d::Zero();
  double restSize_ = 1.0;
  std::optional<CylinderRestShape> cylinder_;
};

/// Default box lattice: rest points fill the local box [boxMin, boxMax] (unit box by default)
/// at the Greville abscissae of each axis (a regular grid for Bernstein and clamped uniform
/// B-splines of degree 1 and of degree count-1; otherwise the points next to each face sit closer to it),
/// so that the rest map is affine and embedding is closed form (Kuriyama 1996, sec. 6.3.2). frame =
/// options.frame.
/// @throws LatticeError on counts < 2, bad bases, boxMax <= boxMin on an axis, non-finite input,
///         or a periodic axis (use makeCylindricalLattice for closed axes).
Lattice makeBoxLattice(const BoxLatticeOptions& options = {});

/// A user-shaped lattice, same as the Lattice constructor (for symmetry with makeBoxLattice).
Lattice makeLattice(const Eigen::Vector3i& counts, const std::array<AxisBasis, 3>& bases,
                    const Eigen::Ref<const Eigen::MatrixX3d>& restPoints,
                    const Eigen::Affine3d& frame = Eigen::Affine3d::Identity());

}  // namespace ffdkit::ffd
