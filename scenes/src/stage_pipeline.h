#pragma once

// The lattice stages that deform one object, as an ffd::Pipeline synced from the scene's widget
// model (private to SceneDeformer). SceneDeformer keeps one over an object's full mesh and, for
// an object a view reads only at a level-of-detail proxy during gestures, one over those points
// (EvaluationRequest::subsets); both are built and synced by the same code.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "ffdkit/ffd/pipeline.h"
#include "ffdkit/scenes/scene.h"

namespace ffdkit::scenes::detail {

/// A lattice deforming an object, with its parent lattice and its priority among its siblings.
struct Stage {
  widgets::WidgetId lattice;               ///< the lattice
  std::optional<widgets::WidgetId> parent;  ///< its parent lattice, none for a root
  int priority = 0;                         ///< among its siblings (or the object's roots)
  /// Compared member by member.
  bool operator==(const Stage&) const = default;
};

/// The lattices deforming `object`, in pipeline order: its attached roots in attachment order,
/// each followed by its subtree in pre-order (Kuriyama 1996, secs. 6.2.3, 6.3.2).
std::vector<Stage> stagesFor(const Scene& scene, ObjectId object);

/// The engine's re-embedding throttle for a lattice's settings.
ffd::ReembedThrottle throttleFor(const widgets::LatticeSettings& settings);

/// An ffd::Pipeline over some points with the scene's lattices as its stages, and what of the
/// widget model it was last synced to.
struct StagePipeline {
  std::vector<Stage> stages;                      ///< the stages, in pipeline order
  std::unique_ptr<ffd::Pipeline> pipeline;        ///< null until built
  std::map<widgets::WidgetId, ffd::LatticeId> ids;  ///< each stage's lattice in `pipeline`
  /// Per stage: the model revisions (frame, control) its lattice in the pipeline was last synced to.
  std::map<widgets::WidgetId, std::pair<std::uint64_t, std::uint64_t>> synced;
  std::uint64_t modelInstance = 0;  ///< WidgetModel::instance the revisions belong to

  /// A new pipeline over `points` (taken over) with `newStages`' lattices from the scene.
  /// Returns the lattices built.
  int build(const Scene& scene, std::unique_ptr<ffd::Pipeline> points, std::vector<Stage> newStages);
  /// The scene's lattices synced into the pipeline in place: a stage whose revisions did not move
  /// is left alone; new control points are written into its lattice (updated incrementally), a
  /// new frame moves it (re-embedding per the throttle); only a new rest shape makes a new
  /// lattice. Returns the lattices built.
  int sync(const Scene& scene);
  /// Throttle, active lattice, update mode and precision for the next run (stages not empty).
  void prepareRun(const Scene& scene, std::optional<widgets::WidgetId> activeLattice, ffd::UpdateMode mode,
                  ffd::Precision precision);
};

}  // namespace ffdkit::scenes::detail
