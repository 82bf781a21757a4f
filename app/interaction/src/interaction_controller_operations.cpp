// The interaction controller, document operations: each an undoable edit (one command holding
// its delta) of the widget model, the attachments or the objects.
#include "ffdkit/interaction/interaction_controller.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <type_traits>

#include "ffdkit/interaction/cell_from_selection.h"
#include "ffdkit/ffd/cylindrical_lattice.h"
#include "ffdkit/ffd/pipeline.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/document_delta.h"
#include "ffdkit/scenes/lattice_fit.h"
#include "ffdkit/scenes/scene_changes.h"

namespace ffdkit::app {

using widgets::WidgetId;
using widgets::WidgetType;

void fitAndAttachLattice(scenes::Scene& scene, WidgetId lattice, const std::string& objectName) {
  const scenes::SceneObject* object = scene.findObject(objectName);
  if (object == nullptr) throw std::invalid_argument("no object '" + objectName + "'");
  if (object->mesh.points.rows() == 0) throw std::invalid_argument("object '" + objectName + "' has no points");
  if (scene.widgets.parentCell(lattice))
    throw std::invalid_argument("'" + scene.widgets.name(lattice) + "' is a child lattice: attach its root");
  // The same rule as scenes::attachNewLattice (lattice_fit.h).
  const Eigen::AlignedBox3d bounds(object->mesh.points.colwise().minCoeff().transpose(),
                                   object->mesh.points.colwise().maxCoeff().transpose());
  scene.widgets.setLatticeFrame(lattice, scenes::fittedLatticeFrame(bounds, 0.05));
  scene.attach(lattice, objectName);
  scenes::validateScene(scene);
}

// ---- operations --------------------------------------------------------------------------

template <class Change>
auto InteractionController::edit(const std::string& description, Change change, const std::string& mergeKey) {
  if (dragging_) cancel();
  // The model's data and the attachments before the change (transient: the command keeps only
  // the records that differ), and the objects there were.
  const widgets::WidgetModelData widgetsBefore = scene_.widgets.toData();
  const std::vector<scenes::Attachment> attachmentsBefore = scene_.attachments();
  const std::size_t objectsBefore = scene_.objects().size();
  const widgets::WidgetModelState animatedBefore = scenes::animatedState(scene_);
  auto deltaFromBefore = [&] {
    scenes::SceneDelta delta;
    delta.widgets = scenes::modelPatch(widgetsBefore, scene_.widgets.toData());
    if (!(attachmentsBefore == scene_.attachments())) delta.attachments = std::pair(attachmentsBefore, scene_.attachments());
    return delta;
  };
  auto finish = [&] {
    auto delta = std::make_shared<const scenes::SceneDelta>(deltaFromBefore());
    // Objects the change added (appended): moved out of the scene into `held` on undo, back on
    // redo; the command holds an object only while it is undone.
    auto held = std::make_shared<std::vector<scenes::SceneObject>>();
    const std::size_t added = scene_.objects().size() - objectsBefore;
    // The animated channels' values before and after the change: its undo or redo after a frame
    // change swaps the records back as at the edit's frame and carries them to the frame shown
    // (scenes::restoreAtEditValues).
    auto animated = std::make_shared<const scenes::StateDelta>(scenes::StateDelta{animatedBefore, scenes::animatedState(scene_)});
    const std::uint64_t madeAt = animationApplications_;
    auto carried = std::make_shared<std::optional<scenes::CarriedStep>>();  // makes an undo's redo exact
    auto apply = [this, delta, held, added, objectsBefore, animated, madeAt, carried](bool forward) {
      scenes::restoreAtEditValues(scene_, forward ? animated->before : animated->after, animationAppliedSince(madeAt), [&] {
        if (!forward) {
          for (std::size_t i = 0; i < added; ++i) held->push_back(scene_.takeObject(scene_.objects()[objectsBefore].id));
        }
        scenes::applySceneDelta(scene_, *delta, forward);
        if (forward && added > 0) {
          for (auto& object : *held) scene_.addObject(std::move(object));
          held->clear();
        }
      }, carried.get());
      pruneSelection();
      refresh();
      if (onStructureChanged) onStructureChanged();
    };
    // At once, not at the window's next frame: an edit whose result cannot be evaluated (a
    // degenerate lattice, an embedding cancelled) is refused and rolled back below.
    deformer_.evaluate(scene_);
    notify();
    if (onStructureChanged) onStructureChanged();
    // The step is pushed last, once the change holds: a throw above leaves no step whose undo
    // would undo nothing, and keeps the steps that could be redone.
    // Edits merge only within one frame: a merged step's undo writes back the first's values.
    const std::string mergeAtFrame = mergeKey.empty() ? mergeKey : mergeKey + "@" + std::to_string(madeAt);
    commands_.push(scenes::Command{description, [apply] { apply(false); }, [apply] { apply(true); }, mergeAtFrame,
                                   delta->bytes() + animated->bytes() + sizeof(*held)});
  };
  try {
    if constexpr (std::is_void_v<decltype(change())>) {
      change();
      finish();
    } else {
      auto result = change();
      finish();
      return result;
    }
  } catch (...) {
    // A failed edit leaves no trace.
    scenes::applySceneDelta(scene_, deltaFromBefore(), /*forward=*/false);
    while (scene_.objects().size() > objectsBefore) scene_.takeObject(scene_.objects().back().id);
    pruneSelection();
    refresh();
    if (onStructureChanged) onStructureChanged();
    throw;
  }
}

void InteractionController::setDisplay(const std::vector<std::string>& objects,
                                       const std::vector<scenes::DisplaySettings>& looks,
                                       const std::string& description) {
  if (objects.size() != looks.size()) throw std::invalid_argument("setDisplay: one look per object");
  std::vector<scenes::DisplaySettings> before;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const scenes::SceneObject* object = scene_.findObject(objects[i]);
    if (object == nullptr) throw std::invalid_argument("no object '" + objects[i] + "'");
    const scenes::DisplaySettings& look = looks[i];
    if (look.zebraStripes < 1 || look.zebraStripes > 256)
      throw std::invalid_argument("zebra stripes must be in [1, 256], got " + std::to_string(look.zebraStripes));
    if (!(look.zebraDirection.norm() > 1e-12)) throw std::invalid_argument("the zebra direction must not be zero");
    if (!(look.combScale > 0.0)) throw std::invalid_argument("the comb scale must be positive");
    before.push_back(object->display);
  }
  if (before == looks) return;
  auto restore = [this, objects](const std::vector<scenes::DisplaySettings>& set) {
    for (std::size_t i = 0; i < objects.size(); ++i)
      if (scene_.findObject(objects[i]) != nullptr) scene_.setObjectDisplay(objects[i], set[i]);
    notify();
  };
  restore(looks);
  std::string key = "look";
  for (const std::string& name : objects) key += "/" + name;
  const std::size_t bytes = 2 * looks.size() * sizeof(scenes::DisplaySettings);
  commands_.push(scenes::Command{description, [restore, before] { restore(before); }, [restore, looks] { restore(looks); },
                                 key, bytes});
}

