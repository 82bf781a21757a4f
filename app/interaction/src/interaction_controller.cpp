#include "ffdkit/app/interaction_controller.h"

#include <algorithm>
#include <cctype>
#include <functional>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <type_traits>

#include "ffdkit/app/cell_from_selection.h"
#include "ffdkit/ffd/cylindrical_lattice.h"
#include "ffdkit/ffd/direct_manipulation.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/pipeline.h"
#include "ffdkit/scenes/document_delta.h"
#include "ffdkit/scenes/lattice_fit.h"
#include "ffdkit/scenes/scene_changes.h"

namespace ffdkit::app {

using widgets::WidgetId;
using widgets::WidgetType;

namespace {
/// "Move x", "Turn z", ...: the undo text of a handle drag.
std::string handleDragDescription(TransformerHandle handle) {
  std::string text = transformerHandleName(handle);
  text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
  return text;
}
}  // namespace

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
  const std::string& name = scene.widgets.name(lattice);
  auto it = std::find_if(scene.attachments.begin(), scene.attachments.end(),
                         [&](const scenes::Attachment& a) { return a.lattice == name; });
  if (it == scene.attachments.end()) {
    scene.attachments.push_back({name, {objectName}});
  } else if (std::find(it->objects.begin(), it->objects.end(), objectName) == it->objects.end()) {
    it->objects.push_back(objectName);
  }
  scenes::touchStructure(scene);
  scenes::validateScene(scene);
}

InteractionController::InteractionController(scenes::Scene& scene, scenes::SceneDeformer& deformer,
                                             scenes::CommandStack& commands)
    : scene_(scene), deformer_(deformer), commands_(commands) {}

// ---- pointer ---------------------------------------------------------------------------

bool InteractionController::hover(const widgets::Ray& ray, double tolerance) {
  if (dragging_) return false;
  widgets::PickOptions options;
  options.tolerance = tolerance;
  const auto hit = scene_.widgets.pick(ray, options);
  // The order of press(): glyphs and cells, lattice points, then the transformer's handles.
  std::optional<TransformerHandle> handle;
  if (!hit)
    if (const auto gizmo = transformer(); gizmo && !pickPoint(ray, tolerance))
      handle = pickTransformer(*gizmo, ray, tolerance);
  const bool handleChanged = handle != hoveredHandle_;
  hoveredHandle_ = handle;
  if (handle) {
    const bool changed = handleChanged || hovered_.has_value();
    hovered_.reset();
    if (changed) notify();
    return changed;
  }
  const std::optional<WidgetId> now = hit ? std::optional<WidgetId>(hit->id) : std::nullopt;
  if (now == hovered_ && !handleChanged) return false;
  hovered_ = now;
  notify();
  return true;
}

InteractionController::PressResult InteractionController::press(const widgets::Ray& ray, double tolerance, bool extend,
                                                                bool lattices) {
  if (dragging_) cancel();
  widgets::PickOptions options;
  options.tolerance = tolerance;
  if (lattices) {
    options.affines = false;
    options.cells = false;
    options.lattices = true;
  }
  const auto hit = scene_.widgets.pick(ray, options);
  if (hit) {
    if (!extend) selection_.clear();
    if (std::find(selection_.begin(), selection_.end(), hit->id) == selection_.end()) selection_.push_back(hit->id);
    point_.reset();
    dragStart_ = scene_.widgets.captureState();
    scene_.widgets.beginDrag(hit->id, ray);
    dragging_ = true;
    dragLattice_ = activeLattice(hit->id);
    notify();
    return PressResult::Widget;
  }
  // A lattice control point: the target of "add widget" (a point cell is made on demand).
  const std::optional<LatticePointRef> best = pickPoint(ray, tolerance);
  // The model's own glyphs, cells and points come first (small targets, and dragging them is the
  // point of the tool); the transformer's larger handles take the rest.
  if (!best && !lattices)
    if (const auto gizmo = transformer())
      if (const auto handle = pickTransformer(*gizmo, ray, tolerance)) {
        beginHandleDrag(*gizmo, *handle, ray);
        return PressResult::Handle;
      }
  if (!best) return PressResult::Nothing;
  point_ = best;
  if (!extend) selection_.clear();
  selection_.push_back(best->lattice);
  notify();
  return PressResult::Point;
}

