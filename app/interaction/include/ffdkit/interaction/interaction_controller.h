#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ffdkit/ffd/direct_manipulation.h"
#include "ffdkit/interaction/object_points.h"
#include "ffdkit/interaction/shape_guard.h"
#include "ffdkit/interaction/transformer.h"
#include "ffdkit/interaction/view_highlights.h"
#include "ffdkit/scenes/command_stack.h"
#include "ffdkit/scenes/document_delta.h"
#include "ffdkit/scenes/primitive.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/widgets/ray.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::app {

/// Options of InteractionController::newLattice (Kuriyama 1996, sec. 6.4): counts and bases per axis,
/// box (unit box at the origin) or cylindrical (EFFD, axes radius / angle / height).
struct NewLatticeOptions {
  Eigen::Vector3i counts = Eigen::Vector3i::Constant(3);
  std::array<ffd::AxisBasis, 3> basis{ffd::AxisBasis::bernstein(), ffd::AxisBasis::bernstein(),
                                      ffd::AxisBasis::bernstein()};
  bool cylindrical = false;  ///< counts (radial, angular, height); the angular basis is made periodic
};

/// Fits a root lattice's frame to the object's bounding box (padded by 5 % of its diagonal, a
/// flat box gets a minimum thickness) and attaches it to the object: the model edit of
/// InteractionController::attachLattice, without undo or deformation (for previews on copies).
/// @throws std::invalid_argument for an unknown or empty object or a child lattice.
void fitAndAttachLattice(scenes::Scene& scene, widgets::WidgetId lattice, const std::string& object);

/// The GUI-free heart of the application: turns world rays into model gestures (hover, pick,
/// drag) and user operations into model edits, each one undoable command on `commands`, and
/// keeps the deformed objects up to date. Views only convert pixels to rays and redraw when
/// onChanged fires (STYLE 9-11: no lattice or widget math in a QWidget).
///
/// A drag is one gesture: press() begins it (WidgetModel::beginDrag), drag() moves it and
/// re-deforms live (SceneDeformer::update with the dragged lattice active), release() ends it,
/// re-embeds what was throttled (finishGesture) and pushes one command.
class InteractionController {
 public:
  /// All three must outlive the controller.
  InteractionController(scenes::Scene& scene, scenes::SceneDeformer& deformer, scenes::CommandStack& commands);

  // ---- pointer -------------------------------------------------------------------------
  /// Updates the hovered widget. `tolerance` in world units. @return true if it changed.
  bool hover(const widgets::Ray& ray, double tolerance);
  /// What a press hit.
  enum class PressResult {
    Nothing,  ///< empty space: the caller orbits the camera (and clears the selection on a click)
    Point,    ///< a lattice control point became the picked point; the camera may still orbit
    Widget,   ///< a widget was selected and its drag began: the caller must not orbit
    Handle    ///< a handle of the transformer manipulator: its drag began (no orbit)
  };
  /// Picks under the ray: an affine glyph or a cell (WidgetModel::pick), else a lattice control
  /// point within `tolerance` (world units), else a handle of the transformer manipulator (when
  /// one is shown). A widget becomes the selection (or is added to it
  /// with `extend`) and starts a drag (WidgetModel::beginDrag).
  /// With `lattices`, only lattice widgets are picked (by their world bounding box) and dragged
  /// in the view plane; the application binds it to Alt+drag.
  PressResult press(const widgets::Ray& ray, double tolerance, bool extend = false, bool lattices = false);
  void drag(const widgets::Ray& ray);
  /// A value typed during a drag (Blender: type `0.5` while dragging): an affine widget's glyph
  /// drag gets that variation change (distance, rad or log factor), a transformer handle drag
  /// that amount (distance, rad or factor), instead of the pointer's; release() confirms.
  /// @return false when neither drag is active.
  bool setDragValue(double value);
  void release();

