#include "ffdkit/scenes/scene.h"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "ffdkit/scenes/cad_objects.h"
#include "ffdkit/scenes/lattice_fit.h"
#include "ffdkit/scenes/volume_object.h"

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
  for (const auto& o : scene.objects()) list += (list.empty() ? "" : ", ") + o.name;
  return list.empty() ? "none" : list;
}

}  // namespace

const SceneObject* Scene::findObject(const std::string& name) const {
  for (const auto& object : objects_)
    if (object.name == name) return &object;
  return nullptr;
}

const SceneObject* Scene::findObject(ObjectId id) const {
  for (const auto& object : objects_)
    if (object.id == id) return &object;
  return nullptr;
}

ObjectId Scene::objectId(const std::string& name) const {
  const SceneObject* found = findObject(name);
  if (found == nullptr) throw std::invalid_argument("scene: unknown object '" + name + "' (known: " + knownObjects(*this) + ")");
  return found->id;
}

const std::string& Scene::objectName(ObjectId id) const {
  const SceneObject* found = findObject(id);
  if (found == nullptr) throw std::invalid_argument("scene: no object " + toString(id) + " (known: " + knownObjects(*this) + ")");
  return found->name;
}

SceneObject& Scene::object(ObjectId id) {
  auto found = std::find_if(objects_.begin(), objects_.end(), [&](const SceneObject& o) { return o.id == id; });
  if (found == objects_.end()) throw std::invalid_argument("scene: no object " + toString(id) + " (known: " + knownObjects(*this) + ")");
  return *found;
}

SceneObject& Scene::object(const std::string& name) {
  auto found = std::find_if(objects_.begin(), objects_.end(), [&](const SceneObject& o) { return o.name == name; });
  if (found == objects_.end()) throw std::invalid_argument("scene: unknown object '" + name + "' (known: " + knownObjects(*this) + ")");
  return *found;
}

ObjectId Scene::addObject(SceneObject object) { return insertObject(objects_.size(), std::move(object)); }

ObjectId Scene::insertObject(std::size_t position, SceneObject object) {
  if (position > objects_.size())
    throw std::invalid_argument("scene: no place " + std::to_string(position) + " among " + std::to_string(objects_.size()) + " objects");
  if (object.name.empty()) throw std::invalid_argument("scene: an object needs a name");
  if (findObject(object.name) != nullptr) throw std::invalid_argument("scene: an object named '" + object.name + "' exists");
  if (!object.id.valid() || findObject(object.id) != nullptr) {
    if (nextObjectId_ == ObjectId::kInvalid) throw std::invalid_argument("scene: out of object ids");
    object.id = ObjectId{nextObjectId_};
  }
  nextObjectId_ = std::max(nextObjectId_, object.id.value + 1);
  const ObjectId id = object.id;
  const std::uint64_t r = stamp();
  object.meshRevision = object.displayRevision = r;
  structureRevision_ = r;
  objects_.insert(objects_.begin() + static_cast<std::ptrdiff_t>(position), std::move(object));
  return id;
}

void Scene::removeObject(const std::string& name) { takeObject(name); }

SceneObject Scene::takeObject(const std::string& objectName) { return takeObject(objectId(objectName)); }

SceneObject Scene::takeObject(ObjectId id) {
  SceneObject& found = object(id);
  SceneObject taken = std::move(found);
  objects_.erase(objects_.begin() + (&found - objects_.data()));
  for (Attachment& a : attachments_) std::erase(a.objects, id);
  std::erase_if(attachments_, [](const Attachment& a) { return a.objects.empty(); });
  structureRevision_ = stamp();
  return taken;
}

void Scene::renameObject(const std::string& fromName, const std::string& to) { renameObject(objectId(fromName), to); }

void Scene::renameObject(ObjectId id, const std::string& to) {
  SceneObject& o = object(id);
  if (to == o.name) return;
  if (to.empty()) throw std::invalid_argument("scene: an object needs a name");
  if (findObject(to) != nullptr) throw std::invalid_argument("scene: an object named '" + to + "' exists");
  o.name = to;
  structureRevision_ = stamp();
}