WidgetId InteractionController::newLattice(const NewLatticeOptions& options) {
  return edit("New lattice", [&] {
    widgets::LatticeOptions lattice;
    lattice.counts = options.counts;
    lattice.settings.basis = options.basis;
    if (options.cylindrical) {
      ffd::CylindricalLatticeOptions cylinder;
      cylinder.counts = options.counts;
      cylinder.bases = options.basis;
      if (cylinder.bases[1].kind != ffd::AxisBasis::Kind::PeriodicBSpline)
        cylinder.bases[1] = ffd::AxisBasis::periodic(std::min(3, options.counts.y() - 1));
      cylinder.outerRadius = 0.5;  // in the unit box like a box lattice
      cylinder.zMin = 0.0;
      cylinder.zMax = 1.0;
      cylinder.frame = Eigen::Translation3d(0.5, 0.5, 0.0);
      const ffd::Lattice rest = ffd::makeCylindricalLattice(cylinder);
      lattice.restPoints = rest.restPoints();
      lattice.settings.basis = cylinder.bases;
      lattice.settings.cylinder = rest.cylinderRestShape();
      lattice.frame = cylinder.frame;
    }
    const WidgetId id = scene_.widgets.addLattice(lattice);
    selection_ = {id};
    return id;
  });
}

WidgetId InteractionController::addCell(WidgetId lattice, const widgets::CellSpec& spec) {
  return edit("Make " + std::string(widgets::cellKindName(spec.kind)) + " cell", [&] {
    const WidgetId id = scene_.widgets.addCell(lattice, spec);
    selection_ = {id};
    point_.reset();
    return id;
  });
}