  /// Direct manipulation (Hsu, Hughes & Kaufman 1992): grabs the point of a deformed
  /// object under the ray (the nearest vertex of the first triangle hit; for curves and point
  /// clouds the nearest vertex within `tolerance`) and begins dragging it in the plane through
  /// it facing the ray. Each drag() gives the lattice that moves that point the least-norm
  /// control-point change (ffd::leastNormControlChange) that puts it on the pointer ray: the
  /// point follows the pointer exactly, the rest of the object smoothly. The lattice is the last
  /// one in the object's pipeline whose input holds the point (the later ones, with the
  /// identity outside policy, leave it alone). release() pushes one command; cancel() undoes.
  /// The pins (pins()) that lattice moves keep their place exactly, or with `carryPins` move by
  /// the same displacement as the grabbed point (pinnedDragWeights).
  /// @return the object's name, or nullopt if no object point is under the ray.
  /// @throws std::invalid_argument naming the object when no lattice can move the point (none
  ///   attached, or the point is outside them).
  std::optional<std::string> pressObject(const widgets::Ray& ray, double tolerance, bool carryPins = false);
  /// The object point under the ray (pickObjectPoint on the deformed objects).
  std::optional<ObjectPoint> objectPointAt(const widgets::Ray& ray, double tolerance) const {
    return pickObjectPoint(scene_, deformer_, ray, tolerance);
  }
  /// Pinned object points (direct manipulation): a view state like the selection, not an edit.
  const std::vector<ObjectPoint>& pins() const { return pins_; }
  /// Pins `point`, or unpins it if it is pinned. @throws std::invalid_argument for an unknown
  ///   object or vertex.
  void togglePin(const ObjectPoint& point);
  void clearPins();
  /// During a direct-manipulation drag: the object and the index of the point being dragged.
  std::optional<std::pair<scenes::ObjectId, Eigen::Index>> grabbedPoint() const {
    if (!objectGrab_) return std::nullopt;
    return std::make_pair(objectGrab_->object, objectGrab_->vertex);
  }
  /// Abandons the active drag (the model returns to the gesture start; nothing is pushed).
  void cancel();
  bool dragging() const { return dragging_; }

  // ---- selection -------------------------------------------------------------------------
  const std::vector<widgets::WidgetId>& selection() const { return selection_; }
  void setSelection(std::vector<widgets::WidgetId> selection);
  const std::optional<LatticePointRef>& pickedPoint() const { return point_; }
  void setPickedPoint(std::optional<LatticePointRef> point);
  void clearSelection();
  std::optional<widgets::WidgetId> hovered() const { return hovered_; }

  // ---- transformer manipulator (Kuriyama 1996, sec. 6.2.1) --------------------------------
  /// The manipulator of the selection: shown when exactly one affine widget or lattice widget is
  /// selected; at the widget's frame (an affine widget, 2.5 glyph sizes, uniform size handles)
  /// or at the lattice's centre along its axes (size handles per axis). Its drags set an affine
  /// widget's placement (the points do not move) or move the lattice's frame through a lattice
  /// gesture (the attached objects are re-embedded, bound widgets follow); one command each.
  std::optional<Transformer> transformer() const;
  /// The handle under the pointer, or being dragged.
  std::optional<TransformerHandle> transformerHandle() const;
  /// During a handle drag: its value so far (TransformerDrag::value: distance, rad or factor).
  std::optional<double> handleDragValue() const {
    return handleDrag_ ? std::optional<double>(handleDrag_->value()) : std::nullopt;
  }
  /// What a view should emphasise now (with the fold-over tints of foldTints()).
  ViewHighlights highlights() const;

  // ---- Keep Volume / Keep Centre and the fold-over tint ----------------------------------------
  /// The objects whose volume and centre every gesture keeps: the one home of that rule. After
  /// each step of a drag (an affine widget's glyph, a cell, a lattice, a transformer handle, an
  /// object point) and of EditController's transforms, the guard corrects the control points the
  /// gesture leaves free in each lattice the gesture has moved; the correction is part of the
  /// gesture's one undo step.
  ShapeGuard& shapeGuard() { return guard_; }
  /// The guard (read-only).
  const ShapeGuard& shapeGuard() const { return guard_; }
  /// ShapeGuard::setKeep with this controller's scene and deformer: keeps `object`'s volume and /
  /// or centre at their values now. @throws std::invalid_argument as ShapeGuard::setKeep.
  void setKeep(scenes::ObjectId object, ShapeKeep keep) {
    deformer_.evaluate(scene_);  // the object as it is shown now (a change may wait for a frame)
    guard_.setKeep(scene_, deformer_, object, keep);
  }
  /// What the guard did at the last step of this controller's drag (one entry per kept object of
  /// the lattices the drag moved; empty when nothing is kept or no drag ran since the press).
  const std::vector<ShapeGuardStep>& guardSteps() const { return guardSteps_; }
  /// The fold-over verdicts (ffd::checkFolding) of the lattices that drags have moved, brought
  /// up to date at each step and after every change of their control points or frames: lattices
  /// with a cell that folds or is unknown (a certified lattice has none).
  const std::vector<FoldTint>& foldTints() const { return foldTints_; }

