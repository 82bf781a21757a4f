#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/ffd/lattice.h"
#include "ffdkit/widgets/affine_kind.h"
#include "ffdkit/widgets/binding.h"
#include "ffdkit/widgets/cell.h"
#include "ffdkit/widgets/lattice_settings.h"
#include "ffdkit/widgets/ray.h"
#include "ffdkit/widgets/widget_changes.h"
#include "ffdkit/widgets/widget_data.h"
#include "ffdkit/widgets/widget_error.h"
#include "ffdkit/widgets/widget_id.h"

namespace ffdkit::widgets {

/// Options of WidgetModel::addLattice.
struct LatticeOptions {
  std::string name;                                          ///< unique; "" -> "lattice<N>"
  Eigen::Vector3i counts = Eigen::Vector3i::Constant(2);     ///< (l, m, n), each >= 2
  Eigen::Affine3d frame = Eigen::Affine3d::Identity();       ///< world = frame * local
  /// pointCount x 3 lattice-local rest points; empty -> the regular grid of the unit box [0,1]^3.
  Eigen::MatrixX3d restPoints;
  LatticeSettings settings;  ///< bases, outside policy, re-embedding
};

/// Options of WidgetModel::addAffine and addFreeAffine.
struct AffineOptions {
  std::string name;  ///< unique; "" -> "<kind><N>"
  /// Relative to the cell's rest frame (origin at the cell centroid, axes of Kuriyama 1996,
  /// sec. 6.2.1): a translate widget moves along placement's x, a rotate widget turns about its z. For a
  /// free widget (no cell) this is its world frame.
  Eigen::Affine3d placement = Eigen::Affine3d::Identity();
  std::optional<AffineMask> mask;  ///< attachment mask; default by cell kind
  std::optional<Glyph> glyph;      ///< default: arrow / ring / cube of size 0.2
};

/// A rigid world frame plus a size: what a renderer needs to draw a glyph or a cell axis triad.
struct WidgetFrame {
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();  ///< rigid world frame
  double size = 1.0;  ///< glyph size in world units (glyph.size times the frame's scale)
};

/// What WidgetModel::pick considers.
struct PickOptions {
  double tolerance = 0.02;  ///< world units: how far from a thin glyph a ray may pass
  bool affines = true;  ///< affine widgets' glyphs
  bool cells = true;  ///< cells' points, edges and faces
  bool lattices = false;    ///< the lattice's world bounding box
};

/// The widget a ray hit, where.
struct PickResult {
  WidgetId id;  ///< the widget hit
  double t = 0.0;                           ///< along the unit ray direction
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< world hit point
};

/// The mutable part of a model, for undo: control points, variations, lattice frames.
/// Cheap to copy; valid for restoreState only on a model with the same widgets.
struct WidgetModelState {
  std::vector<std::pair<WidgetId, Eigen::MatrixX3d>> controlPoints;  ///< local control points per lattice
  std::vector<std::pair<WidgetId, Eigen::Affine3d>> latticeFrames;  ///< root frame / child placement
  std::vector<std::pair<WidgetId, double>> variations;  ///< variation per affine widget
  /// Control-point weights per lattice (pointCount entries; empty when every weight is 1).
  std::vector<std::pair<WidgetId, Eigen::VectorXd>> weights;
};

/// The headless widget model of Kuriyama 1996, ch. 6 (secs. 6.2.1-6.2.3): lattice widgets that own
/// their lattice's control points, cell widgets on them, affine widgets attached to cells,
/// bindings, and gestures propagated breadth-first. A regular value type: copy it to snapshot
/// everything (a copy does not carry an active gesture; its points are those of the moment it was
/// taken).
///
/// Frames. A lattice's control points are lattice-local; world = latticeFrame(lattice) * local.
/// An attached affine widget's frame is F = L * mask(A_cell) * C0 * O (Kuriyama 1996, sec. 6.2.1):
/// L the lattice frame, A_cell the cell's fitted affine elements, C0 the cell's rest frame, O the
/// placement. Motions use F's rigid part (polar decomposition), so distances and angles are
/// world-true.
///
/// Every throwing member throws WidgetError and leaves the model unchanged.
class WidgetModel {
 public:
  WidgetModel();
  ~WidgetModel();
  /// A deep copy (without an active gesture).
  WidgetModel(const WidgetModel&);
  /// A deep copy (without an active gesture).
  WidgetModel& operator=(const WidgetModel&);
  /// Moves the model.
  WidgetModel(WidgetModel&&) noexcept;
  /// Moves the model.
  WidgetModel& operator=(WidgetModel&&) noexcept;

