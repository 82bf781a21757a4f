// The interaction controller, pointer gestures: hover, press, drag, release and cancel of a
// widget, lattice point, transformer handle or object point; the selection and highlights; undo
// steps of gestures. Transformer handle drags are in interaction_controller_handles.cpp, direct
// manipulation and pins in interaction_controller_pins.cpp, document operations (undoable
// edits) in interaction_controller_operations.cpp.
#include "ffdkit/interaction/interaction_controller.h"

#include <algorithm>
#include <cctype>
#include <limits>
#include <memory>

#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/document_delta.h"

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
    recordDragStart();
    scene_.widgets.beginDrag(hit->id, ray);
    dragging_ = true;
    dragLattice_ = activeLattice(hit->id);
    deformer_.beginGesture(dragLattice_);
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

void InteractionController::drag(const widgets::Ray& ray) {
  if (!dragging_) return;
  if (objectGrab_) {
    const ObjectGrab& g = *objectGrab_;
    const auto t = widgets::intersectPlane(ray, g.grab, g.normal);
    if (!t) return;  // parallel to the drag plane: keep the last position
    // World displacement -> lattice-local (world = frame * local), then HHK's least-norm change.
    const Eigen::Vector3d local = g.worldToLocal * (ray.at(*t) - g.grab);
    scene_.widgets.setControlPoints(g.lattice, g.controlStart + g.weights * local.transpose());
    guardObjectStep(ray.at(*t));
    notify();
    return;
  }
  if (handleDrag_) {
    applyHandleMotion(handleDrag_->motion(ray));
    return;
  }
  scene_.widgets.dragTo(ray);
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
  notify();
  return true;
}

void InteractionController::release() {
  if (!dragging_) return;
  dragging_ = false;
  deformer_.endGesture();  // the next evaluation is exact
  // The result is evaluated before its step is pushed, as an edit's and a confirm's: a result
  // that cannot be evaluated (an embedding cancelled) is taken back with no step, so no step's
  // undo undoes nothing and the steps that could be redone stay.
  const auto evaluateOrTakeBack = [this](const std::function<void()>& takeBack) {
    try {
      notify();
    } catch (...) {
      takeBack();
      refresh();
      throw;
    }
  };
  const auto restoreStart = [this] { scene_.widgets.restoreState(dragStart_); };
  if (objectGrab_) {
    const std::string description = "Drag point " + std::to_string(objectGrab_->vertex) + " of " + scene_.objectName(objectGrab_->object);
    objectGrab_.reset();
    evaluateOrTakeBack(restoreStart);
    pushState(description, dragStart_);
    return;
  }
  const std::optional<TransformerHandle> handle =
      handleDrag_ ? std::optional<TransformerHandle>(handleDrag_->handle()) : std::nullopt;
  handleDrag_.reset();
  if (handleStart_) {
    handleStart_ = false;
    const WidgetId target = handleTarget_;
    const Eigen::Affine3d before = placementStart_, after = scene_.widgets.placement(target);
    evaluateOrTakeBack([this, target, before] { scene_.widgets.setPlacement(target, before); });
    if (after.matrix() != before.matrix()) {
      // The placement is not part of the model's state: its change is the command's delta.
      auto place = [this, target](const Eigen::Affine3d& placement) {
        scene_.widgets.setPlacement(target, placement);
        notify();  // a placement moves no points
      };
      commands_.push(scenes::Command{handleDragDescription(handle.value_or(TransformerHandle::MoveX)) + " " +
                                         scene_.widgets.name(target),
                                     [place, before] { place(before); }, [place, after] { place(after); }, "",
                                     2 * sizeof(Eigen::Affine3d)});
    }
    return;
  }
  const WidgetId target = *scene_.widgets.gestureWidget();
  scene_.widgets.endGesture();
  evaluateOrTakeBack(restoreStart);
  const std::string what = handle ? handleDragDescription(*handle) : std::string("Drag");
  // A click that selected a widget changed nothing: no command.
  pushState(what + " " + scene_.widgets.name(target), dragStart_);
}

void InteractionController::cancel() {
  if (!dragging_) return;
  dragging_ = false;
  deformer_.endGesture();
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
  // The points the gesture did not move but Keep Volume / Keep Centre corrected go back too.
  if (!guard_.empty()) scene_.widgets.restoreState(dragStart_);
  refresh();
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
  h.foldTints = foldTints_;
  h.certified = certified_;
  for (const ObjectPoint& pin : pins_)
    if (const scenes::SceneObject* o = scene_.findObject(pin.object); o && pin.vertex < o->mesh.points.rows())
      h.pins.push_back(deformer_.points(pin.object).row(pin.vertex).transpose());
  return h;
}

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

void InteractionController::pushState(const std::string& description, const widgets::WidgetModelState& before,
                                      const std::string& mergeKey) {
  auto delta = std::make_shared<const scenes::StateDelta>(scenes::stateDelta(before, scene_.widgets.captureState()));
  if (delta->empty()) return;
  // The animated channels' values when the gesture began (before) and ended (after), for undo and
  // redo after a frame change (scenes::restoreAtEditValues).
  auto animated = std::make_shared<const scenes::StateDelta>(
      scenes::StateDelta{scenes::animatedPart(scene_, before), scenes::animatedState(scene_)});
  const std::uint64_t madeAt = animationApplications_;
  auto carried = std::make_shared<std::optional<scenes::CarriedStep>>();  // makes an undo's redo exact
  auto apply = [this, delta, animated, madeAt, carried](bool forward) {
    // In place: only what differs is stamped, so the deformer re-embeds nothing unless a frame
    // changed and then only the stages concerned.
    scenes::restoreAtEditValues(scene_, forward ? animated->before : animated->after, animationAppliedSince(madeAt),
                                [&] { scene_.widgets.restoreState(forward ? delta->after : delta->before); }, carried.get());
    refresh();
  };
  // Gestures merge only within one frame: a merged step's undo writes back the first's values.
  const std::string mergeAtFrame = mergeKey.empty() ? mergeKey : mergeKey + "@" + std::to_string(madeAt);
  commands_.push(scenes::Command{description, [apply] { apply(false); }, [apply] { apply(true); }, mergeAtFrame,
                                 delta->bytes() + animated->bytes()});
}

void InteractionController::refresh() { notify(); }

void InteractionController::evaluateChanges() {
  if (requestEvaluation)
    requestEvaluation();  // the window evaluates once, at its next frame
  else
    deformer_.evaluate(scene_);  // what the edits since the last call changed, once
}

void InteractionController::notify() {
  if (dragging_) {
    guardStep();  // Keep Volume / Keep Centre: part of the step, before it is evaluated
    watchMovedLattices();
  }
  guard_.prune(scene_);
  updateFoldTints();
  evaluateChanges();
  if (onChanged) onChanged();
}

}  // namespace ffdkit::app