  // ---- operations (each one undoable command; they throw the model's errors unchanged) ----
  widgets::WidgetId newLattice(const NewLatticeOptions& options);
  /// A translate / rotate / scale widget on `cell`. @throws std::invalid_argument for a rotate or
  /// scale widget on a point cell, which would do nothing (affineRefusal).
  widgets::WidgetId addAffine(widgets::WidgetId cell, widgets::AffineKind kind);
  /// A cell of `lattice` (made from selected points, EditController::makeCell); it becomes the
  /// selection.
  widgets::WidgetId addCell(widgets::WidgetId lattice, const widgets::CellSpec& spec);
  /// A widget on the point cell at `point` (made if the point has none yet).
  widgets::WidgetId addAffineAtPoint(const LatticePointRef& point, widgets::AffineKind kind);
  /// Binds two widgets; the kind follows from their types (a cell and a lattice: hierarchy).
  widgets::BindingId bind(widgets::WidgetId a, widgets::WidgetId b);
  void unbind(widgets::BindingId binding);
  void removeWidget(widgets::WidgetId id);
  /// Fits a root lattice's frame to the object's bounding box (padded by 5 % of its diagonal)
  /// and attaches it to the object.
  void attachLattice(widgets::WidgetId lattice, const std::string& object);
  void detachLattice(widgets::WidgetId lattice, const std::string& object);
  /// Adds a primitive object ("sphere1", ...). @return its name.
  std::string addPrimitive(const scenes::PrimitiveOptions& options);
  /// Adds an object (an imported mesh); its name must be unique.
  void addObject(scenes::SceneObject object);
  /// Changes how objects look, `looks[i]` for `objects[i]` (zebra stripes, curvature comb,
  /// ...): one undoable command, no re-deform.
  /// @throws std::invalid_argument for an unknown object, sizes that differ, or a look out of
  /// range (stripes outside [1, 256], a zero zebra direction, a comb scale not positive).
  void setDisplay(const std::vector<std::string>& objects, const std::vector<scenes::DisplaySettings>& looks,
                  const std::string& description = "Change look");
  void setVariation(widgets::WidgetId affine, double value);
  void setPlacement(widgets::WidgetId affine, const Eigen::Affine3d& placement);
  void setGlyph(widgets::WidgetId affine, const widgets::Glyph& glyph);
  /// Makes an affine widget a translate / rotate / scale widget (its variation restarts at 0).
  void setAffineKind(widgets::WidgetId affine, widgets::AffineKind kind);
  /// One-way: only the binding's `from` end drives its `to` end (Kuriyama 1996, sec. 6.2.2).
  void setOneWay(widgets::BindingId binding, bool oneWay);
  void setMask(widgets::BindingId binding, widgets::AffineMask mask);
  void setRule(widgets::BindingId binding, const widgets::ConversionRule& rule);
  void setLatticeSettings(widgets::WidgetId lattice, const widgets::LatticeSettings& settings);
  /// Changes a lattice's point counts (WidgetModel::setLatticeCounts).
  void setLatticeCounts(widgets::WidgetId lattice, const Eigen::Vector3i& counts);
  /// Sets the weight of control points `points` (flat indices: the picked point, or the edit
  /// mode's selected points) of `lattice` to `weight` (rational FFD, Lamousin & Waggenspack 1994;
  /// weight 1 everywhere is the polynomial lattice): one undoable command.
  /// @throws std::invalid_argument for no points; what WidgetModel::setWeight throws (a weight not
  ///   finite and > 0, an unknown point), nothing changed.
  void setWeight(widgets::WidgetId lattice, const std::vector<Eigen::Index>& points, double weight);
  /// A root lattice's world frame (its placement, orientation and size).
  void setLatticeFrame(widgets::WidgetId lattice, const Eigen::Affine3d& frame);
  void setSiblingPosition(widgets::WidgetId lattice, std::size_t position);
  /// Replaces the widget model (a widget file opened): attachments of lattices that no longer
  /// exist are dropped. With `attachTo`, each root lattice of the new model is then fitted to
  /// that object and attached to it (as attachLattice), all in the same command.
  void replaceWidgets(widgets::WidgetModel model, const std::optional<std::string>& attachTo = std::nullopt);
  /// Removes objects with their links: they leave every attachment, and an attachment left with
  /// no object goes (the lattice stays). One command. @throws std::invalid_argument for an
  /// unknown object (nothing is removed).
  void removeObjects(const std::vector<std::string>& objects);
  /// Renames an object; the attachments naming it follow. @throws std::invalid_argument for an
  /// unknown object, an empty name or one another object has.
  void renameObject(const std::string& object, const std::string& name);
  /// Renames a widget (WidgetModel::rename): bindings, attachments and animation channels hold
  /// its id and stay as they are. @throws what the model throws (a used or empty name).
  void renameWidget(widgets::WidgetId id, const std::string& name);