WidgetId InteractionController::addAffine(WidgetId cell, widgets::AffineKind kind) {
  if (scene_.widgets.contains(cell) && scene_.widgets.type(cell) == WidgetType::Cell)
    if (const auto why = affineRefusal(kind, scene_.widgets.cellSpec(cell).kind)) throw std::invalid_argument(*why);
  return edit("Add " + std::string(widgets::affineKindName(kind)) + " widget", [&] {
    const WidgetId id = scene_.widgets.addAffine(cell, kind);
    selection_ = {id};
    return id;
  });
}

WidgetId InteractionController::addAffineAtPoint(const LatticePointRef& point, widgets::AffineKind kind) {
  if (const auto why = affineRefusal(kind, widgets::CellKind::Point)) throw std::invalid_argument(*why);
  return edit("Add " + std::string(widgets::affineKindName(kind)) + " widget", [&] {
    auto& m = scene_.widgets;
    std::optional<WidgetId> cell;
    for (WidgetId c : m.cellsOf(point.lattice)) {
      const auto& indices = m.cellIndices(c);
      if (m.cellSpec(c).kind == widgets::CellKind::Point && indices.size() == 1 && indices.front() == point.index)
        cell = c;
    }
    if (!cell) {
      const Eigen::Vector3i n = m.counts(point.lattice);
      const int i = static_cast<int>(point.index % n.x());
      const int j = static_cast<int>((point.index / n.x()) % n.y());
      const int k = static_cast<int>(point.index / (n.x() * n.y()));
      cell = m.addCell(point.lattice, widgets::CellSpec::point(i, j, k));
    }
    const WidgetId id = m.addAffine(*cell, kind);
    selection_ = {id};
    point_.reset();
    return id;
  });
}

widgets::BindingId InteractionController::bind(WidgetId a, WidgetId b) {
  return edit("Bind " + scene_.widgets.name(a) + " - " + scene_.widgets.name(b),
              [&] { return scene_.widgets.bind(a, b); });
}

void InteractionController::unbind(widgets::BindingId binding) {
  edit("Unbind", [&] { scene_.widgets.unbind(binding); });
}

void InteractionController::removeWidget(WidgetId id) {
  edit("Remove " + scene_.widgets.name(id), [&] {
    scene_.widgets.remove(id);
    scene_.dropStaleAttachments();
    selection_.clear();
    point_.reset();
  });
}

void InteractionController::attachLattice(WidgetId lattice, const std::string& objectName) {
  edit("Attach " + scene_.widgets.name(lattice) + " to " + objectName, [&] {
    fitAndAttachLattice(scene_, lattice, objectName);
  });
}

void InteractionController::detachLattice(WidgetId lattice, const std::string& object) {
  edit("Detach " + scene_.widgets.name(lattice) + " from " + object,
       [&] { scene_.detach(lattice, object); });
}

std::string InteractionController::addPrimitive(const scenes::PrimitiveOptions& options) {
  return edit(
      "Add " + std::string(scenes::primitiveKindName(options.kind)),
      [&] {
        const std::string base(scenes::primitiveKindName(options.kind));
        std::string name;
        for (int n = 1; name.empty() || scene_.findObject(name) != nullptr; ++n) name = base + std::to_string(n);
        scenes::SceneObject object;
        object.name = name;
        object.source = options;
        object.mesh = scenes::buildObjectMesh(object.source, ".");
        scene_.addObject(std::move(object));
        return name;
      });
}

