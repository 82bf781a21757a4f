#pragma once

// Private to the widget model's sources: the model's state (WidgetModel::Impl) and the frame
// maths its parts share. The definitions are split by concept: widget_frames.cpp (frame maths),
// widget_binding_graph.cpp (bindings, loops), widget_gestures.cpp (gesture propagation),
// widget_picking.cpp (rays), lattice_counts.cpp (resampling), widget_queries.cpp,
// widget_model_data.cpp (state and data), widget_model.cpp (building and editing).

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/LU>
#include <Eigen/SVD>

#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::widgets {
namespace detail {

[[noreturn]] void fail(WidgetErrorCode code, const std::string& message);
inline bool finite(const Eigen::Ref<const Eigen::MatrixXd>& m) { return m.allFinite(); }
// A frame, placement or motion the model can use: finite and invertible.
template <class Transform>
bool finiteAndInvertible(const Transform& t) {
  return t.matrix().allFinite() && std::abs(t.linear().determinant()) >= 1e-300;
}
// The rows of `points` at `indices`, in that order (a cell's points of its lattice).
inline Eigen::MatrixX3d gatherRows(const Eigen::MatrixX3d& points, const std::vector<Eigen::Index>& indices) {
  Eigen::MatrixX3d rows(static_cast<Eigen::Index>(indices.size()), 3);
  for (std::size_t r = 0; r < indices.size(); ++r) rows.row(static_cast<Eigen::Index>(r)) = points.row(indices[r]);
  return rows;
}
// Rigid part and mean scale of an affine map (polar decomposition, via SVD).
WidgetFrame rigidPart(const Eigen::Affine3d& a);
// The local motion D(delta) of an affine widget in its own frame (Kuriyama 1996, sec. 6.2.1).
Eigen::Affine3d localMotion(AffineKind kind, double delta);
// Cell <-> cell transfer (Kuriyama 1996, sec. 6.2.2).
Eigen::Affine3d transferMotion(const Eigen::Affine3d& m, const Eigen::Vector3d& sourceCentroid,
                               const Eigen::Matrix3d& sourceAxes, const Eigen::Vector3d& targetCentroid,
                               const Eigen::Matrix3d& targetAxes, AffineMask mask);
std::string defaultShape(AffineKind kind);
double wrapAngle(double a);

}  // namespace detail

using detail::defaultShape;
using detail::fail;
using detail::finite;
using detail::localMotion;
using detail::rigidPart;
using detail::transferMotion;
using detail::wrapAngle;

struct WidgetModel::Impl {
  struct Node {
    bool alive = false;
    WidgetId id;
    WidgetType type = WidgetType::Lattice;
    std::string name;
    std::vector<BindingId> bindings;  // incident, ascending
    // lattice
    Eigen::Vector3i counts = Eigen::Vector3i::Constant(2);
    Eigen::MatrixX3d rest, control;
    Eigen::VectorXd weights;  // empty: every weight 1
    Eigen::Affine3d frame = Eigen::Affine3d::Identity();  // root frame or child placement
    LatticeSettings settings;
    std::vector<WidgetId> children;
    std::vector<WidgetId> cells;
    BindingId parentBinding;
    // cell
    WidgetId lattice;
    CellSpec spec;
    std::vector<Eigen::Index> indices;
    Eigen::Isometry3d restFrame = Eigen::Isometry3d::Identity();
    Eigen::MatrixX3d restCellPoints;
    std::vector<WidgetId> affines;
    // affine
    AffineKind kind = AffineKind::Translate;
    Eigen::Affine3d placement = Eigen::Affine3d::Identity();
    double variation = 0.0;
    Glyph glyph;
    BindingId attachment;
    // revisions (widget_changes.h): the model revision of the last change of...
    std::uint64_t ownRevision = 0;      // the widget's own data
    std::uint64_t controlRevision = 0;  // lattice: its control points
    std::uint64_t restRevision = 0;     // lattice: its own frame / placement and rest lattice
  };

