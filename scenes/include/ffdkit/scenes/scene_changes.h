#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ffdkit/scenes/scene.h"
#include "ffdkit/widgets/widget_changes.h"

namespace ffdkit::scenes {

/// Where a consumer last looked at a scene: the scene's own revision and the widget model's
/// instance and revision (SceneChanges says what changed after it).
struct SceneMark {
  std::uint64_t scene = 0;  ///< the scene's revision
  std::uint64_t widgetInstance = 0;  ///< 0: never looked
  std::uint64_t widgets = 0;  ///< the widget model's revision
  friend bool operator==(const SceneMark&, const SceneMark&) = default;  ///< the same place
};

/// What changed in a scene after a SceneMark (Scene's edits stamp what they change): the change set the deformer, the view, the outliner
/// and the property panel read instead of comparing the document (change-driven updates).
struct SceneChanges {
  /// The widget model was replaced (a copy, a file): take every widget and lattice anew.
  bool widgetsReplaced = false;
  widgets::WidgetChanges widgets;   ///< within the same model (empty when replaced)
  bool structure = false;           ///< objects added, removed or renamed (labels only); attachments changed
  bool camera = false;              ///< camera or background
  bool animation = false;           ///< keys, frame rate or frame range
  std::vector<ObjectId> meshes;  ///< objects whose own points (or source) changed
  std::vector<ObjectId> looks;   ///< objects whose DisplaySettings changed

  /// True when nothing changed.
  bool empty() const {
    return !widgetsReplaced && widgets.empty() && !structure && !camera && !animation && meshes.empty() && looks.empty();
  }
};

/// The scene's present mark (for a consumer that is now up to date).
SceneMark markOf(const Scene& scene);
/// What changed after `mark`.
SceneChanges changesSince(const Scene& scene, const SceneMark& mark);

}  // namespace ffdkit::scenes