  /// Replaces the deformer's state by one computed elsewhere for the same scene (an embedding
  /// done in a worker thread on a copy), so that the next update has nothing to re-embed.
  void adoptDeformer(scenes::SceneDeformer deformer) { deformer_ = std::move(deformer); }

  /// Re-deforms every object (after undo/redo or a scene change) and notifies.
  void refresh();

  /// Notes that the model was set to the animation at `seconds` (the timeline's frame changes and
  /// playback call it). An edit's command keeps the count it was made at; its undo and redo after
  /// a frame change carry what they write back to the time shown (scenes::restoreAtEditValues).
  void animationApplied(double seconds) {
    ++animationApplications_;
    shownSeconds_ = seconds;
  }
  std::uint64_t animationApplications() const { return animationApplications_; }
  /// The time the model was last set to (animationApplied) if that was after the count
  /// `madeAt`, else nullopt: what an edit's command made at `madeAt` passes to restoreAtEditValues.
  std::optional<double> animationAppliedSince(std::uint64_t madeAt) const {
    return animationApplications_ != madeAt ? std::optional(shownSeconds_) : std::nullopt;
  }

  /// Has the changes made since the last evaluation evaluated (SceneDeformer::evaluate): at once
  /// by default (scripts, tests, the Python Document), or, when requestEvaluation is set, by its
  /// owner. Every model change of this controller and of the edit mode's comes here.
  void evaluateChanges();
  /// Set by an owner that evaluates once per frame (MainWindow: at its next repaint, after the
  /// last event of the event-loop tick; readers of points evaluate first): evaluateChanges() then
  /// only calls it. Empty: evaluateChanges() evaluates at once.
  std::function<void()> requestEvaluation;

  /// Called after every change of the scene, the selection or the hover (redraw, refresh panels).
  std::function<void()> onChanged;
  /// Called after a change of the widget tree or the objects (rebuild outliners).
  std::function<void()> onStructureChanged;