  struct Step {
    WidgetId node;
    int parent = -1;
    BindingId via;
    bool forward = true;  // traversed from the binding's `from` to its `to`
    WidgetType type = WidgetType::Affine;
    AffineKind kind = AffineKind::Translate;
    Eigen::Isometry3d frame0 = Eigen::Isometry3d::Identity();  // affine: rigid world frame
    double variation0 = 0.0;
    Eigen::Vector3d centroid0 = Eigen::Vector3d::Zero();     // cell / lattice, world
    Eigen::Matrix3d axes0 = Eigen::Matrix3d::Identity();     // cell / lattice, world
    Eigen::Affine3d lattice0 = Eigen::Affine3d::Identity();  // cell: its lattice's frame
    Eigen::Affine3d lattice0Inv = Eigen::Affine3d::Identity();
    const Binding* binding = nullptr;
    // per update
    double delta = 0.0;
    Eigen::Affine3d motion = Eigen::Affine3d::Identity();
  };

  enum class DragMode { Axis, Ring, Radial, Plane };
  struct Drag {
    DragMode mode = DragMode::Plane;
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();   // Axis: direction; Ring, Radial, Plane: normal
    Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
    double s0 = 0.0;
    double lastAngle = 0.0;
    double accumulated = 0.0;
    double lastDelta = 0.0;
    Eigen::Vector3d grab = Eigen::Vector3d::Zero();
    Eigen::Affine3d lastMotion = Eigen::Affine3d::Identity();
  };

  struct Gesture {
    WidgetId target;
    std::vector<Step> steps;
    std::vector<std::pair<WidgetId, std::vector<Eigen::Index>>> affected;  // lattice -> points
    std::vector<std::pair<WidgetId, Eigen::MatrixX3d>> startPoints;
    Eigen::Affine3d targetFrame0 = Eigen::Affine3d::Identity();  // lattice target: frame / placement
    bool latticeMovesItself = false;
    std::optional<Drag> drag;
  };

  std::vector<Node> nodes;
  std::vector<std::optional<Binding>> bindings;
  std::vector<WidgetId> roots;
  std::map<std::string, WidgetId, std::less<>> names;
  std::uint64_t revision = 0;
  std::uint64_t instance = nextInstance();
  std::uint64_t structureRevision = 0;
  std::vector<std::uint64_t> bindingRevisions;  // by binding id; 0: never changed
  std::optional<Gesture> gesture;

  static std::uint64_t nextInstance() {
    static std::atomic<std::uint64_t> counter{0};
    return ++counter;
  }

  // ---- lookup ------------------------------------------------------------------------------
  std::string knownIds() const {
    std::vector<std::string> ids;
    for (const Node& n : nodes)
      if (n.alive) ids.push_back(toString(n.id));
    if (ids.empty()) return "none";
    if (ids.size() > 12) return ids.front() + " .. " + ids.back() + " (" + std::to_string(ids.size()) + " widgets)";
    std::string s;
    for (std::size_t i = 0; i < ids.size(); ++i) s += (i ? ", " : "") + ids[i];
    return s;
  }

  const Node& node(WidgetId id) const {
    if (!id.valid() || id.value >= nodes.size() || !nodes[id.value].alive)
      fail(WidgetErrorCode::UnknownWidget, "unknown widget '" + toString(id) + "' (known: " + knownIds() + ")");
    return nodes[id.value];
  }
  Node& node(WidgetId id) { return const_cast<Node&>(std::as_const(*this).node(id)); }

  const Node& node(WidgetId id, WidgetType type) const {
    const Node& n = node(id);
    if (n.type != type)
      fail(WidgetErrorCode::InvalidArgument, "widget '" + label(id) + "' is a " +
                                                 std::string(widgetTypeName(n.type)) + ", expected a " +
                                                 std::string(widgetTypeName(type)));
    return n;
  }
  Node& node(WidgetId id, WidgetType type) { return const_cast<Node&>(std::as_const(*this).node(id, type)); }