void InteractionController::addObject(scenes::SceneObject object) {
  edit(
      "Import " + object.name,
      [&] {
        if (scene_.findObject(object.name) != nullptr) throw std::invalid_argument("object '" + object.name + "' exists");
        scene_.addObject(std::move(object));
      });
}

void InteractionController::setVariation(WidgetId affine, double value) {
  edit("Set variation of " + scene_.widgets.name(affine), [&] { scene_.widgets.setVariation(affine, value); },
       "variation/" + widgets::toString(affine));
}

void InteractionController::setPlacement(WidgetId affine, const Eigen::Affine3d& placement) {
  edit("Place " + scene_.widgets.name(affine), [&] { scene_.widgets.setPlacement(affine, placement); },
       "placement/" + widgets::toString(affine));
}

void InteractionController::setGlyph(WidgetId affine, const widgets::Glyph& glyph) {
  edit("Glyph of " + scene_.widgets.name(affine), [&] { scene_.widgets.setGlyph(affine, glyph); },
       "glyph/" + widgets::toString(affine));
}

void InteractionController::setAffineKind(WidgetId affine, widgets::AffineKind kind) {
  edit("Make " + scene_.widgets.name(affine) + " a " + std::string(widgets::affineKindName(kind)) + " widget",
       [&] { scene_.widgets.setAffineKind(affine, kind); });
}

void InteractionController::setLatticeCounts(WidgetId lattice, const Eigen::Vector3i& counts) {
  edit("Set counts of " + scene_.widgets.name(lattice), [&] { scene_.widgets.setLatticeCounts(lattice, counts); });
}

void InteractionController::setOneWay(widgets::BindingId binding, bool oneWay) {
  edit(oneWay ? "Make binding one-way" : "Make binding two-way", [&] { scene_.widgets.setOneWay(binding, oneWay); });
}

void InteractionController::setMask(widgets::BindingId binding, widgets::AffineMask mask) {
  edit("Set mask " + widgets::maskString(mask), [&] { scene_.widgets.setMask(binding, mask); });
}

void InteractionController::setRule(widgets::BindingId binding, const widgets::ConversionRule& rule) {
  edit("Set conversion rule", [&] { scene_.widgets.setRule(binding, rule); }, "rule/" + widgets::toString(binding));
}

void InteractionController::setLatticeSettings(WidgetId lattice, const widgets::LatticeSettings& settings) {
  edit("Lattice settings of " + scene_.widgets.name(lattice),
       [&] { scene_.widgets.setLatticeSettings(lattice, settings); });
}

void InteractionController::setWeight(WidgetId lattice, const std::vector<Eigen::Index>& points, double weight) {
  if (points.empty()) throw std::invalid_argument("setWeight: no control points given");
  const std::string which =
      points.size() == 1 ? "point " + std::to_string(points.front()) : std::to_string(points.size()) + " points";
  edit("Weight of " + which + " of " + scene_.widgets.name(lattice), [&] {
    for (Eigen::Index point : points) scene_.widgets.setWeight(lattice, point, weight);
  });
}

void InteractionController::setLatticeFrame(WidgetId lattice, const Eigen::Affine3d& frame) {
  edit("Place " + scene_.widgets.name(lattice), [&] { scene_.widgets.setLatticeFrame(lattice, frame); },
       "frame/" + widgets::toString(lattice));
}

void InteractionController::setSiblingPosition(WidgetId lattice, std::size_t position) {
  edit("Reorder " + scene_.widgets.name(lattice), [&] { scene_.widgets.setSiblingPosition(lattice, position); });
}

void InteractionController::replaceWidgets(widgets::WidgetModel model, const std::optional<std::string>& attachTo) {
  edit(attachTo ? "Open widget file on " + *attachTo : std::string("Open widget file"), [&] {
    // Another model has its own ids: an attachment goes over to the new root of its lattice's
    // name, or goes.
    std::vector<std::pair<std::string, std::vector<scenes::ObjectId>>> named;
    for (const scenes::Attachment& a : scene_.attachments()) named.emplace_back(scene_.widgets.name(a.lattice), a.objects);
    scene_.widgets = std::move(model);
    std::vector<scenes::Attachment> attachments;
    const std::vector<WidgetId> roots = scene_.widgets.roots();
    for (auto& [name, objects] : named) {
      // Compared by a plain reference: clang before 16 cannot capture a structured binding.
      const std::string& latticeName = name;
      const auto root = std::find_if(roots.begin(), roots.end(), [&](WidgetId r) { return scene_.widgets.name(r) == latticeName; });
      if (root != roots.end()) attachments.push_back({*root, std::move(objects)});
    }
    scene_.setAttachments(std::move(attachments));
    if (attachTo)
      for (WidgetId root : scene_.widgets.roots()) fitAndAttachLattice(scene_, root, *attachTo);
    selection_.clear();
    point_.reset();
    hovered_.reset();
  });
}