std::optional<LatticePointRef> InteractionController::pickPoint(const widgets::Ray& ray, double tolerance) const {
  const Eigen::Vector3d dir = ray.direction.normalized();
  std::optional<LatticePointRef> best;
  double bestT = std::numeric_limits<double>::infinity();
  for (WidgetId lattice : scene_.widgets.widgets(WidgetType::Lattice)) {
    const Eigen::MatrixX3d points = scene_.widgets.worldControlPoints(lattice);
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      const Eigen::Vector3d v = points.row(i).transpose() - ray.origin;
      const double t = v.dot(dir);
      if (t < 0.0 || (v - t * dir).norm() > tolerance || t >= bestT) continue;
      bestT = t;
      best = LatticePointRef{lattice, i};
    }
  }
  return best;
}

void InteractionController::beginHandleDrag(const Transformer& gizmo, TransformerHandle handle, const widgets::Ray& ray) {
  handleTarget_ = selection_.front();
  handleDrag_.emplace(gizmo, handle, ray);
  hoveredHandle_ = handle;
  point_.reset();
  if (scene_.widgets.type(handleTarget_) == WidgetType::Affine) {
    // The placement is not part of WidgetModelState: the command stores it (release()).
    handleStart_ = true;
    placementStart_ = scene_.widgets.placement(handleTarget_);
    placementBase_ = scene_.widgets.placementBase(handleTarget_);
    dragLattice_.reset();
  } else {
    // A lattice moves through a gesture: its frame (a root) or its parent cell (a child)
    // follows, bound widgets too, and the attached objects are re-embedded as it moves.
    handleStart_ = false;
    dragStart_ = scene_.widgets.captureState();
    scene_.widgets.beginGesture(handleTarget_);
    dragLattice_ = handleTarget_;
  }
  dragging_ = true;
  notify();
}

std::optional<std::string> InteractionController::pressObject(const widgets::Ray& ray, double tolerance, bool carryPins) {
  if (dragging_) cancel();
  const Eigen::Vector3d dir = ray.direction.normalized();
  const std::optional<ObjectPoint> best = objectPointAt(ray, tolerance);
  if (!best) return std::nullopt;
  const auto& [name, vertex] = *best;
  const std::vector<WidgetId> stages = scene_.stagesDeforming(name);
  if (stages.empty()) throw std::invalid_argument("'" + name + "' is not deformed by a lattice: attach one to drag its points");
  const Eigen::Vector3d own = scene_.findObject(name)->mesh.points.row(vertex).transpose();
  // From the last stage back: the first lattice whose input holds the point moves it; a later
  // one that does not hold it must leave it alone (identity outside policy).
  for (std::size_t k = stages.size(); k-- > 0;) {
    const ffd::Lattice lattice = scene_.widgets.ffdLattice(stages[k]);
    const Eigen::Vector3d input = pointBeforeStage(scene_, stages, k, own);
    const ffd::Embedding e = ffd::embed(lattice, input.transpose());
    if (e.status(0) == ffd::PointStatus::Inside) {
      ObjectGrab g;
      g.object = name;
      g.vertex = vertex;
      g.lattice = stages[k];
      g.weights = pinnedDragWeights(scene_, stages[k], e.parameters().row(0), *best, pins_, carryPins);
      g.worldToLocal = lattice.frame().linear().inverse();
      g.grab = deformer_.points(name).row(vertex).transpose();
      g.normal = dir;
      g.controlStart = scene_.widgets.controlPoints(stages[k]);
      objectGrab_ = std::move(g);
      dragStart_ = scene_.widgets.captureState();
      dragLattice_ = stages[k];
      dragging_ = true;
      notify();
      return name;
    }
    if (lattice.outsidePolicy().kind != ffd::OutsidePolicy::Kind::Identity)
      throw std::invalid_argument("point " + std::to_string(vertex) + " of '" + name + "' is outside lattice '" +
                                  scene_.widgets.name(stages[k]) +
                                  "', whose outside policy moves it: direct manipulation needs a point inside");
  }
  throw std::invalid_argument("point " + std::to_string(vertex) + " of '" + name +
                              "' is outside every lattice deforming it: nothing can move it");
}