  // ---- building -------------------------------------------------------------------------
  /// A root lattice widget. @throws InvalidArgument for counts < 2, a rest matrix of the wrong
  /// shape or non-finite values, a duplicate name.
  WidgetId addLattice(const LatticeOptions& options = {});
  /// Shorthand: a root lattice of `counts` points in the unit box at the world origin.
  WidgetId addLattice(std::string name, const Eigen::Vector3i& counts);
  /// A cell of `lattice`. @throws UnknownWidget, InvalidArgument (see cellPointIndices).
  WidgetId addCell(WidgetId lattice, const CellSpec& spec, std::string name = {});
  /// An affine widget attached to `cell` (creates the Attachment binding).
  WidgetId addAffine(WidgetId cell, AffineKind kind, const AffineOptions& options = {});
  /// Shorthand: named, at `placement` relative to the cell's rest frame, default mask and glyph.
  WidgetId addAffine(WidgetId cell, AffineKind kind, std::string name,
                     const Eigen::Affine3d& placement = Eigen::Affine3d::Identity());
  /// A free affine widget (no cell; e.g. a press handle): placement is its world frame.
  WidgetId addFreeAffine(AffineKind kind, const AffineOptions& options = {});

  /// Binds two widgets; the kind follows from their types (cell+affine -> Attachment,
  /// affine+affine -> Variation, cell+cell -> CellMotion, cell+lattice -> Hierarchy; the
  /// order of the arguments is kept as from/to where the kind allows either).
  /// A Hierarchy binding keeps the child's current world frame.
  /// @throws UnknownWidget; InvalidBinding for a self binding, an unsupported pair, a second
  ///   attachment of one affine widget, a duplicate binding, a hierarchy cycle; InvalidArgument
  ///   for a zero / non-finite gain or an empty clamp range; InconsistentLoop when the binding
  ///   closes a loop whose gains do not multiply to 1 or whose masks differ (the message names
  ///   the loop).
  BindingId bind(WidgetId a, WidgetId b, const BindingOptions& options = {});
  /// Shorthand: an affine <-> affine binding with this conversion rule (two-way).
  BindingId bind(WidgetId a, WidgetId b, const ConversionRule& rule);
  /// Shorthand: a binding with this mask (attachment, cell <-> cell, hierarchy; two-way).
  BindingId bind(WidgetId a, WidgetId b, AffineMask mask);
  /// Removes a binding (not an Attachment's cell-widget link of a widget being removed). @throws UnknownWidget.
  void unbind(BindingId binding);
  /// Removes a widget and its bindings. A lattice takes its cells and their attached affine
  /// widgets along; its child lattices become roots at their current world frame. A cell's
  /// attached widgets become free at their current world frame.
  void remove(WidgetId id);

