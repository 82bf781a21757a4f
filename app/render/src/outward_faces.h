#pragma once

// Whether the scene's lattices keep a closed surface's outward faces outward (private to
// ffdkit::render), so that SurfaceMapper may cull its back faces (surface_mapper.h): a fold of the
// space turns part of the surface inside out, and a lattice that moves part of an object and leaves
// the rest (outside points left where they are) can tear it open; either shows back faces that
// culling would hide. Eigen and the widget model only.

#include <cstdint>
#include <map>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/interaction/view_highlights.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::app {

/// The lattices' verdicts on keeping faces outward, kept per lattice and computed again when the
/// lattice's control points or rest lattice change (WidgetModel::controlRevision, frameRevision).
class OutwardFacesGuard {
 public:
  /// True when every lattice of `model` keeps the faces of an object whose rest points lie in the
  /// world box [lo, hi] outward. A lattice does when
  /// - the box lies wholly in its rest parameter box and det J of its map has the rest lattice's
  ///   sign everywhere (ffd::checkFolding certifies every cell: the deformation preserves
  ///   orientation, so a closed outward surface stays outward and does not pass through itself), or
  /// - the box lies wholly outside its rest parameter box and it leaves outside points where they
  ///   are (OutsidePolicy::Identity).
  /// Anything else is false: a lattice across the box, another outside policy, a rest lattice that
  /// is not an affine image of its parameter box (the box test would not be exact), a child lattice
  /// (it deforms its parent's deformed space), a lattice the check cannot bound.
  /// `certified` are verdicts already made (the controllers' during a drag or transform,
  /// ViewHighlights::certified): a lattice among them at its current revisions is not checked again.
  bool keepsOutward(const widgets::WidgetModel& model, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                    const std::vector<CertifiedLattice>& certified);

  /// Fold-over checks run so far (one per lattice and change of it no verdict given covered).
  int checks() const { return checks_; }

 private:
  struct LatticeVerdict {
    std::uint64_t controlRevision = 0, frameRevision = 0;
    bool affineRoot = false;     ///< a root lattice whose rest is an affine image of its parameter box
    bool certified = false;      ///< checkFolding: every cell Positive
    bool identityOutside = false;
    Eigen::Affine3d worldToParameters = Eigen::Affine3d::Identity();  ///< the rest map's inverse
    Eigen::Vector3d parameterMin = Eigen::Vector3d::Zero(), parameterMax = Eigen::Vector3d::Zero();
  };
  const LatticeVerdict& verdict(const widgets::WidgetModel& model, widgets::WidgetId lattice,
                                const std::vector<CertifiedLattice>& certified);

  std::uint64_t instance_ = 0;
  std::map<widgets::WidgetId, LatticeVerdict> verdicts_;
  int checks_ = 0;
};

}  // namespace ffdkit::app