void InteractionController::drag(const widgets::Ray& ray) {
  if (!dragging_) return;
  if (objectGrab_) {
    const ObjectGrab& g = *objectGrab_;
    const auto t = widgets::intersectPlane(ray, g.grab, g.normal);
    if (!t) return;  // parallel to the drag plane: keep the last position
    // World displacement -> lattice-local (world = frame * local), then HHK's least-norm change.
    const Eigen::Vector3d local = g.worldToLocal * (ray.at(*t) - g.grab);
    scene_.widgets.setControlPoints(g.lattice, g.controlStart + g.weights * local.transpose());
    deformer_.update(scene_, dragLattice_);
    notify();
    return;
  }
  if (handleDrag_) {
    applyHandleMotion(handleDrag_->motion(ray));
    return;
  }
  scene_.widgets.dragTo(ray);
  deformer_.update(scene_, dragLattice_);
  notify();
}

bool InteractionController::setDragValue(double value) {
  if (!dragging_ || objectGrab_) return false;
  if (handleDrag_) {
    applyHandleMotion(handleDrag_->motionFor(value));
    return true;
  }
  const auto widget = scene_.widgets.gestureWidget();
  if (!widget || scene_.widgets.type(*widget) != WidgetType::Affine) return false;
  scene_.widgets.updateGesture(value);
  deformer_.update(scene_, dragLattice_);
  notify();
  return true;
}

void InteractionController::applyHandleMotion(const Eigen::Affine3d& motion) {
  if (handleStart_) {
    // F' = M * F with F = base * placement (WidgetModel::placementBase).
    scene_.widgets.setPlacement(handleTarget_, placementBase_.inverse() * motion * placementBase_ * placementStart_);
    notify();  // a placement moves no points
    return;
  }
  scene_.widgets.updateGesture(motion);
  deformer_.update(scene_, dragLattice_);
  notify();
}

void InteractionController::release() {
  if (!dragging_) return;
  dragging_ = false;
  if (objectGrab_) {
    const std::string description = "Drag point " + std::to_string(objectGrab_->vertex) + " of " + objectGrab_->object;
    objectGrab_.reset();
    deformer_.finishGesture(scene_);
    pushState(description, scenes::stateDelta(dragStart_, scene_.widgets.captureState()));
    notify();
    return;
  }
  const std::optional<TransformerHandle> handle =
      handleDrag_ ? std::optional<TransformerHandle>(handleDrag_->handle()) : std::nullopt;
  handleDrag_.reset();
  if (handleStart_) {
    handleStart_ = false;
    if (scene_.widgets.placement(handleTarget_).matrix() != placementStart_.matrix()) {
      // The placement is not part of the model's state: its change is the command's delta.
      const WidgetId target = handleTarget_;
      const Eigen::Affine3d before = placementStart_, after = scene_.widgets.placement(target);
      auto place = [this, target](const Eigen::Affine3d& placement) {
        scene_.widgets.setPlacement(target, placement);
        notify();  // a placement moves no points
      };
      commands_.push(scenes::Command{handleDragDescription(handle.value_or(TransformerHandle::MoveX)) + " " +
                                         scene_.widgets.name(target),
                                     [place, before] { place(before); }, [place, after] { place(after); }, "",
                                     2 * sizeof(Eigen::Affine3d)});
    }
    notify();
    return;
  }
  const WidgetId target = *scene_.widgets.gestureWidget();
  scene_.widgets.endGesture();
  deformer_.finishGesture(scene_);  // the exact result, in one pass
  const std::string what = handle ? handleDragDescription(*handle) : std::string("Drag");
  // A click that selected a widget changed nothing: no command.
  pushState(what + " " + scene_.widgets.name(target), scenes::stateDelta(dragStart_, scene_.widgets.captureState()));
  notify();
}