  /// Renames a widget. @throws InvalidArgument for an empty or duplicate name.
  void rename(WidgetId id, std::string name);
  /// Sets an affine widget's placement, relative to its cell's rest frame (free widget: its world frame).
  void setPlacement(WidgetId affine, const Eigen::Affine3d& placement);
  /// Sets an affine widget's glyph.
  void setGlyph(WidgetId affine, const Glyph& glyph);
  /// Changes what an affine widget does (translate / rotate / scale). The points stay where they
  /// are and the variation restarts at 0 (a distance is no angle); a glyph of the old kind's
  /// default shape becomes the new kind's (a library part stays). Bindings are kept.
  void setAffineKind(WidgetId affine, AffineKind kind);
  /// Sets the affine parts a binding passes. @throws InvalidBinding for a Variation binding.
  void setMask(BindingId binding, AffineMask mask);
  /// Sets a Variation binding's conversion rule. @throws InvalidArgument for a zero or non-finite gain.
  void setRule(BindingId binding, const ConversionRule& rule);
  /// Makes a binding one-way (only `from` drives `to`) or two-way.
  void setOneWay(BindingId binding, bool oneWay);
  /// Sets a lattice's bases, outside policy and re-embedding policy.
  void setLatticeSettings(WidgetId lattice, const LatticeSettings& settings);
  /// Changes a lattice's point counts to (l, m, n), each >= 2, keeping its deformation as well as
  /// the new lattice can hold it (like resizing a Blender lattice):
  /// - rest points: a box lattice (affine rest map) stays the same box, its points at the new
  ///   bases' Greville abscissae; a cylindrical one (settings().cylinder) the same analytic
  ///   cylinder; a user-shaped one samples its old rest map Xbar at the new grid parameters.
  /// - control points: rest + the old displacement X(p) - Xbar(p), taken at the rest-space points
  ///   the new lattice puts at its grid parameters and interpolated by the new bases (per axis,
  ///   collocation at the Greville abscissae). An undeformed lattice stays exactly at rest; an
  ///   affine deformation is kept exactly, and so is any deformation the new lattice can
  ///   represent (a Bernstein axis raised from n to n' > n points: degree elevation). An axis
  ///   that loses points samples the displacement at its new parameters instead (no overshoot);
  ///   other deformations are approximated.
  /// - cells: a grid index i of n points goes to round(i (n'-1) / (n-1)) (periodic axis:
  ///   round(i n' / n) mod n'); point, edge, face and box cells move their lower corner, a slab
  ///   its plane, a custom cell each index (duplicates dropped). Attached affine widgets keep
  ///   their placement on their (remapped) cell and their variation; child lattices keep their
  ///   world frame. Bindings and ids are unchanged. Control-point weights go back to 1.
  /// @throws GestureState during a gesture; InvalidArgument for counts < 2, a basis whose degree
  ///   a new count cannot carry, a cell that no longer fits on the new grid (the message names
  ///   it). The model is unchanged on every error.
  void setLatticeCounts(WidgetId lattice, const Eigen::Vector3i& counts);
  /// Root lattice: sets its world frame. @throws InvalidArgument for a child lattice.
  void setLatticeFrame(WidgetId lattice, const Eigen::Affine3d& frame);
  /// Moves a lattice to `position` among its siblings (roots or children of one parent).
  void setSiblingPosition(WidgetId lattice, std::size_t position);
  /// Sets every control point of a lattice (pointCount x 3, local).
  void setControlPoints(WidgetId lattice, const Eigen::Ref<const Eigen::MatrixX3d>& points);
  /// Sets every control-point weight of a lattice (pointCount values, each finite and > 0; all 1
  /// makes it polynomial again). A weight pulls the deformed shape towards its control point
  /// (rational FFD, Lamousin & Waggenspack 1994); the rest lattice keeps weights 1, so weights
  /// deform without re-embedding. Reported like a control-point edit (controlRevision, the
  /// lattice's control points in WidgetChanges); undoable through captureState/restoreState.
  /// @throws GestureState during a gesture; InvalidArgument on a wrong count or a bad weight
  ///   (naming the point). The model is unchanged on every error.
  void setWeights(WidgetId lattice, const Eigen::Ref<const Eigen::VectorXd>& weights);
  /// Sets the weight of control point `point` (flat index). @throws like setWeights, and
  /// InvalidArgument on a point index out of range.
  void setWeight(WidgetId lattice, Eigen::Index point, double weight);
  /// Back to rest: control points = rest points, weights = 1, variations of the lattice's widgets = 0.
  void resetLattice(WidgetId lattice);

  // ---- queries --------------------------------------------------------------------------
  /// True if the model holds widget `id`.
  bool contains(WidgetId id) const;
  /// Lattice, cell or affine. @throws UnknownWidget.
  WidgetType type(WidgetId id) const;
  /// The widget's unique name. @throws UnknownWidget.
  const std::string& name(WidgetId id) const;
  /// The widget of that name. @throws UnknownWidget naming the known names.
  WidgetId find(std::string_view name) const;
  std::vector<WidgetId> widgets() const;                   ///< all, in id order
  /// The widgets of one type, in id order.
  std::vector<WidgetId> widgets(WidgetType type) const;
  std::vector<BindingId> bindings() const;                 ///< in id order
  /// The bindings with `id` at either end, in id order.
  std::vector<BindingId> bindingsOf(WidgetId id) const;
  /// The binding `id`. @throws UnknownWidget.
  const Binding& binding(BindingId id) const;
  // ---- revisions and change sets (widget_changes.h) ----------------------------------------
  /// Grows by one with every mutation; each item the mutation changed is stamped with it.
  std::uint64_t revision() const;
  /// Identity of this model's revision history: a copy, or a model made by fromData, is a new
  /// instance (a consumer that sees another instance takes the model in full).
  std::uint64_t instance() const;
  /// The revision of the last change of the tree shape (see WidgetChanges::structure).
  std::uint64_t structureRevision() const;
  /// The revision of the last change of a lattice's local control points.
  std::uint64_t controlRevision(WidgetId lattice) const;
  /// The revision of the last change of a lattice's rest lattice in the world (frame, rest points,
  /// counts, bases, outside policy; for a child lattice also its parent lattice's points and
  /// frame and its binding): what an embedding of the lattice depends on.
  std::uint64_t frameRevision(WidgetId lattice) const;
  /// The revision of the last change of a widget's own data (name, placement, glyph, variation,
  /// kind, lattice settings, cell points).
  std::uint64_t widgetRevision(WidgetId id) const;
  /// The revision of the last change of a binding's mask, rule or direction (0: never changed).
  std::uint64_t bindingRevision(BindingId binding) const;
  /// Everything changed after revision `since` (exclusive) up to revision().
  WidgetChanges changesSince(std::uint64_t since) const;