void Scene::setObjectMesh(const std::string& name, MeshData mesh, std::optional<ObjectSource> source) {
  SceneObject& o = object(name);
  o.mesh = std::move(mesh);
  if (source) o.source = std::move(*source);
  o.meshRevision = stamp();
}

Eigen::MatrixX3d Scene::takeObjectPoints(const std::string& name) {
  SceneObject& o = object(name);
  Eigen::MatrixX3d points = std::move(o.mesh.points);
  o.mesh.points.resize(0, 3);
  o.meshRevision = stamp();
  return points;
}

void Scene::setObjectDisplay(const std::string& name, const DisplaySettings& display) {
  SceneObject& o = object(name);
  o.display = display;
  o.displayRevision = stamp();
}

void Scene::setAttachments(std::vector<Attachment> attachments) {
  if (attachments == attachments_) return;
  attachments_ = std::move(attachments);
  structureRevision_ = stamp();
}

void Scene::attach(widgets::WidgetId lattice, const std::string& object) { attach(lattice, objectId(object)); }

void Scene::attach(widgets::WidgetId lattice, ObjectId object) {
  auto it = std::find_if(attachments_.begin(), attachments_.end(), [&](const Attachment& a) { return a.lattice == lattice; });
  if (it == attachments_.end()) {
    attachments_.push_back({lattice, {object}});
  } else if (std::find(it->objects.begin(), it->objects.end(), object) == it->objects.end()) {
    it->objects.push_back(object);
  } else {
    return;
  }
  structureRevision_ = stamp();
}

void Scene::detach(widgets::WidgetId lattice, const std::string& object) {
  const SceneObject* found = findObject(object);
  if (found == nullptr) {
    const std::string name = widgets.contains(lattice) ? widgets.name(lattice) : widgets::toString(lattice);
    throw std::invalid_argument("detach: lattice '" + name + "' does not deform object '" + object + "'");
  }
  detach(lattice, found->id);
}

void Scene::detach(widgets::WidgetId lattice, ObjectId object) {
  for (auto it = attachments_.begin(); it != attachments_.end(); ++it) {
    if (it->lattice != lattice) continue;
    auto o = std::find(it->objects.begin(), it->objects.end(), object);
    if (o == it->objects.end()) continue;
    it->objects.erase(o);
    if (it->objects.empty()) attachments_.erase(it);
    structureRevision_ = stamp();
    return;
  }
  const std::string name = widgets.contains(lattice) ? widgets.name(lattice) : widgets::toString(lattice);
  const SceneObject* found = findObject(object);
  throw std::invalid_argument("detach: lattice '" + name + "' does not deform object '" +
                              (found != nullptr ? found->name : toString(object)) + "'");
}

void Scene::dropStaleAttachments() {
  if (std::erase_if(attachments_, [&](const Attachment& a) { return !widgets.contains(a.lattice); }) > 0)
    structureRevision_ = stamp();
}

std::vector<widgets::WidgetId> Scene::latticesDeforming(const std::string& object) const {
  const SceneObject* found = findObject(object);
  return found != nullptr ? latticesDeforming(found->id) : std::vector<widgets::WidgetId>{};
}

std::vector<widgets::WidgetId> Scene::stagesDeforming(const std::string& object) const {
  const SceneObject* found = findObject(object);
  return found != nullptr ? stagesDeforming(found->id) : std::vector<widgets::WidgetId>{};
}

std::vector<widgets::WidgetId> Scene::latticesDeforming(ObjectId object) const {
  std::vector<widgets::WidgetId> result;
  for (const auto& attachment : attachments_)
    if (std::find(attachment.objects.begin(), attachment.objects.end(), object) != attachment.objects.end())
      result.push_back(attachment.lattice);
  return result;
}

std::vector<widgets::WidgetId> Scene::stagesDeforming(ObjectId object) const {
  std::vector<widgets::WidgetId> stages;
  for (widgets::WidgetId root : latticesDeforming(object)) {
    const std::vector<widgets::WidgetId> tree = widgets.pipelineOrder(root);
    stages.insert(stages.end(), tree.begin(), tree.end());
  }
  return stages;
}

void Scene::setCamera(const Camera& camera) {
  camera_ = camera;
  cameraRevision_ = stamp();
}