void InteractionController::cancel() {
  if (!dragging_) return;
  dragging_ = false;
  if (objectGrab_) {
    scene_.widgets.setControlPoints(objectGrab_->lattice, objectGrab_->controlStart);
    objectGrab_.reset();
    refresh();
    return;
  }
  handleDrag_.reset();
  if (handleStart_) {
    scene_.widgets.setPlacement(handleTarget_, placementStart_);
    handleStart_ = false;
    notify();
    return;
  }
  scene_.widgets.cancelGesture();
  refresh();
}

void InteractionController::togglePin(const ObjectPoint& point) {
  const scenes::SceneObject* object = scene_.findObject(point.object);
  if (object == nullptr || point.vertex < 0 || point.vertex >= object->mesh.points.rows())
    throw std::invalid_argument("no point " + std::to_string(point.vertex) + " of '" + point.object + "' to pin");
  if (std::erase(pins_, point) == 0) pins_.push_back(point);
  notify();
}

void InteractionController::clearPins() {
  pins_.clear();
  notify();
}

std::optional<Transformer> InteractionController::transformer() const {
  if (selection_.size() != 1 || point_) return std::nullopt;
  const auto& m = scene_.widgets;
  const WidgetId id = selection_.front();
  if (!m.contains(id)) return std::nullopt;
  Transformer t;
  if (m.type(id) == WidgetType::Affine) {
    const widgets::WidgetFrame f = m.affineFrame(id);
    t.frame = f.frame;
    t.size = 2.5 * f.size;
    t.uniformSize = true;
    return t;
  }
  if (m.type(id) != WidgetType::Lattice) return std::nullopt;
  // At the centre of the rest lattice, along the rigid part of the frame (polar decomposition).
  const Eigen::Affine3d frame = m.latticeFrame(id);
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(frame.linear(), Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d rotation = svd.matrixU() * svd.matrixV().transpose();
  if (rotation.determinant() < 0.0) rotation = -rotation;  // a mirrored frame: keep right-handed axes
  const Eigen::MatrixX3d rest = m.worldRestPoints(id);
  t.frame.linear() = rotation;
  t.frame.translation() = rest.colwise().mean().transpose();
  t.size = std::max(0.3 * (rest.colwise().maxCoeff() - rest.colwise().minCoeff()).norm(), 1e-6);
  t.uniformSize = false;
  return t;
}

std::optional<TransformerHandle> InteractionController::transformerHandle() const {
  if (handleDrag_) return handleDrag_->handle();
  return transformer() ? hoveredHandle_ : std::nullopt;
}

std::optional<WidgetId> InteractionController::activeLattice(WidgetId id) const {
  const auto& m = scene_.widgets;
  switch (m.type(id)) {
    case WidgetType::Lattice: return id;
    case WidgetType::Cell: return m.latticeOf(id);
    case WidgetType::Affine:
      if (auto cell = m.attachedCell(id)) return m.latticeOf(*cell);
      return std::nullopt;
  }
  return std::nullopt;
}

// ---- selection -------------------------------------------------------------------------

void InteractionController::setSelection(std::vector<WidgetId> selection) {
  selection_ = std::move(selection);
  point_.reset();
  notify();
}

void InteractionController::setPickedPoint(std::optional<LatticePointRef> point) {
  point_ = point;
  notify();
}

void InteractionController::clearSelection() {
  if (selection_.empty() && !point_) return;
  selection_.clear();
  point_.reset();
  notify();
}

ViewHighlights InteractionController::highlights() const {
  ViewHighlights h;
  h.hovered = hovered_;
  h.selected = selection_;
  h.visited = scene_.widgets.gestureVisitOrder();
  h.point = point_;
  h.transformer = transformer();
  h.transformerHandle = transformerHandle();
  for (const ObjectPoint& pin : pins_)
    if (const scenes::SceneObject* o = scene_.findObject(pin.object); o && pin.vertex < o->mesh.points.rows())
      h.pins.push_back(deformer_.points(pin.object).row(pin.vertex).transpose());
  return h;
}

// ---- operations --------------------------------------------------------------------------

void InteractionController::pruneSelection() {
  // Selections may name widgets that no longer exist.
  std::erase_if(selection_, [&](WidgetId id) { return !scene_.widgets.contains(id); });
  if (point_ && !scene_.widgets.contains(point_->lattice)) point_.reset();
  if (hovered_ && !scene_.widgets.contains(*hovered_)) hovered_.reset();
  std::erase_if(pins_, [&](const ObjectPoint& pin) {
    const scenes::SceneObject* object = scene_.findObject(pin.object);
    return object == nullptr || pin.vertex >= object->mesh.points.rows();
  });
}

void InteractionController::pushState(const std::string& description, scenes::StateDelta delta,
                                      const std::string& mergeKey) {
  if (delta.empty()) return;
  const std::size_t bytes = delta.bytes();
  auto shared = std::make_shared<const scenes::StateDelta>(std::move(delta));
  auto apply = [this, shared](bool forward) {
    // In place: only what differs is stamped, so the deformer re-embeds nothing unless a frame
    // changed and then only the stages concerned.
    scene_.widgets.restoreState(forward ? shared->after : shared->before);
    refresh();
  };
  commands_.push(scenes::Command{description, [apply] { apply(false); }, [apply] { apply(true); }, mergeKey, bytes});
}

template <class Change>
auto InteractionController::edit(const std::string& description, Change change, const std::string& mergeKey) {
  if (dragging_) cancel();
  // The model's data and the attachments before the change (transient: the command keeps only
  // the records that differ), and the objects there were.
  const widgets::WidgetModelData widgetsBefore = scene_.widgets.toData();
  const std::vector<scenes::Attachment> attachmentsBefore = scene_.attachments;
  const std::size_t objectsBefore = scene_.objects.size();
  auto deltaFromBefore = [&] {
    scenes::SceneDelta delta;
    delta.widgets = scenes::modelPatch(widgetsBefore, scene_.widgets.toData());
    if (!(attachmentsBefore == scene_.attachments)) delta.attachments = std::pair(attachmentsBefore, scene_.attachments);
    return delta;
  };
  auto finish = [&] {
    auto delta = std::make_shared<const scenes::SceneDelta>(deltaFromBefore());
    // Objects the change added (appended): moved out of the scene into `held` on undo, back on
    // redo; the command holds an object only while it is undone.
    auto held = std::make_shared<std::vector<scenes::SceneObject>>();
    const std::size_t added = scene_.objects.size() - objectsBefore;
    auto apply = [this, delta, held, added, objectsBefore](bool forward) {
      if (!forward) {
        for (std::size_t i = 0; i < added; ++i) held->push_back(std::move(scene_.objects[objectsBefore + i]));
        scene_.objects.resize(objectsBefore);
        if (added > 0) scenes::touchStructure(scene_);
      }
      scenes::applySceneDelta(scene_, *delta, forward);
      if (forward && added > 0) {
        for (auto& object : *held) scenes::addObject(scene_, std::move(object));
        held->clear();
      }
      pruneSelection();
      refresh();
      if (onStructureChanged) onStructureChanged();
    };
    commands_.push(scenes::Command{description, [apply] { apply(false); }, [apply] { apply(true); }, mergeKey,
                                   delta->bytes() + sizeof(*held)});
    deformer_.finishGesture(scene_);
    notify();
    if (onStructureChanged) onStructureChanged();
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
    scene_.objects.resize(std::min(scene_.objects.size(), objectsBefore));
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
      if (scene_.findObject(objects[i]) != nullptr) scenes::setObjectDisplay(scene_, objects[i], set[i]);
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
    const std::string name = scene_.widgets.name(id);
    scene_.widgets.remove(id);
    std::erase_if(scene_.attachments, [&](const scenes::Attachment& a) { return a.lattice == name; });
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
       [&] { scenes::detachLattice(scene_, scene_.widgets.name(lattice), object); });
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
        scenes::addObject(scene_, std::move(object));
        return name;
      });
}

