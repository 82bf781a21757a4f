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
  std::uint64_t scene = 0;
  std::uint64_t widgetInstance = 0;  ///< 0: never looked
  std::uint64_t widgets = 0;
};

/// What changed in a scene after a SceneMark: the change set the deformer, the view, the outliner
/// and the property panel read instead of comparing the document (seed STYLE "change-driven").
struct SceneChanges {
  /// The widget model was replaced (a copy, a file): take every widget and lattice anew.
  bool widgetsReplaced = false;
  widgets::WidgetChanges widgets;   ///< within the same model (empty when replaced)
  bool structure = false;           ///< objects added, removed or renamed; attachments changed
  bool camera = false;              ///< camera or background
  bool animation = false;           ///< keys, frame rate or frame range
  std::vector<std::string> meshes;  ///< objects whose own points (or source) changed
  std::vector<std::string> looks;   ///< objects whose DisplaySettings changed

  bool empty() const {
    return !widgetsReplaced && widgets.empty() && !structure && !camera && !animation && meshes.empty() && looks.empty();
  }
};

/// The scene's present mark (for a consumer that is now up to date).
SceneMark markOf(const Scene& scene);
/// What changed after `mark`.
SceneChanges changesSince(const Scene& scene, const SceneMark& mark);

// ---- edits that stamp their revisions (Scene's fields may also be set directly while a scene is
// built; a consumer that must notice such an edit needs one of these, or a touch* call) ----------

/// Adds an object. @throws std::invalid_argument for an empty or duplicate name.
void addObject(Scene& scene, SceneObject object);
/// Removes an object and its place in every attachment (an attachment left with no object goes).
/// @throws std::invalid_argument for an unknown object.
void removeObject(Scene& scene, const std::string& name);
/// Replaces an object's own points (and source, when given). @throws for an unknown object.
void setObjectMesh(Scene& scene, const std::string& name, MeshData mesh);
/// Changes how an object looks (no geometry changes). @throws for an unknown object.
void setObjectDisplay(Scene& scene, const std::string& name, const DisplaySettings& display);
void setCamera(Scene& scene, const Camera& camera);
void setBackground(Scene& scene, const Eigen::Vector3d& background);
/// After editing `scene.attachments` or `scene.objects` directly: stamps the structure.
void touchStructure(Scene& scene);
/// After editing an object's mesh in place: stamps it. @throws for an unknown object.
void touchMesh(Scene& scene, const std::string& name);

}  // namespace ffdkit::scenes