  std::string label(WidgetId id) const {
    if (id.valid() && id.value < nodes.size() && nodes[id.value].alive)
      return nodes[id.value].name + "' (" + toString(id) + ")";
    return toString(id);
  }

  const Binding& binding(BindingId id) const {
    if (!id.valid() || id.value >= bindings.size() || !bindings[id.value])
      fail(WidgetErrorCode::UnknownWidget, "unknown binding '" + toString(id) + "'");
    return *bindings[id.value];
  }

  WidgetId newId() const { return WidgetId{static_cast<std::uint32_t>(nodes.size())}; }

  void checkName(const std::string& name) const {
    if (name.empty()) fail(WidgetErrorCode::InvalidArgument, "widget name must not be empty");
    if (names.count(name)) fail(WidgetErrorCode::InvalidArgument, "widget name '" + name + "' is already used by " + toString(names.find(name)->second));
  }

  std::string defaultName(std::string_view prefix, WidgetId id) const {
    std::string base = std::string(prefix) + std::to_string(id.value);
    std::string name = base;
    for (int k = 1; names.count(name); ++k) name = base + "_" + std::to_string(k);
    return name;
  }

  Node& emplace(WidgetId id, WidgetType type, std::string name) {
    if (nodes.size() <= id.value) nodes.resize(id.value + 1);
    Node& n = nodes[id.value];
    n = Node{};
    n.alive = true;
    n.id = id;
    n.type = type;
    n.name = std::move(name);
    names.emplace(n.name, id);
    return n;
  }

  // ---- derived geometry ------------------------------------------------------------------
  Eigen::MatrixX3d cellPoints(const Node& cell) const {
    const Node& lat = nodes[cell.lattice.value];
    return detail::gatherRows(lat.control, cell.indices);
  }
  CellAffine fit(const Node& cell) const {
    return fitCellAffine(cell.spec, cell.restFrame, cell.restCellPoints, cellPoints(cell));
  }
  // mask(A_cell) * C0, lattice-local.
  Eigen::Affine3d maskedCellFrame(const Node& cell, AffineMask mask) const {
    return fit(cell).matrix(cell.restFrame, mask) * cell.restFrame;
  }
  Eigen::Affine3d latticeFrame(const Node& lat) const {
    if (!lat.parentBinding.valid()) return lat.frame;
    const Binding& b = *bindings[lat.parentBinding.value];
    const Node& cell = nodes[b.from.value];
    return latticeFrame(nodes[cell.lattice.value]) * maskedCellFrame(cell, b.mask) * lat.frame;
  }
  Eigen::Affine3d affineFull(const Node& a) const {
    if (!a.attachment.valid()) return a.placement;
    const Binding& b = *bindings[a.attachment.value];
    const Node& cell = nodes[b.from.value];
    return latticeFrame(nodes[cell.lattice.value]) * maskedCellFrame(cell, b.mask) * a.placement;
  }
  // World centroid and rigid axes of a cell's current state.
  void cellWorld(const Node& cell, const Eigen::Affine3d& l, Eigen::Vector3d& centroid, Eigen::Matrix3d& axes) const {
    const CellAffine f = fit(cell);
    Eigen::Affine3d full = l * f.matrix(cell.restFrame, AffineMask::tr()) * cell.restFrame;
    centroid = full.translation();
    axes = rigidPart(full).frame.linear();
  }

