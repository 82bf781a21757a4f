// The lattice's FFD as the CAD deformation sees it: a map of world points (the engine's own
// evaluation, outside policy included), and, for box lattices, one polynomial per lattice cell.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/cad/bernstein_composition.h"
#include "ffdkit/cad/cad_deform.h"
#include "ffdkit/ffd/lattice.h"

namespace ffdkit::cad {

class FfdMap {
 public:
  /// @param modelSize the model's bounding-box diagonal (the default tolerance is 1e-6 of it).
  /// @throws CadError on options out of range, or a lattice the method cannot use.
  FfdMap(const ffd::Lattice& lattice, const CadDeformOptions& options, double modelSize);

  const CadDeformOptions& options() const { return options_; }
  const ffd::Lattice& lattice() const { return lattice_; }
  /// The approximation tolerance in model units.
  double tolerance() const { return tolerance_; }
  /// True when the FFD is one polynomial per cell in world coordinates (a box rest shape, clamped axes).
  bool polynomial() const { return polynomial_; }
  /// True when the outside policy continues the end cells' polynomials (Extrapolate).
  bool extrapolates() const { return lattice_.outsidePolicy().kind == ffd::OutsidePolicy::Kind::Extrapolate; }
  /// A bound of |dX| / |dq| in the lattice (tolerances of moved edges and vertices scale by it).
  double lipschitz() const { return lipschitz_; }
  /// Sum of the lattice's degrees: a patch of degree p composes to degree totalDegree() * p.
  int totalDegree() const { return lattice_.axis(0).degree() + lattice_.axis(1).degree() + lattice_.axis(2).degree(); }

  /// (u, v, w) of a world point (polynomial() lattices only).
  Eigen::Vector3d parameters(const Eigen::Vector3d& world) const { return toParameter_ * world; }
  /// The affine map world -> (u, v, w) (polynomial() lattices only).
  const Eigen::Affine3d& toParameter() const { return toParameter_; }
  /// Inside the lattice's parameter box, grown by 1e-9 of each axis's range.
  bool inside(const Eigen::Vector3d& world) const;
  /// The cell of parameter t along `axis` (the end cells beyond the domain).
  int cellOf(int axis, double t) const { return lattice_.axis(axis).cellOf(t); }
  /// The interior cell boundaries (knot planes) along `axis`, increasing.
  const std::vector<double>& knotPlanes(int axis) const { return planes_[axis]; }
  /// Planes of constant lattice parameter, per axis, where the FFD is not smooth: the knot planes
  /// and, unless the policy extrapolates, the lattice's faces (polynomial() lattices only).
  const std::array<std::vector<double>, 3>& kinkPlanes() const { return kinks_; }
  /// The cell's polynomial in Bernstein form (built once per cell).
  const BernsteinVolume& cellVolume(const Eigen::Vector3i& cell) const;

  /// The FFD of world points (#points x 3) as the engine computes it (embed and Deformer, the
  /// outside policy applied): the reference the approximations are fitted and measured against.
  /// extend = true: beyond the lattice, the end cells' polynomials continued (the Extrapolate
  /// policy) instead of the lattice's policy: a smooth target for the parts of a surface that lie
  /// outside the lattice but also outside its face's trim.
  Eigen::MatrixX3d points(const Eigen::MatrixX3d& world, bool extend = false) const;
  /// One point, as points().
  Eigen::Vector3d point(const Eigen::Vector3d& world) const;

 private:
  double lipschitzBound() const;

  const ffd::Lattice& lattice_;
  ffd::Lattice extended_;  // the lattice with the Extrapolate policy
  CadDeformOptions options_;
  double tolerance_ = 0.0;
  bool polynomial_ = false;
  Eigen::Affine3d toParameter_ = Eigen::Affine3d::Identity();
  std::vector<double> planes_[3];
  std::array<std::vector<double>, 3> kinks_;
  double lipschitz_ = 1.0;
  mutable std::map<std::array<int, 3>, BernsteinVolume> cells_;
};

}  // namespace ffdkit::cad