  // lattices
  /// Control points per axis (l, m, n).
  Eigen::Vector3i counts(WidgetId lattice) const;
  const Eigen::MatrixX3d& controlPoints(WidgetId lattice) const;  ///< local, pointCount x 3
  const Eigen::MatrixX3d& restPoints(WidgetId lattice) const;     ///< local, pointCount x 3
  /// Control-point weights, pointCount values (all 1 for a polynomial lattice).
  Eigen::VectorXd weights(WidgetId lattice) const;
  /// True when some control-point weight of the lattice is not 1.
  bool isRational(WidgetId lattice) const;
  /// Control points in the world, pointCount x 3.
  Eigen::MatrixX3d worldControlPoints(WidgetId lattice) const;
  Eigen::MatrixX3d worldRestPoints(WidgetId lattice) const;       ///< rest shape at the current frame
  /// world = latticeFrame * local. Root: its frame. Child: parentFrame * mask(A_cell) * C0 * placement.
  Eigen::Affine3d latticeFrame(WidgetId lattice) const;
  /// Bases, outside policy and re-embedding policy of a lattice.
  const LatticeSettings& latticeSettings(WidgetId lattice) const;
  /// The FFD engine's lattice for a lattice widget: counts, bases, outside policy, rest and
  /// current control points, weights, and its current world frame (what the FFD pipeline deforms with).
  ffd::Lattice ffdLattice(WidgetId lattice) const;
  /// The cell a child lattice rides on (none for a root).
  std::optional<WidgetId> parentCell(WidgetId lattice) const;
  /// The lattice of parentCell() (none for a root).
  std::optional<WidgetId> parentLattice(WidgetId lattice) const;
  std::vector<WidgetId> children(WidgetId lattice) const;  ///< sibling order
  std::vector<WidgetId> roots() const;                     ///< sibling order
  /// The lattices in pre-order (parent before children, siblings in order): the order in which
  /// the FFD pipeline deforms (Kuriyama 1996, secs. 6.2.3, 6.3.2).
  std::vector<WidgetId> pipelineOrder() const;
  /// The lattice `root` and its subtree in the same pre-order (the one traversal every pipeline,
  /// the deformer and the controller use). @throws UnknownWidget, InvalidArgument (not a lattice).
  std::vector<WidgetId> pipelineOrder(WidgetId root) const;
  /// The lattice's cells, in id order.
  std::vector<WidgetId> cellsOf(WidgetId lattice) const;

  // cells
  WidgetId latticeOf(WidgetId cellOrAffine) const;  ///< invalid for a free affine widget
  /// Which points the cell groups, as given.
  const CellSpec& cellSpec(WidgetId cell) const;
  /// Flat indices of the cell's points (cellPointIndices order).
  const std::vector<Eigen::Index>& cellIndices(WidgetId cell) const;
  /// The cell's points in the world, #cell x 3.
  Eigen::MatrixX3d cellWorldPoints(WidgetId cell) const;
  Eigen::Isometry3d cellRestFrame(WidgetId cell) const;   ///< lattice-local
  CellAffine cellAffine(WidgetId cell) const;             ///< lattice-local fit (Kuriyama 1996, sec. 6.2.1)
  /// The cell's current frame in the world (rigid) with its mean scale as size.
  WidgetFrame cellFrame(WidgetId cell) const;
  /// The affine widgets attached to the cell, in id order.
  std::vector<WidgetId> affinesOf(WidgetId cell) const;

