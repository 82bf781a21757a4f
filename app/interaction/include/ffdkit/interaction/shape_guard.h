#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/scenes/object_id.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/widgets/widget_id.h"

namespace ffdkit::ffd {
class ShapeConstraints;
class Lattice;
}  // namespace ffdkit::ffd

namespace ffdkit::app {

/// What an object keeps while its lattice is edited (the app's Keep Volume / Keep Centre).
struct ShapeKeep {
  bool volume = false;  ///< the volume its closed surface encloses
  bool centre = false;  ///< the centroid of that solid (a closed surface), else the mean of its points
  /// True when either is kept.
  bool any() const { return volume || centre; }
  friend bool operator==(const ShapeKeep&, const ShapeKeep&) = default;  ///< equal when both flags are
};

/// What one correction did to one kept object (for the status bar).
struct ShapeGuardStep {
  scenes::ObjectId object;  ///< the kept object
  /// (V - V0) / |V0| after the correction, V0 the volume when Keep Volume was turned on (NaN
  /// when the volume is not kept or the correction failed).
  double volumeChange = 0.0;
  int iterations = 0;  ///< Newton steps of the solve
  /// Why the object was not corrected (empty when it was): the constraints cannot be met with
  /// the free control points, or more than one lattice deforms the object.
  std::string problem;
};

/// Keep Volume / Keep Centre in the app: per object, the volume (and / or centre) it had when
/// the keep was turned on, held through every later edit of its lattice's control points. After
/// each step of a transform the free control points (those the transform does not move) get the
/// least-norm change that restores them (ffd::ShapeConstraints: Newton on the Lagrange system to
/// 1e-12, Hsu, Hughes & Kaufman 1992 with the volume as a constraint); the corrected points are
/// part of the transform's model edit, so its undo step holds them.
///
/// Precompute: the object's embedding and, for a volume, its cubic polynomial in the control
/// points (ffd::VolumeEvaluation::Automatic), built when the keep is turned on and again only
/// when the object's mesh or the lattice's rest frame changes; a step then costs O(lattice) (a
/// centroid on a closed surface costs passes over the vertices per Newton step, and so does the
/// volume while a typed weight makes the lattice's weights differ from its rest weights).
/// Holds for an object deformed by exactly one lattice.
class ShapeGuard {
 public:
  ShapeGuard();
  ~ShapeGuard();
  ShapeGuard(ShapeGuard&&) noexcept;
  ShapeGuard& operator=(ShapeGuard&&) noexcept;

  /// Keeps `object`'s volume and / or centre at their values now (its evaluated points in
  /// `deformer`, else its own points), or stops keeping them. Precomputes what the steps need.
  /// @throws std::invalid_argument naming the object for an unknown object, or a volume asked
  ///   of one that is not a closed triangulated surface (the reason: "edge (3, 4) is used by 1
  ///   triangle"), or whose volume is zero.
  void setKeep(const scenes::Scene& scene, const scenes::SceneDeformer& deformer, scenes::ObjectId object,
               ShapeKeep keep);
  /// What `object` keeps (nothing for an object never kept).
  ShapeKeep keep(scenes::ObjectId object) const;
  /// True when no object keeps anything.
  bool empty() const { return kept_.empty(); }
  /// The volume Keep Volume holds `object` at. @throws std::invalid_argument when it keeps none.
  double keptVolume(scenes::ObjectId object) const;

  /// Corrects the control points of `lattice` in `scene` (local, WidgetModel::setControlPoints)
  /// so that every kept object deformed by `lattice` alone keeps its volume and centre: the
  /// least-norm change of the points with `free[i]` true (#controlPoints entries) from the current
  /// ones. An object whose constraints cannot be met is left as it is, with the reason in its
  /// step. @return one step per kept object `lattice` deforms (none when it deforms none).
  std::vector<ShapeGuardStep> correct(scenes::Scene& scene, widgets::WidgetId lattice, const std::vector<bool>& free);

  /// Forgets the objects the scene no longer has (and every object for another scene's model).
  void prune(const scenes::Scene& scene);

 private:
  struct Kept;
  struct Prepared;
  /// The constraints of `object` for `lattice`, built anew when its mesh or the lattice's rest
  /// frame changed. @throws std::invalid_argument as setKeep.
  Prepared& prepare(const scenes::Scene& scene, scenes::ObjectId object, widgets::WidgetId lattice);

  std::map<scenes::ObjectId, Kept> kept_;
  std::map<scenes::ObjectId, std::unique_ptr<Prepared>> prepared_;
};

}  // namespace ffdkit::app