void InteractionController::removeObjects(const std::vector<std::string>& objects) {
  for (const std::string& object : objects)
    if (scene_.findObject(object) == nullptr) throw std::invalid_argument("no object '" + object + "'");
  if (objects.empty()) return;
  if (dragging_) cancel();
  std::string description = "Delete " + objects.front();
  if (objects.size() > 1) description += " and " + std::to_string(objects.size() - 1) + " more";
  // The command holds the removed objects (with their places) while they are removed, and the
  // attachments before (a few ids); Scene::takeObject drops each from its attachments. Objects
  // are held by id (a put-back object keeps its id, so a redo removes the same ones).
  auto held = std::make_shared<std::vector<std::pair<std::size_t, scenes::SceneObject>>>();
  const auto attachmentsBefore = std::make_shared<const std::vector<scenes::Attachment>>(scene_.attachments());
  std::vector<scenes::ObjectId> ids;
  for (const std::string& object : objects) ids.push_back(scene_.objectId(object));
  auto remove = [this, ids, held] {
    for (std::size_t i = scene_.objects().size(); i-- > 0;)
      if (std::find(ids.begin(), ids.end(), scene_.objects()[i].id) != ids.end())
        held->emplace_back(i, scene_.takeObject(scene_.objects()[i].id));
  };
  auto putBack = [this, held, attachmentsBefore] {
    for (auto it = held->rbegin(); it != held->rend(); ++it)
      scene_.insertObject(it->first, std::move(it->second));
    held->clear();
    scene_.setAttachments(*attachmentsBefore);
  };
  auto after = [this] {
    pruneSelection();
    refresh();
    if (onStructureChanged) onStructureChanged();
  };
  remove();
  std::size_t bytes = 0;
  for (const auto& [place, object] : *held)
    bytes += sizeof(object) + 8 * static_cast<std::size_t>(object.mesh.points.size()) +
             4 * static_cast<std::size_t>(object.mesh.triangles.size() + object.mesh.segments.size());
  commands_.push(scenes::Command{description,
                                 [putBack, after] {
                                   putBack();
                                   after();
                                 },
                                 [remove, after] {
                                   remove();
                                   after();
                                 },
                                 {}, bytes});
  after();
}

void InteractionController::renameObject(const std::string& object, const std::string& name) {
  if (scene_.findObject(object) == nullptr) throw std::invalid_argument("no object '" + object + "'");
  if (name == object) return;
  if (name.empty()) throw std::invalid_argument("an object needs a name");
  if (scene_.findObject(name) != nullptr) throw std::invalid_argument("object name '" + name + "' is already used");
  if (dragging_) cancel();
  // By id: a name is a label, and the rename touches nothing else (no pipeline, no actor).
  const scenes::ObjectId id = scene_.objectId(object);
  auto rename = [this, id](const std::string& to) {
    scene_.renameObject(id, to);
    refresh();
    if (onStructureChanged) onStructureChanged();
  };
  rename(name);
  commands_.push(scenes::Command{"Rename " + object + " to " + name, [rename, object] { rename(object); },
                                 [rename, name] { rename(name); }, {}, 0});
}

void InteractionController::renameWidget(WidgetId id, const std::string& name) {
  const std::string old = scene_.widgets.name(id);
  if (name == old) return;
  edit("Rename " + old + " to " + name, [&] {
    // Attachments and animation channels hold the id: nothing else changes.
    scene_.widgets.rename(id, name);
  });
}

}  // namespace ffdkit::app