  // affine widgets
  /// Translate, rotate or scale.
  AffineKind affineKind(WidgetId affine) const;
  /// The cell the widget is attached to (none for a free widget).
  std::optional<WidgetId> attachedCell(WidgetId affine) const;
  /// Placement relative to the cell's rest frame (free widget: world frame).
  const Eigen::Affine3d& placement(WidgetId affine) const;
  /// Accumulated variation: distance, angle (rad) or log scale factor.
  double variation(WidgetId affine) const;
  /// How the widget is drawn and picked.
  const Glyph& glyph(WidgetId affine) const;
  /// World frame (rigid) and glyph size of an affine widget (Kuriyama 1996, sec. 6.2.1).
  WidgetFrame affineFrame(WidgetId affine) const;
  /// The full (not necessarily rigid) frame an affine widget's placement is relative to:
  /// L * mask(A_cell) * C0 for an attached widget, the identity for a free one; so the widget's
  /// world frame is placementBase(affine) * placement(affine) before its rigid part is taken.
  /// A transformer manipulator that moves the widget by a world motion M sets the placement to
  /// placementBase^-1 * M * placementBase * placement.
  Eigen::Affine3d placementBase(WidgetId affine) const;

  // ---- gestures (Kuriyama 1996, secs. 6.2.1, 6.2.2)
  // -------------------------------------------------------------
  /// Starts a gesture on a widget: records the gesture-start state and the breadth-first
  /// visiting order over the bindings. @throws GestureState if one is active; UnknownWidget.
  void beginGesture(WidgetId id);
  /// Affine widget: the variation change since the start (distance, rad, log scale).
  /// Every update resets the affected points to their gesture-start positions and re-applies
  /// the motions in visiting order: no drift. @throws GestureState.
  void updateGesture(double variationDelta);
  /// Cell or lattice widget: its world motion since the start (an affine map of world space).
  void updateGesture(const Eigen::Affine3d& worldMotion);
  /// Ends the gesture: its changes stay. @throws GestureState if none is active.
  void endGesture();
  /// Restores the gesture-start state.
  void cancelGesture();
  /// True between beginGesture() and endGesture() / cancelGesture().
  bool gestureActive() const;
  /// The widget of the active gesture (none when no gesture is active).
  std::optional<WidgetId> gestureWidget() const;
  /// Widgets that the active gesture visits, in visiting order (for highlighting).
  std::vector<WidgetId> gestureVisitOrder() const;

  // ---- ray interaction (STYLE 9): rays in, semantic gestures out -------------------------
  /// Nearest widget glyph hit by the ray (affine glyphs: arrow segment, ring, cube; cells:
  /// points as spheres of radius tolerance, edges as segments, faces as quads); nullopt on a miss.
  std::optional<PickResult> pick(const Ray& ray, const PickOptions& options = {}) const;
  /// Begins a drag of `id` grabbed by `ray`: translate along the axis line, rotate in the
  /// widget's xy plane, scale by the distance ratio from the origin in the view plane; cells and
  /// lattices translate in the view plane through the grab point.
  void beginDrag(WidgetId id, const Ray& ray);
  /// Updates the active drag from the current mouse ray. Rays parallel to the drag line or plane
  /// keep the last value.
  void dragTo(const Ray& ray);

  // ---- scripting conveniences (one whole gesture each) -----------------------------------
  /// begin + update(delta) + end on an affine widget.
  void applyVariation(WidgetId affine, double delta);
  /// Sets the variation of an affine widget to `value` through a gesture (bindings follow).
  void setVariation(WidgetId affine, double value);
  /// begin + update(worldMotion) + end on a cell or a lattice.
  void applyMotion(WidgetId id, const Eigen::Affine3d& worldMotion);

  // ---- state and data ---------------------------------------------------------------------
  /// Control points, variations and lattice frames, for undo (restoreState()).
  WidgetModelState captureState() const;
  /// @throws InvalidArgument if the state names other widgets or shapes than this model holds.
  void restoreState(const WidgetModelState& state);
  /// The whole model as plain data (what a widget file holds).
  WidgetModelData toData() const;
  /// Builds a model from data, validating ids, references, names, shapes and every binding as
  /// bind() would. Errors carry a location ("/bindings/2/to").
  static WidgetModel fromData(const WidgetModelData& data);
  /// Makes this model hold `data` (validated as fromData validates it) IN PLACE: the same
  /// instance, its revision history going on, one new revision stamped on just the widgets and
  /// bindings whose records differ (added, removed, changed) and on the structure when the trees'
  /// shape differs. Ids are the data's. An undo or redo of a structural edit goes through it, so
  /// its consumers update only what it changed (changesSince) instead of taking a new model.
  /// @throws GestureState during a gesture; WidgetError as fromData (the model is unchanged).
  void assignData(const WidgetModelData& data);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ffdkit::widgets