void InteractionController::addObject(scenes::SceneObject object) {
  edit(
      "Import " + object.name,
      [&] {
        if (scene_.findObject(object.name) != nullptr) throw std::invalid_argument("object '" + object.name + "' exists");
        scenes::addObject(scene_, std::move(object));
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

void InteractionController::setLatticeFrame(WidgetId lattice, const Eigen::Affine3d& frame) {
  edit("Place " + scene_.widgets.name(lattice), [&] { scene_.widgets.setLatticeFrame(lattice, frame); },
       "frame/" + widgets::toString(lattice));
}

void InteractionController::setSiblingPosition(WidgetId lattice, std::size_t position) {
  edit("Reorder " + scene_.widgets.name(lattice), [&] { scene_.widgets.setSiblingPosition(lattice, position); });
}

void InteractionController::replaceWidgets(widgets::WidgetModel model, const std::optional<std::string>& attachTo) {
  edit(attachTo ? "Open widget file on " + *attachTo : std::string("Open widget file"), [&] {
    scene_.widgets = std::move(model);
    std::erase_if(scene_.attachments, [&](const scenes::Attachment& a) {
      const auto roots = scene_.widgets.roots();
      return std::none_of(roots.begin(), roots.end(), [&](WidgetId r) { return scene_.widgets.name(r) == a.lattice; });
    });
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
  // attachments before (a few names); scenes::removeObject drops each from its attachments.
  auto held = std::make_shared<std::vector<std::pair<std::size_t, scenes::SceneObject>>>();
  const auto attachmentsBefore = std::make_shared<const std::vector<scenes::Attachment>>(scene_.attachments);
  auto remove = [this, objects, held] {
    for (std::size_t i = scene_.objects.size(); i-- > 0;)
      if (std::find(objects.begin(), objects.end(), scene_.objects[i].name) != objects.end()) {
        const std::string name = scene_.objects[i].name;
        held->emplace_back(i, std::move(scene_.objects[i]));
        scene_.objects[i].name = name;  // the moved-from entry, which removeObject finds and erases
        scenes::removeObject(scene_, name);
      }
  };
  auto putBack = [this, held, attachmentsBefore] {
    for (auto it = held->rbegin(); it != held->rend(); ++it)
      scene_.objects.insert(scene_.objects.begin() + static_cast<std::ptrdiff_t>(it->first), std::move(it->second));
    held->clear();
    scene_.attachments = *attachmentsBefore;
    scenes::touchStructure(scene_);
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
  // The attachments name objects (scenes::Attachment::objects): they follow.
  auto rename = [this](const std::string& from, const std::string& to) {
    scene_.findObject(from)->name = to;
    for (scenes::Attachment& a : scene_.attachments) std::replace(a.objects.begin(), a.objects.end(), from, to);
    scenes::touchStructure(scene_);
    refresh();
    if (onStructureChanged) onStructureChanged();
  };
  rename(object, name);
  commands_.push(scenes::Command{"Rename " + object + " to " + name, [rename, object, name] { rename(name, object); },
                                 [rename, object, name] { rename(object, name); }, {}, 0});
}

void InteractionController::renameWidget(WidgetId id, const std::string& name) {
  const std::string old = scene_.widgets.name(id);
  if (name == old) return;
  edit("Rename " + old + " to " + name, [&] {
    scene_.widgets.rename(id, name);
    // Attachments name root lattices (scenes::Attachment::lattice).
    for (scenes::Attachment& a : scene_.attachments)
      if (a.lattice == old) a.lattice = name;
  });
}

void InteractionController::refresh() {
  deformer_.finishGesture(scene_);
  notify();
}

void InteractionController::notify() {
  if (onChanged) onChanged();
}

}  // namespace ffdkit::app
