#include "ffdkit/scenes/scene_changes.h"

namespace ffdkit::scenes {

SceneMark markOf(const Scene& scene) { return {scene.revision(), scene.widgets.instance(), scene.widgets.revision()}; }

SceneChanges changesSince(const Scene& scene, const SceneMark& mark) {
  SceneChanges changes;
  if (mark.widgetInstance != scene.widgets.instance()) {
    changes.widgetsReplaced = true;
  } else {
    changes.widgets = scene.widgets.changesSince(mark.widgets);
  }
  changes.structure = scene.structureRevision() > mark.scene;
  changes.camera = scene.cameraRevision() > mark.scene;
  changes.animation = scene.animationRevision() > mark.scene;
  for (const SceneObject& o : scene.objects()) {
    if (o.meshRevision > mark.scene) changes.meshes.push_back(o.id);
    if (o.displayRevision > mark.scene) changes.looks.push_back(o.id);
  }
  return changes;
}

}  // namespace ffdkit::scenes
