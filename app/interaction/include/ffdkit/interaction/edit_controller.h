#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/interaction/cell_from_selection.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/interaction/modal_transform.h"
#include "ffdkit/interaction/point_selection.h"
#include "ffdkit/interaction/shape_guard.h"
#include "ffdkit/interaction/soft_selection.h"
#include "ffdkit/interaction/transformer.h"
#include "ffdkit/interaction/view_highlights.h"
#include "ffdkit/scenes/command_stack.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"

namespace ffdkit::app {

/// A lattice's edit mode and the transforms of selections (issue 19; Blender's edit mode and
/// its G / R / S): points of one lattice are picked, box-selected, selected all / none /
/// inverted / linked, then moved, turned and sized about a pivot with the transformer's handles
/// or a modal transform (axis constraints, typed values, snapping); a cell is made from them
/// (Make Cell). Outside the edit mode, two or more selected widgets (affine widgets, root
/// lattices, cells) get one transformer that moves, turns and sizes them together.
///
/// Headless, beside InteractionController (which owns the widget selection): rays in, model
/// edits out. A transform changes the model live (objects deform through the pipeline at every
/// step) and becomes one command when confirmed: the control points and frames that changed
/// (scenes::StateDelta) and the placements of the affine widgets it moved, never a copy of the
/// document. Cancel puts everything back and pushes nothing.
class EditController {
 public:
  /// All four must outlive this object.
  EditController(scenes::Scene& scene, scenes::SceneDeformer& deformer, scenes::CommandStack& commands,
                 InteractionController& widgets);

  // ---- edit mode ---------------------------------------------------------------------------
  /// Enters the edit mode of `lattice` with no point selected.
  /// @throws std::invalid_argument if it is not a lattice of the scene.
  void enter(widgets::WidgetId lattice);
  /// Leaves the edit mode (a transform in progress is cancelled).
  void exit();
  /// In a lattice's edit mode, with that lattice still there at the same counts (an undo that
  /// removes or resizes it ends the mode's effect).
  bool editing() const;
  /// The lattice in edit mode. @throws std::logic_error outside the edit mode.
  widgets::WidgetId lattice() const;
  /// The selected points. @throws std::logic_error outside the edit mode.
  const PointSelection& points() const;

  /// The point of the edited lattice nearest the camera within `tolerance` (world units) of the ray.
  std::optional<Eigen::Index> pointUnder(const widgets::Ray& ray, double tolerance) const;
  /// Picks the point under the ray (SelectMode) and @return true; a miss changes nothing.
  bool click(const widgets::Ray& ray, double tolerance, SelectMode mode);
  /// Points by flat index (a box select: pointsInRectangle over worldPoints() projected).
  void pickMany(const std::vector<Eigen::Index>& indices, SelectMode mode);
  void selectAll();
  void selectNone();
  void invert();
  /// Rows along `axis`, or with `plane` index planes normal to it (PointSelection::selectLinked).
  void selectLinked(int axis, bool plane);
  /// The edited lattice's control points in the world (#points x 3).
  Eigen::MatrixX3d worldPoints() const;

  // ---- transforms --------------------------------------------------------------------------
  /// Mirror editing (Blender's lattice X-mirror): with an index axis (0 = i, 1 = j, 2 = k), a
  /// transform of the edit mode's points also moves each selected point's mirror image, the
  /// point at index n-1-i along that axis, by the mirrored motion S M S, where S reflects across
  /// the lattice's mid-plane normal to that axis (in its frame: the plane through the mean of
  /// its rest points along that axis). A symmetric pair stays exactly symmetric. A point whose
  /// image is selected too, or that is its own image (on the mid-plane), moves by M only.
  /// nullopt: off. @throws std::invalid_argument for another axis.
  void setMirror(std::optional<int> axis);
  std::optional<int> mirror() const { return mirror_; }
  PivotChoice pivot() const { return pivot_; }
  void setPivot(PivotChoice pivot);
  /// What a transform would move now: the selected points in the edit mode, else two or more
  /// selected widgets that can move. @return a reason when there is nothing ("select points
  /// first", "'c' is a child lattice: its frame follows its parent cell").
  std::optional<std::string> refusal() const;
  /// The pivot of what a transform would move (Individual: the median), or nullopt.
  std::optional<Eigen::Vector3d> pivotPoint() const;
  /// The transformer of what a transform would move, at the pivot along the world axes, or
  /// nullopt (nothing to move, or one widget: InteractionController's own transformer).
  std::optional<Transformer> transformer() const;