void Scene::setBackground(const Eigen::Vector3d& background) {
  background_ = background;
  cameraRevision_ = stamp();
}

void Scene::setAnimation(Animation animation) {
  animation_ = std::move(animation);
  animationRevision_ = stamp();
}

void Scene::setFrameRate(double framesPerSecond) {
  animation_.framesPerSecond = framesPerSecond;
  animationRevision_ = stamp();
}

void Scene::setFrameRange(int first, int last) {
  animation_.firstFrame = first;
  animation_.lastFrame = last;
  animationRevision_ = stamp();
}

MeshData buildObjectMesh(const ObjectSource& source, const std::filesystem::path& baseDirectory,
                         const GeneratorRegistry& generators) {
  return buildObjectMesh(source, baseDirectory, ObjectMeshOptions{.generators = &generators, .confinement = {.allowOutside = true}});
}

MeshData buildObjectMesh(const ObjectSource& source, const std::filesystem::path& baseDirectory,
                         const ObjectMeshOptions& options) {
  meshio::ReadBudget ownBudget;
  meshio::ReadBudget& budget = options.budget != nullptr ? *options.budget : ownBudget;
  const GeneratorRegistry& generators = options.generators != nullptr ? *options.generators : builtinGenerators();
  return std::visit(
      Overloaded{[&](const PrimitiveOptions& primitive) {
                   chargePrimitive(budget, primitive);
                   // The welding storage lives only while the primitive is built.
                   const PrimitiveSize size = primitiveSize(primitive);
                   const std::uint64_t building = size.vertices * kPrimitiveWeldBytesPerVertex +
                                                  size.triangles * kPrimitiveBuildBytesPerTriangle;
                   budget.chargeBytes(1, building,
                                      "primitive " + std::string(primitiveKindName(primitive.kind)) + ": welding its seams");
                   const geometry::TriangleMesh mesh = makePrimitive(primitive);
                   budget.releaseBytes(building);
                   return MeshData{mesh.vertices, mesh.triangles, {}, false};
                 },
                 [&](const MeshFileSource& file) {
                   const std::filesystem::path path = meshio::confinedPath(baseDirectory, file.path, "mesh file", options.confinement);
                   // A solver's volume mesh: every point, and its boundary surface to draw (volume_object.h).
                   if (meshio::volumeMeshFormatOf(path)) return volumeObjectMesh(path, file.up, budget, options.confinement);
                   // A STEP or IGES part: its tessellation, by the reader the program registered
                   // (Z up: CAD files are not turned).
                   if (isCadFile(path)) return readCadMesh(path, budget);
                   MeshData mesh = readMesh(path, meshio::MeshReadOptions{.limits = budget.limits(), .budget = &budget, .confinement = options.confinement});
                   convertToZUp(mesh, file.up);
                   return mesh;
                 },
                 [&](const GeneratedSource& generated) {
                   return generators.generate(generated.generator, generated.parameters, generated.density, budget);
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
  for (const std::string& object : objects) scene.attach(id, object);
  return id;
}

void validateScene(const Scene& scene) {
  std::set<std::string> names;
  std::set<ObjectId> ids;
  for (const auto& object : scene.objects()) {
    if (object.name.empty()) throw std::invalid_argument("scene: an object has an empty name");
    if (!names.insert(object.name).second) throw std::invalid_argument("scene: duplicate object name '" + object.name + "'");
    if (!object.id.valid() || !ids.insert(object.id).second)
      throw std::invalid_argument("scene: object '" + object.name + "' has no id of its own (" + toString(object.id) + ")");
  }
  std::set<std::pair<widgets::WidgetId, ObjectId>> pairs;
  for (const auto& attachment : scene.attachments()) {
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
    for (const ObjectId object : attachment.objects) {
      const SceneObject* found = scene.findObject(object);
      if (found == nullptr)
        throw std::invalid_argument("scene: lattice '" + name + "' is attached to unknown object " + toString(object) +
                                    " (known: " + knownObjects(scene) + ")");
      if (!pairs.insert({id, object}).second)
        throw std::invalid_argument("scene: lattice '" + name + "' is attached to '" + found->name + "' twice");
    }
  }
}

}  // namespace ffdkit::scenes