  // One mutation takes one new revision (touch) and stamps every item it changed with it.
  void touch() { ++revision; }
  void markStructure() { structureRevision = revision; }
  void markWidget(WidgetId id) { nodes[id.value].ownRevision = revision; }
  void markControl(WidgetId lattice) { nodes[lattice.value].controlRevision = revision; }
  void markRest(WidgetId lattice) { nodes[lattice.value].restRevision = revision; }
  void markBinding(BindingId id) {
    if (bindingRevisions.size() <= id.value) bindingRevisions.resize(id.value + 1, 0);
    bindingRevisions[id.value] = revision;
  }
  std::uint64_t bindingRevision(BindingId id) const {
    return id.value < bindingRevisions.size() ? bindingRevisions[id.value] : 0;
  }
  // A child lattice's world frame follows its parent cell: its rest lattice changes with the
  // parent's points and frame and with its binding's mask.
  std::uint64_t frameRevision(const Node& lat) const {
    std::uint64_t r = lat.restRevision;
    if (lat.parentBinding.valid()) {
      const Node& parent = nodes[nodes[bindings[lat.parentBinding.value]->from.value].lattice.value];
      r = std::max({r, bindingRevision(lat.parentBinding), parent.controlRevision, frameRevision(parent)});
    }
    return r;
  }
  // What the active gesture's last update (or its cancel) changed: the points of the lattices it
  // moves, the variations of its affine widgets, the frame of a lattice that moves itself.
  void markGesture() {
    const Gesture& g = *gesture;
    for (const auto& [lattice, points] : g.affected) markControl(lattice);
    for (const Step& s : g.steps)
      if (s.type == WidgetType::Affine) markWidget(s.node);
    if (g.latticeMovesItself) markRest(g.target);
  }

  // The FFD engine's lattice for these settings; its errors become WidgetError.
  static ffd::Lattice makeFfd(const Eigen::Vector3i& counts, const LatticeSettings& settings,
                              const Eigen::MatrixX3d& rest, const Eigen::MatrixX3d& control,
                              const Eigen::Affine3d& frame, const Eigen::VectorXd& weights = {}) {
    try {
      ffd::Lattice l(counts, settings.basis, rest, frame);
      l.setOutsidePolicy(settings.outside);
      l.setCylinderRestShape(settings.cylinder);
      l.setControlPoints(control);
      if (weights.size() > 0) l.setWeights(weights);
      return l;
    } catch (const std::invalid_argument& e) {
      fail(WidgetErrorCode::InvalidArgument, e.what());
    }
  }

  void requireNoGesture(std::string_view what) const {
    if (gesture) fail(WidgetErrorCode::GestureState, std::string(what) + " is not allowed during a gesture on " + toString(gesture->target));
  }

  // ---- graph -------------------------------------------------------------------------------
  // Path of bindings from a to b over all bindings (undirected), or empty when unconnected.
  std::vector<BindingId> path(WidgetId a, WidgetId b) const;
  bool isDescendantOrSelf(WidgetId lattice, WidgetId candidate) const;
  // Validates a binding and returns it with its kind and mask decided; throws without changes.
  Binding prepareBinding(WidgetId a, WidgetId b, const BindingOptions& options) const;
  // Whether binding e carries motion from widget u to its other end during a gesture.
  static bool drives(const Binding& e, WidgetId u);
  // Refuses a binding that closes a loop along which one gesture could reach a widget twice
  // (Kuriyama 1996, sec. 6.2.2), unless the loop is consistent: all variation bindings whose gains
  // multiply to 1, or all cell bindings with equal masks. Loops that propagation cannot run around
  // (two widgets attached to different cells meet only at those cells) are harmless and accepted.
  void checkLoop(const Binding& nb) const;
  // The exhaustive form of the loop rule for components of moderate size: with `nb` added, a
  // gesture started anywhere must not reach a widget along two routes that disagree (different
  // kinds, gain products or masks). The cycle test above examines one loop; this one all of
  // them, at O(V (V + E)) per binding, so it is skipped for components above kMaxRouteCheck.
  void checkRoutes(const Binding& nb) const;
  BindingId insertBinding(Binding b, BindingId explicitId);
  void eraseBinding(BindingId id);

  // ---- gestures ------------------------------------------------------------------------------
  Step makeStep(WidgetId id, int parent, BindingId via, bool forward) const;
  void begin(WidgetId target);
  void resetToStart();
  void run(double delta, const Eigen::Affine3d& motion);
};

}  // namespace ffdkit::widgets