  /// Updates the hovered handle of transformer(). @return true if it changed.
  bool hover(const widgets::Ray& ray, double tolerance);
  /// Starts a handle drag if the ray hits a handle of transformer() (within `tolerance`).
  bool pressHandle(const widgets::Ray& ray, double tolerance);
  /// Starts a modal transform (G / R / S) from the pointer at `ray`; `viewDirection` from the
  /// camera into the scene. @throws std::invalid_argument with refusal(), or for a rotate or
  /// scale of points about their individual origins (which would leave them in place).
  void beginModal(TransformMode mode, const widgets::Ray& ray, const Eigen::Vector3d& viewDirection);
  /// During a modal transform: its constraint and typed value (then call update()).
  ModalTransform* modal() { return modal_ ? &*modal_ : nullptr; }
  /// Moves the active transform (handle drag or modal) to the pointer at `ray`; `snap` (Ctrl)
  /// rounds to increments.
  void update(const widgets::Ray& ray, bool snap);
  /// During a handle drag: sets the handle's amount to `value` (a number typed during the drag;
  /// InteractionController::setDragValue for one widget): a distance (world units), an angle
  /// (rad) or a factor. From then on the pointer no longer moves it (the typed value rules);
  /// the next confirm() makes it one command. @return false (nothing changes) with no handle
  /// drag, or for a factor that is not positive.
  bool setDragValue(double value);
  /// The handle being dragged, or nullopt (no transform, or a modal one).
  std::optional<TransformerHandle> draggedHandle() const;
  /// Ends the active transform: one command (nothing if nothing moved).
  void confirm();
  /// Abandons the active transform: the model as before it, nothing pushed.
  void cancel();
  bool transforming() const { return live_.has_value(); }
  /// The active transform's amount for the status bar ("move (0.000, 0.000, 0.500) along z").
  std::string describe() const;

  // ---- make cell ---------------------------------------------------------------------------
  /// The cell of `kind` the selected points make, or with no kind the kind they are
  /// (classifySelection; a selection that is none of them gets no spec, for the caller to ask
  /// about a custom cell). @throws std::logic_error outside the edit mode.
  CellFromSelection cellFor(std::optional<widgets::CellKind> kind) const;
  /// Adds the cell `spec` to the edited lattice (one command); it becomes the widget selection,
  /// so that Add Translate / Rotate / Scale act on it. @return its id.
  widgets::WidgetId makeCell(const widgets::CellSpec& spec);

  // ---- soft selection (Blender's proportional editing) ----------------------------------------
  /// The soft selection of the edit mode's transforms (off by default).
  const SoftSelection& softSelection() const { return soft_; }
  /// Sets it; during a transform the points follow at once.
  /// @throws std::invalid_argument for a radius that is not positive and finite.
  void setSoftSelection(const SoftSelection& soft);
  /// Multiplies the radius by `factor` (> 0): the wheel or PageUp / PageDown during G / R / S.
  void scaleSoftRadius(double factor);
  /// Per point of the edited lattice, the weight a transform gives it now (softSelectionWeights
  /// over the points where the live transform started, else where they are): 1 selected,
  /// the falloff within the radius, 0 beyond. Empty outside the edit mode.
  Eigen::VectorXd softWeights() const;

  // ---- Keep Volume / Keep Centre ---------------------------------------------------------------
  /// The objects whose volume and centre the transforms keep: InteractionController's guard, the
  /// one every gesture uses. Each step of a transform of points (edit mode, cells of a group)
  /// corrects the points it does not move.
  ShapeGuard& shapeGuard() { return widgets_.shapeGuard(); }
  /// InteractionController::setKeep: keeps `object`'s volume and / or centre at their values
  /// now. @throws std::invalid_argument as ShapeGuard::setKeep.
  void setKeep(scenes::ObjectId object, ShapeKeep keep) { widgets_.setKeep(object, keep); }
  /// What the last step's corrections did (one entry per kept object of the moved lattices).
  const std::vector<ShapeGuardStep>& guardSteps() const { return guardSteps_; }

