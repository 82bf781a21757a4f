#include "ffdkit/scenes/scene.h"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "ffdkit/scenes/lattice_fit.h"
#include "ffdkit/scenes/scene_changes.h"

namespace ffdkit::scenes {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

std::string knownObjects(const Scene& scene) {
  std::string list;
  for (const auto& o : scene.objects) list += (list.empty() ? "" : ", ") + o.name;
  return list.empty() ? "none" : list;
}

}  // namespace

const SceneObject* Scene::findObject(const std::string& name) const {
  for (const auto& object : objects)
    if (object.name == name) return &object;
  return nullptr;
}

SceneObject* Scene::findObject(const std::string& name) {
  return const_cast<SceneObject*>(static_cast<const Scene&>(*this).findObject(name));
}

std::vector<widgets::WidgetId> Scene::latticesDeforming(const std::string& object) const {
  std::vector<widgets::WidgetId> result;
  for (const auto& attachment : attachments)
    if (std::find(attachment.objects.begin(), attachment.objects.end(), object) != attachment.objects.end())
      result.push_back(attachment.lattice);
  return result;
}

std::vector<widgets::WidgetId> Scene::stagesDeforming(const std::string& object) const {
  std::vector<widgets::WidgetId> stages;
  for (widgets::WidgetId root : latticesDeforming(object)) {
    const std::vector<widgets::WidgetId> tree = widgets.pipelineOrder(root);
    stages.insert(stages.end(), tree.begin(), tree.end());
  }
  return stages;
}

MeshData buildObjectMesh(const ObjectSource& source, const std::filesystem::path& baseDirectory,
                         const GeneratorRegistry& generators) {
  return std::visit(Overloaded{
                        [](const PrimitiveOptions& primitive) {
                          const geometry::TriangleMesh mesh = makePrimitive(primitive);
                          return MeshData{mesh.vertices, mesh.triangles, {}, false};
                        },
                        [&](const MeshFileSource& file) {
                          const std::filesystem::path path(file.path);
                          MeshData mesh = readMesh(path.is_absolute() ? path : baseDirectory / path);
                          convertToZUp(mesh, file.up);
                          return mesh;
                        },
                        [&](const GeneratedSource& generated) {
                          return generators.generate(generated.generator, generated.parameters, generated.density);
                        }},
                    source);
}

widgets::WidgetId attachNewLattice(Scene& scene, const std::vector<std::string>& objects, const AttachOptions& options) {
  if (objects.empty()) throw std::invalid_argument("attach: name at least one object");
  Eigen::AlignedBox3d box;
  for (const auto& name : objects) {
    const SceneObject* object = scene.findObject(name);
    if (object == nullptr)
      throw std::invalid_argument("attach: unknown object '" + name + "' (known: " + knownObjects(scene) + ")");
    for (Eigen::Index i = 0; i < object->mesh.points.rows(); ++i) box.extend(Eigen::Vector3d(object->mesh.points.row(i)));
  }
  if (box.isEmpty()) throw std::invalid_argument("attach: the objects have no points");
  widgets::LatticeOptions lattice;
  lattice.name = options.latticeName;
  lattice.counts = options.counts;
  lattice.frame = fittedLatticeFrame(box, options.padding);
  lattice.settings = options.settings;
  const widgets::WidgetId id = scene.widgets.addLattice(lattice);
  scene.attachments.push_back(Attachment{id, objects});
  touchStructure(scene);
  return id;
}

void detachLattice(Scene& scene, widgets::WidgetId lattice, const std::string& object) {
  for (auto it = scene.attachments.begin(); it != scene.attachments.end(); ++it) {
    if (it->lattice != lattice) continue;
    auto o = std::find(it->objects.begin(), it->objects.end(), object);
    if (o == it->objects.end()) continue;
    it->objects.erase(o);
    if (it->objects.empty()) scene.attachments.erase(it);
    touchStructure(scene);
    return;
  }
  const std::string name = scene.widgets.contains(lattice) ? scene.widgets.name(lattice) : widgets::toString(lattice);
  throw std::invalid_argument("detach: lattice '" + name + "' does not deform object '" + object + "'");
}

void validateScene(const Scene& scene) {
  std::set<std::string> names;
  for (const auto& object : scene.objects) {
    if (object.name.empty()) throw std::invalid_argument("scene: an object has an empty name");
    if (!names.insert(object.name).second) throw std::invalid_argument("scene: duplicate object name '" + object.name + "'");
  }
  std::set<std::pair<widgets::WidgetId, std::string>> pairs;
  for (const auto& attachment : scene.attachments) {
    const widgets::WidgetId id = attachment.lattice;
    if (!scene.widgets.contains(id))
      throw std::invalid_argument("scene: an attachment holds lattice " + widgets::toString(id) +
                                  ", which the widget model does not have");
    const std::string& name = scene.widgets.name(id);
    if (scene.widgets.type(id) != widgets::WidgetType::Lattice)
      throw std::invalid_argument("scene: attachment names '" + name + "', which is not a lattice widget");
    if (scene.widgets.parentCell(id).has_value())
      throw std::invalid_argument("scene: attachment names '" + name +
                                  "', a child lattice: attach its root (children deform through it)");
    for (const auto& object : attachment.objects) {
      if (names.count(object) == 0)
        throw std::invalid_argument("scene: lattice '" + name + "' is attached to unknown object '" + object +
                                    "' (known: " + knownObjects(scene) + ")");
      if (!pairs.insert({id, object}).second)
        throw std::invalid_argument("scene: lattice '" + name + "' is attached to '" + object + "' twice");
    }
  }
}

}  // namespace ffdkit::scenes
