#pragma once

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "ffdkit/scenes/scene.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::scenes {

/// What a gesture or a value edit changed in a widget model's mutable state (control points,
/// control-point weights, lattice frames, variations): only the items that differ, before and after. Undo and redo
/// write them in place (WidgetModel::restoreState), which stamps only what differs, so the
/// deformer re-embeds nothing unless a frame changed.
struct StateDelta {
  widgets::WidgetModelState before;  ///< the changed items as they were
  widgets::WidgetModelState after;  ///< the same items as they are after the change

  /// True when nothing changed.
  bool empty() const {
    return before.controlPoints.empty() && before.latticeFrames.empty() && before.variations.empty() &&
           before.weights.empty();
  }
  /// Heap and inline bytes held.
  std::size_t bytes() const;
};

/// The items of `after` that differ from `before` (both captured from one model, same widgets).
StateDelta stateDelta(const widgets::WidgetModelState& before, const widgets::WidgetModelState& after);

/// What a structural edit changed in a widget model's data (WidgetModel::toData): the records
/// (lattices, cells, affine widgets, bindings) added, removed or changed, each as (before,
/// after) with nullopt for "absent", and the root order when it changed. Applying it gives the
/// model its present data with these records swapped, in place (WidgetModel::assignData): the
/// same model instance, with just the widgets and bindings concerned stamped, so the deformer
/// re-embeds only the stages concerned and the view redraws only the widgets concerned.
struct ModelPatch {
  template <class Record>
  /// (before, after) pairs of records; nullopt: absent.
  using Changes = std::vector<std::pair<std::optional<Record>, std::optional<Record>>>;
  Changes<widgets::LatticeData> lattices;  ///< lattices added, removed or changed
  Changes<widgets::CellData> cells;  ///< cells added, removed or changed
  Changes<widgets::AffineData> affines;  ///< affine widgets added, removed or changed
  Changes<widgets::Binding> bindings;  ///< bindings added, removed or changed
  std::optional<std::pair<std::vector<widgets::WidgetId>, std::vector<widgets::WidgetId>>> rootOrder;  ///< root order before and after, when it changed

  /// True when nothing changed.
  bool empty() const {
    return lattices.empty() && cells.empty() && affines.empty() && bindings.empty() && !rootOrder;
  }
  /// Heap and inline bytes held.
  std::size_t bytes() const;
};

/// The records that differ between two data snapshots of one model (matched by id).
ModelPatch modelPatch(const widgets::WidgetModelData& before, const widgets::WidgetModelData& after);

/// Applies `patch` to `model`, forward (before -> after) or backward.
/// @throws widgets::WidgetError if the model is not in the state the patch starts from.
void applyPatch(widgets::WidgetModel& model, const ModelPatch& patch, bool forward);

/// A document edit's delta: its widget patch and, when they changed, the attachments before and
/// after (a few ids each). Objects added or removed are kept by the command that moved them.
struct SceneDelta {
  ModelPatch widgets;  ///< the widget model's records that changed
  std::optional<std::pair<std::vector<Attachment>, std::vector<Attachment>>> attachments;  ///< attachments before and after, when they changed

  /// True when nothing changed.
  bool empty() const { return widgets.empty() && !attachments; }
  /// Heap and inline bytes held.
  std::size_t bytes() const;
};

/// Applies a SceneDelta forward or backward (stamps the scene's structure when attachments change).
void applySceneDelta(Scene& scene, const SceneDelta& delta, bool forward);

}  // namespace ffdkit::scenes