  // ---- fold-over tint --------------------------------------------------------------------------
  /// The fold-over verdicts (ffd::checkFolding) of the edited lattice and of the lattices a
  /// transform moves, brought up to date after every change of their control points or frames.
  const std::vector<FoldTint>& foldTints() const { return foldTints_; }

  /// The controller's highlights with this object's: the selected points, the transformer, the
  /// soft selection's radius and the fold-over tints.
  ViewHighlights highlights(ViewHighlights widgetHighlights) const;

  /// Called after every change of the selection or of the model this object makes.
  std::function<void()> onChanged;

 private:
  // One target of a live transform, with its state at the start.
  struct Target {
    enum class Kind { Points, Frame, Placement } kind = Kind::Points;
    widgets::WidgetId id;                 ///< the lattice (points, frame) or the affine widget
    std::vector<Eigen::Index> indices;    ///< Points: which
    std::vector<Eigen::Vector3d> centres; ///< Points: each one's centre for the Individual pivot (world)
    Eigen::MatrixX3d startPoints;         ///< Points: the lattice's local control points
    Eigen::Affine3d start = Eigen::Affine3d::Identity();  ///< Frame: lattice frame; Placement: placement
    Eigen::Affine3d base = Eigen::Affine3d::Identity();   ///< Placement: WidgetModel::placementBase
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();     ///< world; the edit mode's points: their mean
    std::optional<Eigen::Vector3d> activeCentre;          ///< the edit mode's active point (world)
    /// Points, mirror editing: (image index, position in `indices` of the point it mirrors).
    std::vector<std::pair<Eigen::Index, std::size_t>> images;
    Eigen::Affine3d reflection = Eigen::Affine3d::Identity();  ///< Points, mirror editing: S (local)
    /// Points, soft selection: (index, weight) of the unselected points it moves, weight in (0, 1).
    std::vector<std::pair<Eigen::Index, double>> soft;
  };
  struct Live {
    std::vector<Target> targets;
    widgets::WidgetModelState before;
    std::string verb;  ///< "Move", "Turn", "Size"
    std::string what;  ///< "4 points of lattice1", "3 widgets"
    Eigen::Vector3d pivot = Eigen::Vector3d::Zero();
    std::optional<TransformerDrag> handle;
    std::optional<double> typed;  ///< a handle drag's typed amount (setDragValue)
    Transformer transformer;  ///< the one whose handle is dragged
    Eigen::Affine3d motion = Eigen::Affine3d::Identity();  ///< the last motion applied
  };
  std::vector<Target> targets() const;
  void startLive(std::vector<Target> targets, const std::string& verb);
  void apply(const Eigen::Affine3d& motion);
  void notify();
  std::vector<widgets::WidgetId> movableWidgets() const;
  /// The soft selection's points of a Points target (Target::soft) from its start points.
  void softenTarget(Target& target) const;
  /// Keep Volume / Keep Centre after a step: the points the step did not move are corrected.
  void guardStep();
  /// foldTints_ for the edited lattice and the live targets' lattices whose revisions moved.
  void updateFoldTints();

  scenes::Scene& scene_;
  scenes::SceneDeformer& deformer_;
  scenes::CommandStack& commands_;
  InteractionController& widgets_;
  std::optional<PointSelection> selection_;
  PivotChoice pivot_ = PivotChoice::Median;
  std::optional<int> mirror_;
  std::optional<Live> live_;
  std::optional<ModalTransform> modal_;
  std::optional<TransformerHandle> hoveredHandle_;
  SoftSelection soft_;
  std::vector<ShapeGuardStep> guardSteps_;
  std::vector<FoldTint> foldTints_;
  std::vector<CertifiedLattice> certified_;  ///< the checked lattices the check certified, at their revisions
  /// Per tinted lattice, the (controlRevision, frameRevision) its verdicts were computed for.
  std::map<widgets::WidgetId, std::pair<std::uint64_t, std::uint64_t>> foldRevisions_;
};

}  // namespace ffdkit::app
