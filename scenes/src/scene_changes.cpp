#include "ffdkit/scenes/scene_changes.h"

#include <algorithm>
#include <stdexcept>

namespace ffdkit::scenes {
namespace {

SceneObject& object(Scene& scene, const std::string& name) {
  SceneObject* found = scene.findObject(name);
  if (found == nullptr) throw std::invalid_argument("scene: unknown object '" + name + "'");
  return *found;
}

}  // namespace

SceneMark markOf(const Scene& scene) { return {scene.revision, scene.widgets.instance(), scene.widgets.revision()}; }

SceneChanges changesSince(const Scene& scene, const SceneMark& mark) {
  SceneChanges changes;
  if (mark.widgetInstance != scene.widgets.instance()) {
    changes.widgetsReplaced = true;
  } else {
    changes.widgets = scene.widgets.changesSince(mark.widgets);
  }
  changes.structure = scene.structureRevision > mark.scene;
  changes.camera = scene.cameraRevision > mark.scene;
  changes.animation = scene.animationRevision > mark.scene;
  for (const SceneObject& o : scene.objects) {
    if (o.meshRevision > mark.scene) changes.meshes.push_back(o.name);
    if (o.displayRevision > mark.scene) changes.looks.push_back(o.name);
  }
  return changes;
}

void addObject(Scene& scene, SceneObject object) {
  if (object.name.empty()) throw std::invalid_argument("scene: an object needs a name");
  if (scene.findObject(object.name) != nullptr)
    throw std::invalid_argument("scene: an object named '" + object.name + "' exists");
  const std::uint64_t r = ++scene.revision;
  object.meshRevision = object.displayRevision = r;
  scene.structureRevision = r;
  scene.objects.push_back(std::move(object));
}

void removeObject(Scene& scene, const std::string& name) {
  auto it = std::find_if(scene.objects.begin(), scene.objects.end(), [&](const SceneObject& o) { return o.name == name; });
  if (it == scene.objects.end()) throw std::invalid_argument("scene: unknown object '" + name + "'");
  scene.objects.erase(it);
  for (Attachment& a : scene.attachments) std::erase(a.objects, name);
  std::erase_if(scene.attachments, [](const Attachment& a) { return a.objects.empty(); });
  scene.structureRevision = ++scene.revision;
}

void setObjectMesh(Scene& scene, const std::string& name, MeshData mesh) {
  SceneObject& o = object(scene, name);
  o.mesh = std::move(mesh);
  o.meshRevision = ++scene.revision;
}

void setObjectDisplay(Scene& scene, const std::string& name, const DisplaySettings& display) {
  SceneObject& o = object(scene, name);
  o.display = display;
  o.displayRevision = ++scene.revision;
}

void setCamera(Scene& scene, const Camera& camera) {
  scene.camera = camera;
  scene.cameraRevision = ++scene.revision;
}

void setBackground(Scene& scene, const Eigen::Vector3d& background) {
  scene.background = background;
  scene.cameraRevision = ++scene.revision;
}

void touchStructure(Scene& scene) { scene.structureRevision = ++scene.revision; }

void touchMesh(Scene& scene, const std::string& name) { object(scene, name).meshRevision = ++scene.revision; }

}  // namespace ffdkit::scenes