 private:
  /// Pushes a gesture's delta from `before` (the model's state when it began) to the model now as
  /// one command (nothing when nothing changed).
  void pushState(const std::string& description, const widgets::WidgetModelState& before,
                 const std::string& mergeKey = {});
  /// Runs `change` on the scene and pushes it as one command holding its delta (the widget records
  /// and attachments it changed, the objects it added); edits with the same non-empty
  /// `mergeKey` in a row merge into one step.
  template <class Change>
  auto edit(const std::string& description, Change change, const std::string& mergeKey = {});
  /// Drops selected, picked or hovered widgets that no longer exist.
  void pruneSelection();
  std::optional<widgets::WidgetId> activeLattice(widgets::WidgetId id) const;
  /// The nearest lattice control point within `tolerance` of the ray.
  std::optional<LatticePointRef> pickPoint(const widgets::Ray& ray, double tolerance) const;
  void beginHandleDrag(const Transformer& gizmo, TransformerHandle handle, const widgets::Ray& ray);
  /// A handle drag's world motion applied: an affine widget's placement, else the lattice gesture.
  void applyHandleMotion(const Eigen::Affine3d& motion);
  void notify();
  /// At a drag's press: the lattices' revisions (what the drag moves is what changes from them)
  /// and no guard report yet.
  void recordDragStart();
  /// Keep Volume / Keep Centre after a drag step: guard_.correct on each lattice the drag moved,
  /// with the points it moves (the gesture's cells, or the grabbed point's lattice) held.
  void guardStep();
  /// Per lattice the active widget-model gesture moves points of: which (#points flags).
  std::map<widgets::WidgetId, std::vector<bool>> gestureMovedPoints() const;
  /// Direct manipulation with a kept object: alternates the guard's correction and the least-norm
  /// change that brings the grabbed point back to `target` (world) until both hold.
  void guardObjectStep(const Eigen::Vector3d& target);
  /// Notes the lattices whose control points or frames changed since the drag's press (foldWatch_).
  void watchMovedLattices();
  /// foldTints_ for the watched lattices whose revisions moved.
  void updateFoldTints();

  scenes::Scene& scene_;
  scenes::SceneDeformer& deformer_;
  scenes::CommandStack& commands_;
  std::vector<widgets::WidgetId> selection_;
  std::optional<LatticePointRef> point_;
  std::optional<widgets::WidgetId> hovered_;
  std::uint64_t animationApplications_ = 0;
  double shownSeconds_ = 0.0;
  bool dragging_ = false;
  std::optional<widgets::WidgetId> dragLattice_;
  widgets::WidgetModelState dragStart_;
  // Transformer: the hovered handle; during a handle drag, its math, its widget, and for an
  // affine widget (handleStart_) the placement and base at the press.
  std::optional<TransformerHandle> hoveredHandle_;
  std::optional<TransformerDrag> handleDrag_;
  widgets::WidgetId handleTarget_;
  Eigen::Affine3d placementStart_ = Eigen::Affine3d::Identity();
  Eigen::Affine3d placementBase_ = Eigen::Affine3d::Identity();
  bool handleStart_ = false;
  // Direct manipulation: the grabbed point and the lattice that moves it.
  struct ObjectGrab {
    scenes::ObjectId object;
    Eigen::Index vertex = 0;
    widgets::WidgetId lattice;
    Eigen::Vector3d grab = Eigen::Vector3d::Zero();  ///< its deformed world position at the press
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< of the drag plane
    Eigen::MatrixX3d controlStart;                   ///< the lattice's local control points at the press
    /// Precomputed at the press (the weights and the frame do not change during the drag): the
    /// least-norm change is `weights * (worldToLocal * d)^T` for a world displacement d, with
    /// weights from pinnedDragWeights (HHK 1992 with the pins as further constraints).
    Eigen::VectorXd weights;
    Eigen::Matrix3d worldToLocal = Eigen::Matrix3d::Identity();
    /// The lattice's basis at the grabbed point (its deformed position is linear in the controls).
    std::vector<ffd::BasisWeight> basis;
  };
  std::optional<ObjectGrab> objectGrab_;
  std::vector<ObjectPoint> pins_;
  ShapeGuard guard_;
  std::vector<ShapeGuardStep> guardSteps_;
  /// Per lattice, its (controlRevision, frameRevision) at the press of the drag.
  std::map<widgets::WidgetId, std::pair<std::uint64_t, std::uint64_t>> dragRevisions_;
  /// The lattices drags have moved (their fold-over verdicts are kept up to date), with the
  /// revisions the verdicts in foldTints_ were computed for.
  std::map<widgets::WidgetId, std::pair<std::uint64_t, std::uint64_t>> foldWatch_;
  std::vector<FoldTint> foldTints_;
  std::vector<CertifiedLattice> certified_;  ///< the watched lattices the check certified, at their revisions
};

}  // namespace ffdkit::app
