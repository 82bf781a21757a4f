#include "ffdkit/widgets/widget_model.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <utility>

#include <Eigen/LU>
#include <Eigen/SVD>

#include "ffdkit/ffd/cylindrical_lattice.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/widgets/glyph_shape.h"

namespace ffdkit::widgets {
namespace {

[[noreturn]] void fail(WidgetErrorCode code, const std::string& message) { throw WidgetError(code, message); }

bool finite(const Eigen::Ref<const Eigen::MatrixXd>& m) { return m.allFinite(); }

// Rigid part and mean scale of an affine map (polar decomposition, via SVD).
WidgetFrame rigidPart(const Eigen::Affine3d& a) {
  WidgetFrame f;
  f.frame.translation() = a.translation();
  const Eigen::Matrix3d l = a.linear();
  const double det = l.determinant();
  f.size = std::cbrt(std::abs(det));
  const Eigen::Matrix3d ltl = l.transpose() * l;
  const double s2 = ltl.trace() / 3.0;
  if (det > 0 && (ltl - s2 * Eigen::Matrix3d::Identity()).norm() <= 1e-13 * s2) {
    f.frame.linear() = l / std::sqrt(s2);  // a similarity: the common case, no SVD needed
    return f;
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(l, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  f.frame.linear() = svd.matrixU() * d * svd.matrixV().transpose();
  return f;
}

// The local motion D(delta) of an affine widget in its own frame (spec §4).
Eigen::Affine3d localMotion(AffineKind kind, double delta) {
  Eigen::Affine3d d = Eigen::Affine3d::Identity();
  switch (kind) {
    case AffineKind::Translate: d.translation().x() = delta; break;
    case AffineKind::Rotate: d.linear() = Eigen::AngleAxisd(delta, Eigen::Vector3d::UnitZ()).toRotationMatrix(); break;
    case AffineKind::Scale: d.linear() *= std::exp(delta); break;
  }
  return d;
}

// Cell <-> cell transfer (spec §5.3): the same translation vector, the same rotation about the
// target's centroid, the same per-axis scale in the target's axes, as far as the mask allows.
Eigen::Affine3d transferMotion(const Eigen::Affine3d& m, const Eigen::Vector3d& sourceCentroid,
                               const Eigen::Matrix3d& sourceAxes, const Eigen::Vector3d& targetCentroid,
                               const Eigen::Matrix3d& targetAxes, AffineMask mask) {
  const Eigen::Vector3d t = m * sourceCentroid - sourceCentroid;
  const WidgetFrame polar = rigidPart(m);
  const Eigen::Matrix3d r = polar.frame.linear();
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
  if (mask.rotate) linear = r;
  if (mask.scale) {
    const Eigen::Matrix3d k = r.transpose() * m.linear();
    const Eigen::Vector3d s = (sourceAxes.transpose() * k * sourceAxes).diagonal();
    linear = linear * targetAxes * s.asDiagonal() * targetAxes.transpose();
  }
  Eigen::Affine3d out = Eigen::Affine3d::Identity();
  out.linear() = linear;
  out.translation() = targetCentroid + (mask.translate ? t : Eigen::Vector3d::Zero()) - linear * targetCentroid;
  return out;
}

std::string defaultShape(AffineKind kind) {
  switch (kind) {
    case AffineKind::Translate: return "arrow";
    case AffineKind::Rotate: return "ring";
    case AffineKind::Scale: return "cube";
  }
  return "arrow";
}

double wrapAngle(double a) {
  const double twoPi = 2.0 * std::numbers::pi;
  a = std::fmod(a + std::numbers::pi, twoPi);
  if (a < 0) a += twoPi;
  return a - std::numbers::pi;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
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
    Eigen::MatrixX3d p(static_cast<Eigen::Index>(cell.indices.size()), 3);
    for (std::size_t r = 0; r < cell.indices.size(); ++r) p.row(static_cast<Eigen::Index>(r)) = lat.control.row(cell.indices[r]);
    return p;
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
                              const Eigen::Affine3d& frame) {
    try {
      ffd::Lattice l(counts, settings.basis, rest, frame);
      l.setOutsidePolicy(settings.outside);
      l.setCylinderRestShape(settings.cylinder);
      l.setControlPoints(control);
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
  std::vector<BindingId> path(WidgetId a, WidgetId b) const {
    std::vector<BindingId> via(nodes.size());
    std::vector<char> seen(nodes.size(), 0);
    std::vector<WidgetId> queue{a};
    seen[a.value] = 1;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const WidgetId u = queue[q];
      if (u == b) break;
      for (BindingId bid : nodes[u.value].bindings) {
        const Binding& e = *bindings[bid.value];
        const WidgetId v = e.from == u ? e.to : e.from;
        if (seen[v.value]) continue;
        seen[v.value] = 1;
        via[v.value] = bid;
        queue.push_back(v);
      }
    }
    if (!seen[b.value]) return {};
    std::vector<BindingId> out;
    for (WidgetId v = b; v != a;) {
      const Binding& e = *bindings[via[v.value].value];
      out.push_back(e.id);
      v = e.from == v ? e.to : e.from;
    }
    std::reverse(out.begin(), out.end());  // from a to b
    return out;
  }

  bool isDescendantOrSelf(WidgetId lattice, WidgetId candidate) const {
    if (lattice == candidate) return true;
    for (WidgetId c : nodes[lattice.value].children)
      if (isDescendantOrSelf(c, candidate)) return true;
    return false;
  }

  // Validates a binding and returns it with its kind and mask decided; throws without changes.
  Binding prepareBinding(WidgetId a, WidgetId b, const BindingOptions& options) const {
    const Node& na = node(a);
    const Node& nb = node(b);
    if (a == b) fail(WidgetErrorCode::InvalidBinding, "cannot bind widget '" + label(a) + " to itself");
    Binding out;
    out.oneWay = options.oneWay;
    out.rule = options.rule;
    auto pair = [&](WidgetType x, WidgetType y) { return (na.type == x && nb.type == y) || (na.type == y && nb.type == x); };
    auto ordered = [&](WidgetType first) {
      out.from = na.type == first ? a : b;
      out.to = na.type == first ? b : a;
    };
    if (pair(WidgetType::Cell, WidgetType::Affine)) {
      out.kind = BindingKind::Attachment;
      ordered(WidgetType::Cell);
      const Node& aff = nodes[out.to.value];
      if (aff.attachment.valid())
        fail(WidgetErrorCode::InvalidBinding, "affine widget '" + label(out.to) + " is already attached to '" +
                                                  label(bindings[aff.attachment.value]->from));
      out.mask = options.mask.value_or(defaultAttachmentMask(nodes[out.from.value].spec.kind));
    } else if (na.type == WidgetType::Affine && nb.type == WidgetType::Affine) {
      out.kind = BindingKind::Variation;
      out.from = a;
      out.to = b;
      out.mask = AffineMask::none();
      if (!std::isfinite(options.rule.gain) || options.rule.gain == 0.0)
        fail(WidgetErrorCode::InvalidArgument, "conversion gain must be finite and non-zero, got " + std::to_string(options.rule.gain));
      if (options.rule.clamp) {
        const VariationRange& r = *options.rule.clamp;
        if (!std::isfinite(r.min) || !std::isfinite(r.max) || r.min > r.max)
          fail(WidgetErrorCode::InvalidArgument, "clamp range must be finite with min <= max, got [" +
                                                     std::to_string(r.min) + ", " + std::to_string(r.max) + "]");
      }
    } else if (na.type == WidgetType::Cell && nb.type == WidgetType::Cell) {
      out.kind = BindingKind::CellMotion;
      out.from = a;
      out.to = b;
      out.mask = options.mask.value_or(AffineMask::tr());
    } else if (pair(WidgetType::Cell, WidgetType::Lattice)) {
      out.kind = BindingKind::Hierarchy;
      ordered(WidgetType::Cell);
      out.mask = options.mask.value_or(AffineMask::trs());
      const Node& child = nodes[out.to.value];
      const WidgetId parentLattice = nodes[out.from.value].lattice;
      if (child.parentBinding.valid())
        fail(WidgetErrorCode::InvalidBinding, "lattice '" + label(out.to) + " already has a parent cell '" +
                                                  label(bindings[child.parentBinding.value]->from));
      if (isDescendantOrSelf(out.to, parentLattice))
        fail(WidgetErrorCode::InvalidBinding, "binding lattice '" + label(out.to) + " to cell '" + label(out.from) +
                                                  " would make the lattice its own ancestor");
    } else {
      fail(WidgetErrorCode::InvalidBinding, "cannot bind a " + std::string(widgetTypeName(na.type)) + " ('" + label(a) +
                                                ") to a " + std::string(widgetTypeName(nb.type)) + " ('" + label(b) +
                                                "): supported pairs are cell+affine, affine+affine, cell+cell, cell+lattice");
    }
    if (out.kind != BindingKind::Variation && (options.rule.clamp.has_value() || options.rule.gain != 1.0))
      fail(WidgetErrorCode::InvalidArgument, "a conversion rule applies to affine <-> affine bindings only");
    for (BindingId bid : na.bindings) {
      const Binding& e = *bindings[bid.value];
      if ((e.from == a && e.to == b) || (e.from == b && e.to == a))
        fail(WidgetErrorCode::InvalidBinding, "'" + label(a) + " and '" + label(b) + " are already bound by " + toString(e.id));
    }
    checkLoop(out);
    return out;
  }

  // Whether binding e carries motion from widget u to its other end during a gesture.
  static bool drives(const Binding& e, WidgetId u) {
    const bool fromSide = e.from == u;
    switch (e.kind) {
      case BindingKind::Attachment:  // the widget drives its cell; the cell -> widget side only follows
      case BindingKind::Hierarchy:   // the child lattice drives its parent cell; the other side follows
        return !fromSide && !e.oneWay;
      case BindingKind::Variation:
      case BindingKind::CellMotion: return fromSide || !e.oneWay;
    }
    return false;
  }

  // Refuses a binding that closes a loop along which one gesture could reach a widget twice
  // (spec §5), unless the loop is consistent: all variation bindings whose gains multiply to 1,
  // or all cell bindings with equal masks. Loops that propagation cannot run around (two
  // widgets attached to different cells meet only at those cells) are harmless and accepted.
  void checkLoop(const Binding& nb) const {
    const std::vector<BindingId> p = path(nb.to, nb.from);
    if (p.empty()) return;
    // The cycle: nodes v0 = from, v1 = to, ..., and edges[i] joining v_i and v_{i+1 mod n}.
    std::vector<WidgetId> v{nb.from, nb.to};
    std::vector<const Binding*> edges{&nb};
    for (BindingId bid : p) {
      const Binding& e = *bindings[bid.value];
      edges.push_back(&e);
      v.push_back(e.from == v.back() ? e.to : e.from);
    }
    v.pop_back();  // back at `from`
    const std::size_t n = edges.size();
    bool reachTwice = false;
    for (std::size_t s = 0; s < n && !reachTwice; ++s) {
      std::size_t forward = 0, backward = 0;
      while (forward < n && drives(*edges[(s + forward) % n], v[(s + forward) % n])) ++forward;
      while (backward < n && drives(*edges[(s + n - 1 - backward) % n], v[(s + n - backward) % n])) ++backward;
      reachTwice = forward + backward >= n;
    }
    if (!reachTwice) {
      checkRoutes(nb);
      return;
    }
    std::string loop;
    for (WidgetId w : v) loop += toString(w) + " -> ";
    loop += toString(v.front());
    bool allVariation = true, allCell = true, masksEqual = true;
    double gain = 1.0;
    for (std::size_t i = 0; i < n; ++i) {
      const Binding& e = *edges[i];
      allVariation = allVariation && e.kind == BindingKind::Variation;
      allCell = allCell && e.kind == BindingKind::CellMotion;
      if (e.kind == BindingKind::Variation) gain *= e.from == v[i] ? e.rule.gain : 1.0 / e.rule.gain;
      masksEqual = masksEqual && e.mask == nb.mask;
    }
    const std::string head = "binding '" + label(nb.from) + " <-> '" + label(nb.to) + " closes the loop " + loop;
    if (allVariation) {
      if (std::abs(gain - 1.0) > 1e-12)
        fail(WidgetErrorCode::InconsistentLoop, head + " whose gains multiply to " + std::to_string(gain) +
                                                    " (a loop must map a variation to itself: product 1)");
    } else if (allCell) {
      if (!masksEqual)
        fail(WidgetErrorCode::InconsistentLoop, head + " whose masks differ (a loop of cell bindings needs equal masks)");
    } else {
      fail(WidgetErrorCode::InconsistentLoop,
           head + " through bindings of different kinds, along which one gesture would move a widget twice");
    }
    checkRoutes(nb);
  }

  // The exhaustive form of the loop rule for components of moderate size: with `nb` added, a
  // gesture started anywhere must not reach a widget along two routes that disagree (different
  // kinds, gain products or masks). The cycle test above examines one loop; this one all of
  // them, at O(V (V + E)) per binding, so it is skipped for components above kMaxRouteCheck.
  void checkRoutes(const Binding& nb) const {
    constexpr std::size_t kMaxRouteCheck = 256;
    auto incident = [&](WidgetId w, auto&& visit) {
      for (BindingId bid : nodes[w.value].bindings) visit(*bindings[bid.value]);
      if (nb.from == w || nb.to == w) visit(nb);
    };
    std::vector<WidgetId> component{nb.from};
    std::vector<char> inComponent(nodes.size(), 0);
    inComponent[nb.from.value] = 1;
    for (std::size_t q = 0; q < component.size(); ++q) {
      if (component.size() > kMaxRouteCheck) return;
      incident(component[q], [&](const Binding& e) {
        const WidgetId o = e.from == component[q] ? e.to : e.from;
        if (!inComponent[o.value]) {
          inComponent[o.value] = 1;
          component.push_back(o);
        }
      });
    }
    struct Visit {
      int parent = -1;
      const Binding* via = nullptr;
      int depth = 0;
    };
    std::vector<int> slot(nodes.size(), -1);
    for (WidgetId start : component) {
      std::vector<WidgetId> order{start};
      std::vector<Visit> visit(1);
      std::fill(slot.begin(), slot.end(), -1);
      slot[start.value] = 0;
      for (std::size_t q = 0; q < order.size(); ++q) {
        const WidgetId u = order[q];
        incident(u, [&](const Binding& e) {
          if (!drives(e, u) || &e == visit[q].via) return;
          const WidgetId v = e.from == u ? e.to : e.from;
          if (slot[v.value] < 0) {
            slot[v.value] = static_cast<int>(order.size());
            order.push_back(v);
            visit.push_back({static_cast<int>(q), &e, visit[q].depth + 1});
            return;
          }
          // Second arrival at v: compare the route along the tree with the one through u.
          auto route = [&](int from, int to) {  // tree edges from ancestor `to` down to `from`
            std::vector<std::pair<int, const Binding*>> r;
            for (int x = from; x != to; x = visit[static_cast<std::size_t>(x)].parent) r.emplace_back(x, visit[static_cast<std::size_t>(x)].via);
            return r;
          };
          int a = slot[v.value], b = static_cast<int>(q);
          while (visit[static_cast<std::size_t>(a)].depth > visit[static_cast<std::size_t>(b)].depth) a = visit[static_cast<std::size_t>(a)].parent;
          while (visit[static_cast<std::size_t>(b)].depth > visit[static_cast<std::size_t>(a)].depth) b = visit[static_cast<std::size_t>(b)].parent;
          while (a != b) {
            a = visit[static_cast<std::size_t>(a)].parent;
            b = visit[static_cast<std::size_t>(b)].parent;
          }
          const auto first = route(slot[v.value], a);
          auto second = route(static_cast<int>(q), a);
          bool allVariation = e.kind == BindingKind::Variation, allCell = e.kind == BindingKind::CellMotion;
          bool masksEqual = true;
          double gainFirst = 1.0, gainSecond = e.kind == BindingKind::Variation ? (e.from == u ? e.rule.gain : 1.0 / e.rule.gain) : 1.0;
          auto account = [&](const std::vector<std::pair<int, const Binding*>>& r, double& gain) {
            for (const auto& [x, edge] : r) {
              const WidgetId to = order[static_cast<std::size_t>(x)];
              allVariation = allVariation && edge->kind == BindingKind::Variation;
              allCell = allCell && edge->kind == BindingKind::CellMotion;
              masksEqual = masksEqual && edge->mask == e.mask;
              if (edge->kind == BindingKind::Variation) gain *= edge->to == to ? edge->rule.gain : 1.0 / edge->rule.gain;
            }
          };
          account(first, gainFirst);
          account(second, gainSecond);
          const bool consistent = (allVariation && std::abs(gainFirst - gainSecond) <= 1e-12 * std::abs(gainFirst)) ||
                                  (allCell && masksEqual);
          if (consistent) return;
          auto describe = [&](const std::vector<std::pair<int, const Binding*>>& r, const std::string& tail) {
            std::string text = toString(order[static_cast<std::size_t>(a)]);
            for (auto it = r.rbegin(); it != r.rend(); ++it) text += " -> " + toString(order[static_cast<std::size_t>(it->first)]);
            return text + tail;
          };
          fail(WidgetErrorCode::InconsistentLoop,
               "binding '" + label(nb.from) + " <-> '" + label(nb.to) + " closes a loop: a gesture on '" + label(start) +
                   " would reach '" + label(v) + " along two routes that disagree (" + describe(first, "") + " and " +
                   describe(second, " -> " + toString(v)) + ")");
        });
      }
    }
  }

  BindingId insertBinding(Binding b, BindingId explicitId) {
    b.id = explicitId.valid() ? explicitId : BindingId{static_cast<std::uint32_t>(bindings.size())};
    if (bindings.size() <= b.id.value) bindings.resize(b.id.value + 1);
    bindings[b.id.value] = b;
    for (WidgetId w : {b.from, b.to}) {
      auto& list = nodes[w.value].bindings;
      list.insert(std::upper_bound(list.begin(), list.end(), b.id), b.id);
    }
    if (b.kind == BindingKind::Attachment) {
      nodes[b.to.value].attachment = b.id;
      nodes[b.from.value].affines.push_back(b.to);
    } else if (b.kind == BindingKind::Hierarchy) {
      Node& child = nodes[b.to.value];
      child.parentBinding = b.id;
      roots.erase(std::remove(roots.begin(), roots.end(), b.to), roots.end());
      nodes[nodes[b.from.value].lattice.value].children.push_back(b.to);
    }
    return b.id;
  }

  void eraseBinding(BindingId id) {
    const Binding b = *bindings[id.value];
    if (b.kind == BindingKind::Attachment) {
      Node& aff = nodes[b.to.value];
      aff.placement = affineFull(aff);  // a free widget stays where it was
      aff.attachment = BindingId{};
      auto& list = nodes[b.from.value].affines;
      list.erase(std::remove(list.begin(), list.end(), b.to), list.end());
    } else if (b.kind == BindingKind::Hierarchy) {
      Node& child = nodes[b.to.value];
      child.frame = latticeFrame(child);
      child.parentBinding = BindingId{};
      auto& list = nodes[nodes[b.from.value].lattice.value].children;
      list.erase(std::remove(list.begin(), list.end(), b.to), list.end());
      roots.push_back(b.to);
    }
    for (WidgetId w : {b.from, b.to}) {
      auto& list = nodes[w.value].bindings;
      list.erase(std::remove(list.begin(), list.end(), id), list.end());
    }
    bindings[id.value].reset();
  }

  // ---- gestures ------------------------------------------------------------------------------
  Step makeStep(WidgetId id, int parent, BindingId via, bool forward) const {
    Step s;
    const Node& n = nodes[id.value];
    s.node = id;
    s.parent = parent;
    s.via = via;
    s.forward = forward;
    s.type = n.type;
    s.binding = via.valid() ? &*bindings[via.value] : nullptr;
    if (n.type == WidgetType::Affine) {
      s.kind = n.kind;
      s.frame0 = rigidPart(affineFull(n)).frame;
      s.variation0 = n.variation;
    } else if (n.type == WidgetType::Cell) {
      s.lattice0 = latticeFrame(nodes[n.lattice.value]);
      s.lattice0Inv = s.lattice0.inverse();
      cellWorld(n, s.lattice0, s.centroid0, s.axes0);
    } else {
      const Eigen::Affine3d l = latticeFrame(n);
      s.centroid0 = l * Eigen::Vector3d(n.control.colwise().mean().transpose());
      s.axes0 = rigidPart(l).frame.linear();
    }
    return s;
  }

  void begin(WidgetId target) {
    if (gesture) fail(WidgetErrorCode::GestureState, "a gesture on '" + label(gesture->target) + " is already active");
    const Node& t = node(target);
    Gesture g;
    g.target = target;
    std::vector<char> visited(nodes.size(), 0);
    visited[target.value] = 1;
    g.steps.push_back(makeStep(target, -1, BindingId{}, true));
    for (std::size_t s = 0; s < g.steps.size(); ++s) {
      const WidgetId u = g.steps[s].node;
      const Node& nu = nodes[u.value];
      for (BindingId bid : nu.bindings) {
        const Binding& b = *bindings[bid.value];
        const bool uIsFrom = b.from == u;
        const WidgetId v = uIsFrom ? b.to : b.from;
        if (visited[v.value] || (!uIsFrom && b.oneWay)) continue;
        bool drives = false;
        switch (b.kind) {
          case BindingKind::Attachment: drives = !uIsFrom; break;  // widget drives cell; cell -> widget is following
          case BindingKind::Variation:
          case BindingKind::CellMotion: drives = true; break;
          case BindingKind::Hierarchy: drives = !uIsFrom; break;  // child lattice drives its parent cell
        }
        if (!drives) continue;
        visited[v.value] = 1;
        g.steps.push_back(makeStep(v, static_cast<int>(s), bid, uIsFrom));
      }
    }
    if (t.type == WidgetType::Lattice) {
      g.targetFrame0 = t.frame;
      g.latticeMovesItself = !(t.parentBinding.valid() && !bindings[t.parentBinding.value]->oneWay);
    }
    // Points that the motions touch, per lattice, and their start positions.
    std::map<std::uint32_t, std::vector<Eigen::Index>> touched;
    for (const Step& s : g.steps) {
      if (s.type != WidgetType::Cell) continue;
      const Node& c = nodes[s.node.value];
      auto& list = touched[c.lattice.value];
      list.insert(list.end(), c.indices.begin(), c.indices.end());
    }
    for (auto& [lat, list] : touched) {
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
      g.affected.emplace_back(WidgetId{lat}, std::move(list));
      g.startPoints.emplace_back(WidgetId{lat}, nodes[lat].control);
    }
    gesture = std::move(g);
  }

  void resetToStart() {
    Gesture& g = *gesture;
    for (std::size_t a = 0; a < g.affected.size(); ++a) {
      Node& lat = nodes[g.affected[a].first.value];
      const Eigen::MatrixX3d& start = g.startPoints[a].second;
      for (Eigen::Index i : g.affected[a].second) lat.control.row(i) = start.row(i);
    }
    for (const Step& s : g.steps)
      if (s.type == WidgetType::Affine) nodes[s.node.value].variation = s.variation0;
    if (nodes[g.target.value].type == WidgetType::Lattice) nodes[g.target.value].frame = g.targetFrame0;
  }

  void run(double delta, const Eigen::Affine3d& motion) {
    Gesture& g = *gesture;
    resetToStart();
    for (std::size_t i = 0; i < g.steps.size(); ++i) {
      Step& s = g.steps[i];
      if (i == 0) {
        s.delta = delta;
        s.motion = motion;
      } else {
        const Step& p = g.steps[static_cast<std::size_t>(s.parent)];
        const Binding& b = *s.binding;
        switch (b.kind) {
          case BindingKind::Attachment:
            s.motion = p.frame0 * localMotion(p.kind, p.delta) * p.frame0.inverse();
            break;
          case BindingKind::Variation: {
            double d = s.forward ? b.rule.gain * p.delta : p.delta / b.rule.gain;
            if (s.forward && b.rule.clamp) {
              const double lo = std::min(b.rule.clamp->min, s.variation0), hi = std::max(b.rule.clamp->max, s.variation0);
              d = std::clamp(s.variation0 + d, lo, hi) - s.variation0;
            }
            s.delta = d;
            break;
          }
          case BindingKind::CellMotion:
          case BindingKind::Hierarchy:
            s.motion = transferMotion(p.motion, p.centroid0, p.axes0, s.centroid0, s.axes0, b.mask);
            break;
        }
      }
      Node& n = nodes[s.node.value];
      switch (s.type) {
        case WidgetType::Affine: n.variation = s.variation0 + s.delta; break;
        case WidgetType::Cell: {
          const Eigen::Affine3d local = s.lattice0Inv * s.motion * s.lattice0;
          Node& lat = nodes[n.lattice.value];
          for (Eigen::Index r : n.indices) lat.control.row(r) = (local * Eigen::Vector3d(lat.control.row(r).transpose())).transpose();
          break;
        }
        case WidgetType::Lattice:
          if (i == 0 && g.latticeMovesItself) {
            if (!n.parentBinding.valid()) {
              n.frame = s.motion * g.targetFrame0;
            } else {
              const Eigen::Affine3d l0 = latticeFrame(n);  // frame at start: the parent is not driven
              n.frame = g.targetFrame0 * l0.inverse() * s.motion * l0;
            }
          }
          break;
      }
    }
    touch();
    markGesture();
  }
};

// ---------------------------------------------------------------------------------------------
WidgetModel::WidgetModel() : impl_(std::make_unique<Impl>()) {}
WidgetModel::~WidgetModel() = default;
// A copy is another revision history (its consumers must not mistake it for the original).
WidgetModel::WidgetModel(const WidgetModel& o) : impl_(std::make_unique<Impl>(*o.impl_)) {
  impl_->gesture.reset();
  impl_->instance = Impl::nextInstance();
}
WidgetModel& WidgetModel::operator=(const WidgetModel& o) {
  if (this != &o) {
    impl_ = std::make_unique<Impl>(*o.impl_);
    impl_->gesture.reset();  // steps point into the source's bindings
    impl_->instance = Impl::nextInstance();
  }
  return *this;
}
WidgetModel::WidgetModel(WidgetModel&&) noexcept = default;
WidgetModel& WidgetModel::operator=(WidgetModel&&) noexcept = default;

WidgetId WidgetModel::addLattice(const LatticeOptions& options) {
  Impl& m = *impl_;
  m.requireNoGesture("adding a lattice");
  const Eigen::Vector3i& c = options.counts;
  if ((c.array() < 2).any())
    fail(WidgetErrorCode::InvalidArgument, "lattice needs >= 2 points per axis, got (" + std::to_string(c.x()) + ", " +
                                               std::to_string(c.y()) + ", " + std::to_string(c.z()) + ")");
  if (static_cast<double>(c.x()) * c.y() * c.z() > 1e8)
    fail(WidgetErrorCode::InvalidArgument, "lattice has too many control points (at most 1e8): (" + std::to_string(c.x()) +
                                               ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) + ")");
  const Eigen::Index n = static_cast<Eigen::Index>(c.prod());
  Eigen::MatrixX3d rest = options.restPoints;
  if (rest.rows() == 0) {
    // The engine's box lattice: the unit box, B-spline rest points at the Greville abscissae.
    ffd::BoxLatticeOptions box;
    box.counts = c;
    box.bases = options.settings.basis;
    box.capDegreeToCount = false;
    try {
      rest = ffd::makeBoxLattice(box).restPoints();
    } catch (const std::invalid_argument& e) {
      fail(WidgetErrorCode::InvalidArgument, e.what());
    }
  } else if (rest.rows() != n) {
    fail(WidgetErrorCode::InvalidArgument, "rest points must be " + std::to_string(n) + " x 3, got " +
                                               std::to_string(rest.rows()) + " x 3");
  }
  if (!finite(rest) || !finite(options.frame.matrix()))
    fail(WidgetErrorCode::InvalidArgument, "lattice rest points and frame must be finite");
  if (std::abs(options.frame.linear().determinant()) < 1e-300)
    fail(WidgetErrorCode::InvalidArgument, "lattice frame must be invertible");
  if (options.settings.reembed.kind == ReembedKind::EveryN && options.settings.reembed.everyN < 1)
    fail(WidgetErrorCode::InvalidArgument, "re-embed every N needs N >= 1");
  Impl::makeFfd(c, options.settings, rest, rest, options.frame);  // validates bases and policy
  const WidgetId id = m.newId();
  std::string name = options.name.empty() ? m.defaultName("lattice", id) : options.name;
  m.checkName(name);
  Impl::Node& node = m.emplace(id, WidgetType::Lattice, std::move(name));
  node.counts = c;
  node.rest = rest;
  node.control = rest;
  node.frame = options.frame;
  node.settings = options.settings;
  m.roots.push_back(id);
  m.touch();
  m.markStructure();
  m.markWidget(id);
  m.markControl(id);
  m.markRest(id);
  return id;
}

WidgetId WidgetModel::addLattice(std::string name, const Eigen::Vector3i& counts) {
  LatticeOptions o;
  o.name = std::move(name);
  o.counts = counts;
  return addLattice(o);
}

WidgetId WidgetModel::addAffine(WidgetId cell, AffineKind kind, std::string name, const Eigen::Affine3d& placement) {
  AffineOptions o;
  o.name = std::move(name);
  o.placement = placement;
  return addAffine(cell, kind, o);
}

BindingId WidgetModel::bind(WidgetId a, WidgetId b, const ConversionRule& rule) {
  BindingOptions o;
  o.rule = rule;
  return bind(a, b, o);
}

BindingId WidgetModel::bind(WidgetId a, WidgetId b, AffineMask mask) {
  BindingOptions o;
  o.mask = mask;
  return bind(a, b, o);
}

WidgetId WidgetModel::addCell(WidgetId lattice, const CellSpec& spec, std::string name) {
  Impl& m = *impl_;
  m.requireNoGesture("adding a cell");
  const Impl::Node& lat = m.node(lattice, WidgetType::Lattice);
  std::vector<Eigen::Index> indices = cellPointIndices(lat.counts, spec);
  const WidgetId id = m.newId();
  if (name.empty()) name = m.defaultName(cellKindName(spec.kind), id);
  m.checkName(name);
  Eigen::MatrixX3d rest(static_cast<Eigen::Index>(indices.size()), 3);
  for (std::size_t r = 0; r < indices.size(); ++r) rest.row(static_cast<Eigen::Index>(r)) = lat.rest.row(indices[r]);
  const Eigen::Isometry3d frame = widgets::cellRestFrame(spec, lat.counts, rest);
  Impl::Node& node = m.emplace(id, WidgetType::Cell, std::move(name));
  node.lattice = lattice;
  node.spec = spec;
  node.indices = std::move(indices);
  node.restCellPoints = std::move(rest);
  node.restFrame = frame;
  m.nodes[lattice.value].cells.push_back(id);
  m.touch();
  m.markStructure();
  m.markWidget(id);
  return id;
}

WidgetId WidgetModel::addFreeAffine(AffineKind kind, const AffineOptions& options) {
  Impl& m = *impl_;
  m.requireNoGesture("adding an affine widget");
  if (!finite(options.placement.matrix()) || std::abs(options.placement.linear().determinant()) < 1e-300)
    fail(WidgetErrorCode::InvalidArgument, "placement must be finite and invertible");
  if (options.glyph && !(options.glyph->size > 0.0 && std::isfinite(options.glyph->size)))
    fail(WidgetErrorCode::InvalidArgument, "glyph size must be positive");
  const WidgetId id = m.newId();
  std::string name = options.name.empty() ? m.defaultName(affineKindName(kind), id) : options.name;
  m.checkName(name);
  Impl::Node& node = m.emplace(id, WidgetType::Affine, std::move(name));
  node.kind = kind;
  node.placement = options.placement;
  node.glyph = options.glyph.value_or(Glyph{defaultShape(kind), 0.2, Eigen::Affine3d::Identity()});
  if (node.glyph.shape.empty()) node.glyph.shape = defaultShape(kind);
  m.touch();
  m.markStructure();
  m.markWidget(id);
  return id;
}

WidgetId WidgetModel::addAffine(WidgetId cell, AffineKind kind, const AffineOptions& options) {
  Impl& m = *impl_;
  m.requireNoGesture("adding an affine widget");
  const Impl::Node& c = m.node(cell, WidgetType::Cell);
  const AffineMask mask = options.mask.value_or(defaultAttachmentMask(c.spec.kind));
  const WidgetId id = addFreeAffine(kind, options);
  Binding b;
  b.kind = BindingKind::Attachment;
  b.from = cell;
  b.to = id;
  b.mask = mask;
  m.insertBinding(b, BindingId{});  // a fresh widget closes no loop; placement stays cell-relative
  m.markStructure();  // the revision addFreeAffine took
  return id;
}

BindingId WidgetModel::bind(WidgetId a, WidgetId b, const BindingOptions& options) {
  Impl& m = *impl_;
  m.requireNoGesture("binding");
  Binding nb = m.prepareBinding(a, b, options);
  if (nb.kind == BindingKind::Attachment) {
    // Keep the free widget where it is: its world placement becomes cell-relative.
    Impl::Node& aff = m.nodes[nb.to.value];
    const Impl::Node& cell = m.nodes[nb.from.value];
    const Eigen::Affine3d base = m.latticeFrame(m.nodes[cell.lattice.value]) * m.maskedCellFrame(cell, nb.mask);
    aff.placement = base.inverse() * aff.placement;
  } else if (nb.kind == BindingKind::Hierarchy) {
    Impl::Node& child = m.nodes[nb.to.value];
    const Impl::Node& cell = m.nodes[nb.from.value];
    const Eigen::Affine3d base = m.latticeFrame(m.nodes[cell.lattice.value]) * m.maskedCellFrame(cell, nb.mask);
    child.frame = base.inverse() * child.frame;
  }
  const BindingId id = m.insertBinding(nb, BindingId{});
  m.touch();
  m.markStructure();
  m.markBinding(id);
  if (nb.kind == BindingKind::Attachment) m.markWidget(nb.to);  // its placement became cell-relative
  if (nb.kind == BindingKind::Hierarchy) m.markRest(nb.to);
  return id;
}

void WidgetModel::unbind(BindingId binding) {
  Impl& m = *impl_;
  m.requireNoGesture("unbinding");
  const Binding old = m.binding(binding);
  m.eraseBinding(binding);
  m.touch();
  m.markStructure();
  if (old.kind == BindingKind::Attachment) m.markWidget(old.to);  // free at its world frame
  if (old.kind == BindingKind::Hierarchy) m.markRest(old.to);       // a root at its world frame
}

void WidgetModel::remove(WidgetId id) {
  Impl& m = *impl_;
  m.requireNoGesture("removing a widget");
  const Impl::Node& n = m.node(id);
  const WidgetType removedType = n.type;
  std::vector<WidgetId> doomed{id};
  if (removedType == WidgetType::Lattice) {
    for (WidgetId c : n.cells) {
      doomed.push_back(c);
      for (WidgetId a : m.nodes[c.value].affines) doomed.push_back(a);
    }
  }
  // Widgets left behind (affine widgets freed, child lattices made roots) keep their world frames
  // through new placements / root frames.
  std::vector<WidgetId> freed;
  for (WidgetId w : doomed)
    for (BindingId b : m.nodes[w.value].bindings)
      if (const Binding& binding = *m.bindings[b.value];
          binding.kind != BindingKind::Variation && binding.kind != BindingKind::CellMotion &&
          std::find(doomed.begin(), doomed.end(), binding.to) == doomed.end())
        freed.push_back(binding.to);
  // Bindings first (free widgets and orphaned child lattices keep their world frames), then nodes.
  for (WidgetId w : doomed) {
    while (!m.nodes[w.value].bindings.empty()) m.eraseBinding(m.nodes[w.value].bindings.front());
  }
  for (WidgetId w : doomed) {
    Impl::Node& d = m.nodes[w.value];
    m.names.erase(d.name);
    if (d.type == WidgetType::Cell && removedType != WidgetType::Lattice) {
      auto& cells = m.nodes[d.lattice.value].cells;
      cells.erase(std::remove(cells.begin(), cells.end(), w), cells.end());
    }
    if (d.type == WidgetType::Lattice) m.roots.erase(std::remove(m.roots.begin(), m.roots.end(), w), m.roots.end());
    d = Impl::Node{};
  }
  m.touch();
  m.markStructure();
  for (WidgetId w : freed) {
    if (m.nodes[w.value].type == WidgetType::Lattice) m.markRest(w);
    else m.markWidget(w);
  }
}

void WidgetModel::rename(WidgetId id, std::string name) {
  Impl& m = *impl_;
  Impl::Node& n = m.node(id);
  if (n.name == name) return;
  m.checkName(name);
  m.names.erase(n.name);
  n.name = std::move(name);
  m.names.emplace(n.name, id);
  m.touch();
  m.markWidget(id);
}

void WidgetModel::setPlacement(WidgetId affine, const Eigen::Affine3d& placement) {
  Impl& m = *impl_;
  m.requireNoGesture("setting a placement");
  Impl::Node& n = m.node(affine, WidgetType::Affine);
  if (!finite(placement.matrix()) || std::abs(placement.linear().determinant()) < 1e-300)
    fail(WidgetErrorCode::InvalidArgument, "placement must be finite and invertible");
  n.placement = placement;
  m.touch();
  m.markWidget(affine);
}

void WidgetModel::setGlyph(WidgetId affine, const Glyph& glyph) {
  Impl& m = *impl_;
  Impl::Node& n = m.node(affine, WidgetType::Affine);
  if (!(glyph.size > 0.0 && std::isfinite(glyph.size)) || glyph.shape.empty())
    fail(WidgetErrorCode::InvalidArgument, "glyph needs a shape name and a positive size");
  n.glyph = glyph;
  m.touch();
  m.markWidget(affine);
}

void WidgetModel::setAffineKind(WidgetId affine, AffineKind kind) {
  Impl& m = *impl_;
  m.requireNoGesture("changing an affine widget's kind");
  Impl::Node& n = m.node(affine, WidgetType::Affine);
  if (n.kind == kind) return;
  if (n.glyph.shape == defaultShape(n.kind)) n.glyph.shape = defaultShape(kind);
  n.kind = kind;
  n.variation = 0.0;
  m.touch();
  m.markWidget(affine);
}

void WidgetModel::setMask(BindingId binding, AffineMask mask) {
  Impl& m = *impl_;
  m.requireNoGesture("setting a mask");
  const Binding old = m.binding(binding);
  if (old.kind == BindingKind::Variation) fail(WidgetErrorCode::InvalidArgument, "a variation binding has no mask");
  if (old.mask == mask) return;
  // Re-check the loop with the new mask: temporarily take the binding out.
  Binding nb = old;
  nb.mask = mask;
  m.bindings[binding.value].reset();
  for (WidgetId w : {old.from, old.to}) {
    auto& l = m.nodes[w.value].bindings;
    l.erase(std::remove(l.begin(), l.end(), binding), l.end());
  }
  auto restore = [&] {
    m.bindings[binding.value] = old;
    for (WidgetId w : {old.from, old.to}) {
      auto& l = m.nodes[w.value].bindings;
      l.insert(std::upper_bound(l.begin(), l.end(), binding), binding);
    }
  };
  try {
    m.checkLoop(nb);
  } catch (...) {
    restore();
    throw;
  }
  restore();
  // Keep the follower where it is under the new mask.
  if (old.kind == BindingKind::Attachment) {
    Impl::Node& aff = m.nodes[old.to.value];
    const Eigen::Affine3d world = m.affineFull(aff);
    m.bindings[binding.value]->mask = mask;
    const Impl::Node& cell = m.nodes[old.from.value];
    aff.placement = (m.latticeFrame(m.nodes[cell.lattice.value]) * m.maskedCellFrame(cell, mask)).inverse() * world;
  } else if (old.kind == BindingKind::Hierarchy) {
    Impl::Node& child = m.nodes[old.to.value];
    const Eigen::Affine3d world = m.latticeFrame(child);
    m.bindings[binding.value]->mask = mask;
    const Impl::Node& cell = m.nodes[old.from.value];
    child.frame = (m.latticeFrame(m.nodes[cell.lattice.value]) * m.maskedCellFrame(cell, mask)).inverse() * world;
  } else {
    m.bindings[binding.value]->mask = mask;
  }
  m.touch();
  m.markBinding(binding);
  if (old.kind == BindingKind::Attachment) m.markWidget(old.to);  // its placement keeps it in place
  if (old.kind == BindingKind::Hierarchy) m.markRest(old.to);
}

void WidgetModel::setRule(BindingId binding, const ConversionRule& rule) {
  Impl& m = *impl_;
  m.requireNoGesture("setting a conversion rule");
  const Binding old = m.binding(binding);
  if (old.kind != BindingKind::Variation)
    fail(WidgetErrorCode::InvalidArgument, "a conversion rule applies to affine <-> affine bindings only");
  // Validate as a fresh binding would be, without this binding in the graph.
  m.eraseBinding(binding);
  try {
    BindingOptions o;
    o.rule = rule;
    o.oneWay = old.oneWay;
    Binding nb = m.prepareBinding(old.from, old.to, o);
    m.insertBinding(nb, binding);
  } catch (...) {
    m.insertBinding(old, binding);
    throw;
  }
  m.touch();
  m.markBinding(binding);
}

void WidgetModel::setOneWay(BindingId binding, bool oneWay) {
  Impl& m = *impl_;
  m.requireNoGesture("changing a binding direction");
  m.binding(binding);
  m.bindings[binding.value]->oneWay = oneWay;
  m.touch();
  m.markBinding(binding);
}

void WidgetModel::setLatticeSettings(WidgetId lattice, const LatticeSettings& settings) {
  Impl& m = *impl_;
  Impl::Node& n = m.node(lattice, WidgetType::Lattice);
  if (settings.reembed.kind == ReembedKind::EveryN && settings.reembed.everyN < 1)
    fail(WidgetErrorCode::InvalidArgument, "re-embed every N needs N >= 1, got " + std::to_string(settings.reembed.everyN));
  Impl::makeFfd(n.counts, settings, n.rest, n.control, Eigen::Affine3d::Identity());  // validates bases and policy
  n.settings = settings;
  m.touch();
  m.markWidget(lattice);
  m.markRest(lattice);
}

// ---- setLatticeCounts ---------------------------------------------------------------------------
namespace {

// Index i of n grid points along an axis, moved to a grid of n2 points: the point at the same
// relative position (round(i (n2-1) / (n-1)); a periodic axis has no end point: round(i n2 / n) mod n2).
int remapGridIndex(int i, int n, int n2, bool periodic) {
  if (periodic) return static_cast<int>(std::lround(static_cast<double>(i) * n2 / n)) % n2;
  return static_cast<int>(std::lround(static_cast<double>(i) * (n2 - 1) / (n - 1)));
}

Eigen::Vector3i remapGrid(const Eigen::Vector3i& g, const Eigen::Vector3i& from, const Eigen::Vector3i& to,
                          const std::array<bool, 3>& periodic) {
  Eigen::Vector3i out;
  for (int a = 0; a < 3; ++a) out[a] = remapGridIndex(g[a], from[a], to[a], periodic[static_cast<std::size_t>(a)]);
  return out;
}

std::string countsString(const Eigen::Vector3i& c) {
  return "(" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) + ")";
}

// The cell spec on the new grid (see setLatticeCounts); throws a message (without the cell's
// name) when the cell does not fit or collapses.
CellSpec remapCellSpec(const CellSpec& spec, const Eigen::Vector3i& from, const Eigen::Vector3i& to,
                       const std::array<bool, 3>& periodic) {
  CellSpec out = spec;
  switch (spec.kind) {
    case CellKind::Point:
    case CellKind::Edge:
    case CellKind::Face:
    case CellKind::Box: out.base = remapGrid(spec.base, from, to, periodic); break;
    case CellKind::Slab: {
      const auto a = static_cast<std::size_t>(spec.axis);
      if (spec.axis >= 0 && spec.axis < 3)
        out.base[spec.axis] = remapGridIndex(spec.base[spec.axis], from[spec.axis], to[spec.axis], periodic[a]);
      break;
    }
    case CellKind::Custom: {
      out.indices.clear();
      const Eigen::Index l = from.x(), m = from.y();
      for (Eigen::Index f : spec.indices) {
        const Eigen::Vector3i g(static_cast<int>(f % l), static_cast<int>((f / l) % m), static_cast<int>(f / (l * m)));
        const Eigen::Vector3i r = remapGrid(g, from, to, periodic);
        const Eigen::Index flat = r.x() + static_cast<Eigen::Index>(to.x()) * (r.y() + static_cast<Eigen::Index>(to.y()) * r.z());
        if (std::find(out.indices.begin(), out.indices.end(), flat) == out.indices.end()) out.indices.push_back(flat);
      }
      break;
    }
  }
  return out;
}

// n x n collocation matrix of an axis: row r holds the basis functions at params[r].
Eigen::MatrixXd collocation(const ffd::AxisSpline& axis, const Eigen::VectorXd& params) {
  const int n = axis.count();
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(params.size(), n);
  std::vector<double> values(static_cast<std::size_t>(axis.degree() + 1));
  for (Eigen::Index r = 0; r < params.size(); ++r) {
    const int cell = axis.cellOf(params[r]);
    axis.basis(cell, params[r], values.data());
    for (int q = 0; q <= axis.degree(); ++q) c(r, axis.controlIndex(cell, q)) += values[static_cast<std::size_t>(q)];
  }
  return c;
}

// Solves (N_w (x) N_v (x) N_u) X = B for X, B one row per grid point (i fastest), one axis at a time.
Eigen::MatrixX3d solveTensor(const std::array<Eigen::MatrixXd, 3>& n, const Eigen::Vector3i& counts, Eigen::MatrixX3d b) {
  const std::array<Eigen::Index, 3> stride{1, counts.x(), static_cast<Eigen::Index>(counts.x()) * counts.y()};
  for (std::size_t a = 0; a < 3; ++a) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(n[a]);
    const int len = counts[static_cast<int>(a)];
    Eigen::MatrixX3d line(len, 3);
    for (Eigen::Index start = 0; start < b.rows(); ++start) {
      if ((start / stride[a]) % len != 0) continue;  // first point of a line along axis a
      for (int r = 0; r < len; ++r) line.row(r) = b.row(start + r * stride[a]);
      const Eigen::MatrixX3d x = lu.solve(line);
      for (int r = 0; r < len; ++r) b.row(start + r * stride[a]) = x.row(r);
    }
  }
  return b;
}

}  // namespace

void WidgetModel::setLatticeCounts(WidgetId lattice, const Eigen::Vector3i& counts) {
  Impl& m = *impl_;
  m.requireNoGesture("changing a lattice's counts");
  const Impl::Node& n = m.node(lattice, WidgetType::Lattice);
  const std::string who = "lattice '" + m.label(lattice);
  if ((counts.array() < 2).any())
    fail(WidgetErrorCode::InvalidArgument, who + " needs >= 2 points per axis, got " + countsString(counts));
  if (static_cast<double>(counts.x()) * counts.y() * counts.z() > 1e8)
    fail(WidgetErrorCode::InvalidArgument, who + " would have too many control points (at most 1e8): " + countsString(counts));
  if (n.counts == counts) return;

  // The bases resolved for the new counts (a degree the count cannot carry fails here).
  std::array<ffd::AxisSpline, 3> axes;
  std::array<bool, 3> periodic{};
  for (int a = 0; a < 3; ++a) {
    const auto s = static_cast<std::size_t>(a);
    try {
      axes[s] = ffd::AxisSpline(n.settings.basis[s], counts[a], a == 0 ? "u" : a == 1 ? "v" : "w");
    } catch (const std::exception& e) {
      fail(WidgetErrorCode::InvalidArgument, who + " cannot take " + std::to_string(counts[a]) + " points along " + "uvw"[a] +
                                                 " with its basis: " + e.what());
    }
    periodic[s] = axes[s].periodic();
  }

  // Cells on the new grid, all checked before anything changes.
  const std::vector<WidgetId> cellIds = n.cells;
  std::vector<CellSpec> specs;
  std::vector<std::vector<Eigen::Index>> indices;
  for (WidgetId c : cellIds) {
    const CellSpec& old = m.nodes[c.value].spec;
    const std::string cellWho = "cell '" + m.label(c) + " (" + std::string(cellKindName(old.kind)) + ")";
    CellSpec spec = remapCellSpec(old, n.counts, counts, periodic);
    try {
      indices.push_back(cellPointIndices(counts, spec));
    } catch (const WidgetError& e) {
      fail(WidgetErrorCode::InvalidArgument, "cannot change " + who + " to " + countsString(counts) + ": " + cellWho +
                                                 " does not fit on the new grid (" + e.message() + ")");
    }
    specs.push_back(std::move(spec));
  }

  // Parameters of the new grid: the Greville abscissae of the new bases, and the same relative
  // position in the old parameter box.
  const ffd::Lattice old = Impl::makeFfd(n.counts, n.settings, n.rest, n.control, Eigen::Affine3d::Identity());
  const Eigen::Index total = static_cast<Eigen::Index>(counts.prod());
  Eigen::MatrixX3d params(total, 3), oldParams(total, 3);
  for (Eigen::Index f = 0; f < total; ++f) {
    const Eigen::Vector3i g(static_cast<int>(f % counts.x()), static_cast<int>((f / counts.x()) % counts.y()),
                            static_cast<int>(f / (static_cast<Eigen::Index>(counts.x()) * counts.y())));
    for (int a = 0; a < 3; ++a) {
      const ffd::AxisSpline& ax = axes[static_cast<std::size_t>(a)];
      const double t = ax.greville()[g[a]];
      params(f, a) = t;
      const ffd::AxisSpline& o = old.axis(a);
      oldParams(f, a) = o.domainMin() + (t - ax.domainMin()) * (o.domainMax() - o.domainMin()) / (ax.domainMax() - ax.domainMin());
    }
  }

  // New rest points: a box stays the same box (its affine rest map at the new parameters), a
  // cylinder the same analytic cylinder, a user-shaped lattice samples its old rest map.
  Eigen::MatrixX3d rest(total, 3);
  const bool cylinder = n.settings.cylinder.has_value() && periodic[1];
  if (cylinder) {
    ffd::CylindricalLatticeOptions o;
    o.counts = counts;
    o.bases = n.settings.basis;
    o.innerRadius = n.settings.cylinder->innerRadius;
    o.outerRadius = n.settings.cylinder->outerRadius;
    o.zMin = n.settings.cylinder->zMin;
    o.zMax = n.settings.cylinder->zMax;
    try {
      rest = ffd::makeCylindricalLattice(o).restPoints();
    } catch (const std::exception& e) {
      fail(WidgetErrorCode::InvalidArgument, who + ": " + e.what());
    }
  } else {
    for (Eigen::Index f = 0; f < total; ++f) {
      const Eigen::Vector3d t = oldParams.row(f).transpose();
      rest.row(f) = (old.restIsAffine() ? Eigen::Vector3d(old.restAffineLinear() * t + old.restAffineOffset())
                                        : old.evaluateRest(t))
                        .transpose();
    }
  }
  const ffd::Lattice fresh = Impl::makeFfd(counts, n.settings, rest, rest, Eigen::Affine3d::Identity());

  // The deformation to keep, as a displacement d(x) = X(p) - Xbar(p) of rest-space points x =
  // Xbar(p), sampled where the new lattice's rest map puts its grid parameters; the new control
  // displacements interpolate these samples (tensor-product collocation at the Greville
  // abscissae). Exactly zero for an undeformed lattice; exact for an affine deformation (every
  // basis reproduces affine maps) and when the old displacement lies in the new lattice's space
  // (a Bernstein axis raised from n to n' > n points: degree elevation). An axis that loses
  // points samples the old displacement instead of interpolating it: detail the coarser lattice
  // cannot hold would make the interpolant overshoot (a random 30-point cubic B-spline
  // displacement interpolated by 5 points: control displacements 2.4x the old ones).
  Eigen::MatrixX3d at = oldParams;  // parameters of the samples in the old lattice
  if (!old.restIsAffine() || cylinder) {
    Eigen::MatrixX3d samples(total, 3);
    for (Eigen::Index f = 0; f < total; ++f) samples.row(f) = fresh.evaluateRest(params.row(f).transpose()).transpose();
    ffd::EmbedOptions eo;
    eo.parallel = false;
    const ffd::Embedding e = ffd::embed(old, samples, eo);
    if (e.failedCount() > 0)
      fail(WidgetErrorCode::InvalidArgument, "cannot change " + who + " to " + countsString(counts) + ": " +
                                                 std::to_string(e.failedCount()) + " new grid points could not be located in the old lattice");
    at = e.parameters();
  }
  Eigen::MatrixX3d displacement(total, 3);
  for (Eigen::Index f = 0; f < total; ++f) {
    const Eigen::Vector3d p = at.row(f).transpose();
    displacement.row(f) = (old.evaluate(p) - old.evaluateRest(p)).transpose();
  }
  if (!displacement.isZero(0.0)) {
    std::array<Eigen::MatrixXd, 3> colloc;
    for (int a = 0; a < 3; ++a) {
      const auto s = static_cast<std::size_t>(a);
      const bool sample = counts[a] < n.counts[a];
      colloc[s] = sample ? Eigen::MatrixXd::Identity(counts[a], counts[a]) : collocation(axes[s], axes[s].greville());
    }
    displacement = solveTensor(colloc, counts, displacement);
  }
  const Eigen::MatrixX3d control = rest + displacement;
  if (!finite(control))
    fail(WidgetErrorCode::InvalidArgument, "cannot change " + who + " to " + countsString(counts) + ": the resampled points are not finite");

  // Child lattices keep their world frame (the deformation they add stays where it was).
  std::vector<std::pair<WidgetId, Eigen::Affine3d>> childWorld;
  for (WidgetId child : n.children) childWorld.emplace_back(child, m.latticeFrame(m.nodes[child.value]));

  // Commit: nothing below throws.
  Impl::Node& w = m.nodes[lattice.value];
  w.counts = counts;
  w.rest = rest;
  w.control = control;
  for (std::size_t c = 0; c < cellIds.size(); ++c) {
    Impl::Node& cell = m.nodes[cellIds[c].value];
    cell.spec = std::move(specs[c]);
    cell.indices = std::move(indices[c]);
    cell.restCellPoints.resize(static_cast<Eigen::Index>(cell.indices.size()), 3);
    for (std::size_t r = 0; r < cell.indices.size(); ++r)
      cell.restCellPoints.row(static_cast<Eigen::Index>(r)) = rest.row(cell.indices[r]);
    cell.restFrame = widgets::cellRestFrame(cell.spec, counts, cell.restCellPoints);
  }
  for (const auto& [child, world] : childWorld) {
    Impl::Node& ch = m.nodes[child.value];
    const Binding& b = *m.bindings[ch.parentBinding.value];
    const Impl::Node& cell = m.nodes[b.from.value];
    ch.frame = (m.latticeFrame(w) * m.maskedCellFrame(cell, b.mask)).inverse() * world;
  }
  m.touch();
  m.markStructure();  // its cells hold other points
  m.markWidget(lattice);
  m.markControl(lattice);
  m.markRest(lattice);
  for (WidgetId cell : m.nodes[lattice.value].cells) m.markWidget(cell);
}

ffd::Lattice WidgetModel::ffdLattice(WidgetId lattice) const {
  const Impl::Node& n = impl_->node(lattice, WidgetType::Lattice);
  return Impl::makeFfd(n.counts, n.settings, n.rest, n.control, impl_->latticeFrame(n));
}

void WidgetModel::setLatticeFrame(WidgetId lattice, const Eigen::Affine3d& frame) {
  Impl& m = *impl_;
  m.requireNoGesture("setting a lattice frame");
  Impl::Node& n = m.node(lattice, WidgetType::Lattice);
  if (n.parentBinding.valid())
    fail(WidgetErrorCode::InvalidArgument, "lattice '" + m.label(lattice) + " follows cell '" +
                                               m.label(m.bindings[n.parentBinding.value]->from) + ": unbind it to set its frame");
  if (!finite(frame.matrix()) || std::abs(frame.linear().determinant()) < 1e-300)
    fail(WidgetErrorCode::InvalidArgument, "lattice frame must be finite and invertible");
  n.frame = frame;
  m.touch();
  m.markRest(lattice);
}

void WidgetModel::setSiblingPosition(WidgetId lattice, std::size_t position) {
  Impl& m = *impl_;
  const Impl::Node& n = m.node(lattice, WidgetType::Lattice);
  std::vector<WidgetId>& list = n.parentBinding.valid()
                                    ? m.nodes[m.nodes[m.bindings[n.parentBinding.value]->from.value].lattice.value].children
                                    : m.roots;
  if (position >= list.size())
    fail(WidgetErrorCode::InvalidArgument, "sibling position " + std::to_string(position) + " outside [0, " +
                                               std::to_string(list.size() - 1) + "]");
  list.erase(std::find(list.begin(), list.end(), lattice));
  list.insert(list.begin() + static_cast<std::ptrdiff_t>(position), lattice);
  m.touch();
  m.markStructure();
}

void WidgetModel::setControlPoints(WidgetId lattice, const Eigen::Ref<const Eigen::MatrixX3d>& points) {
  Impl& m = *impl_;
  m.requireNoGesture("setting control points");
  Impl::Node& n = m.node(lattice, WidgetType::Lattice);
  if (points.rows() != n.control.rows() || !finite(points))
    fail(WidgetErrorCode::InvalidArgument, "control points must be " + std::to_string(n.control.rows()) +
                                               " x 3 finite values, got " + std::to_string(points.rows()) + " x 3");
  n.control = points;
  m.touch();
  m.markControl(lattice);
}

void WidgetModel::resetLattice(WidgetId lattice) {
  Impl& m = *impl_;
  m.requireNoGesture("resetting a lattice");
  Impl::Node& n = m.node(lattice, WidgetType::Lattice);
  n.control = n.rest;
  m.touch();
  m.markControl(lattice);
  for (WidgetId c : n.cells)
    for (WidgetId a : m.nodes[c.value].affines) {
      m.nodes[a.value].variation = 0.0;
      m.markWidget(a);
    }
}

// ---- queries ----------------------------------------------------------------------------------
bool WidgetModel::contains(WidgetId id) const {
  return id.valid() && id.value < impl_->nodes.size() && impl_->nodes[id.value].alive;
}
WidgetType WidgetModel::type(WidgetId id) const { return impl_->node(id).type; }
const std::string& WidgetModel::name(WidgetId id) const { return impl_->node(id).name; }

WidgetId WidgetModel::find(std::string_view name) const {
  auto it = impl_->names.find(name);
  if (it != impl_->names.end()) return it->second;
  std::string known;
  std::size_t count = 0;
  for (const auto& [n, id] : impl_->names) {
    if (count++ == 12) {
      known += ", ...";
      break;
    }
    known += (known.empty() ? "" : ", ") + n;
  }
  fail(WidgetErrorCode::UnknownWidget, "unknown widget name '" + std::string(name) + "' (known: " + (known.empty() ? "none" : known) + ")");
}

std::vector<WidgetId> WidgetModel::widgets() const {
  std::vector<WidgetId> out;
  for (const auto& n : impl_->nodes)
    if (n.alive) out.push_back(n.id);
  return out;
}
std::vector<WidgetId> WidgetModel::widgets(WidgetType type) const {
  std::vector<WidgetId> out;
  for (const auto& n : impl_->nodes)
    if (n.alive && n.type == type) out.push_back(n.id);
  return out;
}
std::vector<BindingId> WidgetModel::bindings() const {
  std::vector<BindingId> out;
  for (const auto& b : impl_->bindings)
    if (b) out.push_back(b->id);
  return out;
}
std::vector<BindingId> WidgetModel::bindingsOf(WidgetId id) const { return impl_->node(id).bindings; }
const Binding& WidgetModel::binding(BindingId id) const { return impl_->binding(id); }
std::uint64_t WidgetModel::revision() const { return impl_->revision; }
std::uint64_t WidgetModel::instance() const { return impl_->instance; }
std::uint64_t WidgetModel::structureRevision() const { return impl_->structureRevision; }
std::uint64_t WidgetModel::controlRevision(WidgetId lattice) const {
  return impl_->node(lattice, WidgetType::Lattice).controlRevision;
}
std::uint64_t WidgetModel::frameRevision(WidgetId lattice) const {
  return impl_->frameRevision(impl_->node(lattice, WidgetType::Lattice));
}
std::uint64_t WidgetModel::widgetRevision(WidgetId id) const { return impl_->node(id).ownRevision; }
std::uint64_t WidgetModel::bindingRevision(BindingId binding) const {
  impl_->binding(binding);
  return impl_->bindingRevision(binding);
}

WidgetChanges WidgetModel::changesSince(std::uint64_t since) const {
  const Impl& m = *impl_;
  WidgetChanges changes;
  changes.since = since;
  changes.revision = m.revision;
  changes.structure = m.structureRevision > since;
  for (const Impl::Node& n : m.nodes) {
    if (!n.alive) continue;
    if (n.ownRevision > since) changes.widgets.push_back(n.id);
    if (n.type != WidgetType::Lattice) continue;
    if (n.controlRevision > since) changes.controlPoints.push_back(n.id);
    if (m.frameRevision(n) > since) changes.frames.push_back(n.id);
  }
  for (const auto& b : m.bindings)
    if (b && m.bindingRevision(b->id) > since) changes.bindings.push_back(b->id);
  return changes;
}

Eigen::Vector3i WidgetModel::counts(WidgetId lattice) const { return impl_->node(lattice, WidgetType::Lattice).counts; }
const Eigen::MatrixX3d& WidgetModel::controlPoints(WidgetId lattice) const { return impl_->node(lattice, WidgetType::Lattice).control; }
const Eigen::MatrixX3d& WidgetModel::restPoints(WidgetId lattice) const { return impl_->node(lattice, WidgetType::Lattice).rest; }
Eigen::MatrixX3d WidgetModel::worldControlPoints(WidgetId lattice) const {
  const auto& n = impl_->node(lattice, WidgetType::Lattice);
  const Eigen::Affine3d f = impl_->latticeFrame(n);
  return (n.control * f.linear().transpose()).rowwise() + f.translation().transpose();
}
Eigen::MatrixX3d WidgetModel::worldRestPoints(WidgetId lattice) const {
  const auto& n = impl_->node(lattice, WidgetType::Lattice);
  const Eigen::Affine3d f = impl_->latticeFrame(n);
  return (n.rest * f.linear().transpose()).rowwise() + f.translation().transpose();
}
Eigen::Affine3d WidgetModel::latticeFrame(WidgetId lattice) const {
  return impl_->latticeFrame(impl_->node(lattice, WidgetType::Lattice));
}
const LatticeSettings& WidgetModel::latticeSettings(WidgetId lattice) const {
  return impl_->node(lattice, WidgetType::Lattice).settings;
}
std::optional<WidgetId> WidgetModel::parentCell(WidgetId lattice) const {
  const auto& n = impl_->node(lattice, WidgetType::Lattice);
  if (!n.parentBinding.valid()) return std::nullopt;
  return impl_->bindings[n.parentBinding.value]->from;
}
std::optional<WidgetId> WidgetModel::parentLattice(WidgetId lattice) const {
  auto cell = parentCell(lattice);
  if (!cell) return std::nullopt;
  return impl_->nodes[cell->value].lattice;
}
std::vector<WidgetId> WidgetModel::children(WidgetId lattice) const { return impl_->node(lattice, WidgetType::Lattice).children; }
std::vector<WidgetId> WidgetModel::roots() const { return impl_->roots; }
std::vector<WidgetId> WidgetModel::pipelineOrder() const {
  std::vector<WidgetId> out;
  for (WidgetId root : impl_->roots) {
    const std::vector<WidgetId> tree = pipelineOrder(root);
    out.insert(out.end(), tree.begin(), tree.end());
  }
  return out;
}

std::vector<WidgetId> WidgetModel::pipelineOrder(WidgetId root) const {
  impl_->node(root, WidgetType::Lattice);
  std::vector<WidgetId> out;
  std::vector<WidgetId> stack{root};
  while (!stack.empty()) {
    const WidgetId id = stack.back();
    stack.pop_back();
    out.push_back(id);
    const auto& ch = impl_->nodes[id.value].children;
    stack.insert(stack.end(), ch.rbegin(), ch.rend());
  }
  return out;
}
std::vector<WidgetId> WidgetModel::cellsOf(WidgetId lattice) const { return impl_->node(lattice, WidgetType::Lattice).cells; }

WidgetId WidgetModel::latticeOf(WidgetId id) const {
  const auto& n = impl_->node(id);
  if (n.type == WidgetType::Lattice) return id;
  if (n.type == WidgetType::Cell) return n.lattice;
  if (!n.attachment.valid()) return WidgetId{};
  return impl_->nodes[impl_->bindings[n.attachment.value]->from.value].lattice;
}
const CellSpec& WidgetModel::cellSpec(WidgetId cell) const { return impl_->node(cell, WidgetType::Cell).spec; }
const std::vector<Eigen::Index>& WidgetModel::cellIndices(WidgetId cell) const { return impl_->node(cell, WidgetType::Cell).indices; }
Eigen::MatrixX3d WidgetModel::cellWorldPoints(WidgetId cell) const {
  const auto& c = impl_->node(cell, WidgetType::Cell);
  const Eigen::Affine3d f = impl_->latticeFrame(impl_->nodes[c.lattice.value]);
  return (impl_->cellPoints(c) * f.linear().transpose()).rowwise() + f.translation().transpose();
}
Eigen::Isometry3d WidgetModel::cellRestFrame(WidgetId cell) const { return impl_->node(cell, WidgetType::Cell).restFrame; }
CellAffine WidgetModel::cellAffine(WidgetId cell) const { return impl_->fit(impl_->node(cell, WidgetType::Cell)); }
WidgetFrame WidgetModel::cellFrame(WidgetId cell) const {
  const auto& c = impl_->node(cell, WidgetType::Cell);
  return rigidPart(impl_->latticeFrame(impl_->nodes[c.lattice.value]) * impl_->maskedCellFrame(c, AffineMask::trs()));
}
std::vector<WidgetId> WidgetModel::affinesOf(WidgetId cell) const { return impl_->node(cell, WidgetType::Cell).affines; }

AffineKind WidgetModel::affineKind(WidgetId affine) const { return impl_->node(affine, WidgetType::Affine).kind; }
std::optional<WidgetId> WidgetModel::attachedCell(WidgetId affine) const {
  const auto& n = impl_->node(affine, WidgetType::Affine);
  if (!n.attachment.valid()) return std::nullopt;
  return impl_->bindings[n.attachment.value]->from;
}
const Eigen::Affine3d& WidgetModel::placement(WidgetId affine) const { return impl_->node(affine, WidgetType::Affine).placement; }
double WidgetModel::variation(WidgetId affine) const { return impl_->node(affine, WidgetType::Affine).variation; }
const Glyph& WidgetModel::glyph(WidgetId affine) const { return impl_->node(affine, WidgetType::Affine).glyph; }
WidgetFrame WidgetModel::affineFrame(WidgetId affine) const {
  const auto& n = impl_->node(affine, WidgetType::Affine);
  WidgetFrame f = rigidPart(impl_->affineFull(n));
  f.size *= n.glyph.size;
  return f;
}

Eigen::Affine3d WidgetModel::placementBase(WidgetId affine) const {
  const auto& n = impl_->node(affine, WidgetType::Affine);
  if (!n.attachment.valid()) return Eigen::Affine3d::Identity();
  const Binding& b = *impl_->bindings[n.attachment.value];
  const auto& cell = impl_->nodes[b.from.value];
  return impl_->latticeFrame(impl_->nodes[cell.lattice.value]) * impl_->maskedCellFrame(cell, b.mask);
}

// ---- gestures -----------------------------------------------------------------------------------
void WidgetModel::beginGesture(WidgetId id) { impl_->begin(id); }

void WidgetModel::updateGesture(double variationDelta) {
  Impl& m = *impl_;
  if (!m.gesture) fail(WidgetErrorCode::GestureState, "updateGesture without beginGesture");
  if (m.nodes[m.gesture->target.value].type != WidgetType::Affine)
    fail(WidgetErrorCode::GestureState, "a variation drives affine widgets; '" + m.label(m.gesture->target) +
                                            " takes a world motion");
  if (!std::isfinite(variationDelta)) fail(WidgetErrorCode::InvalidArgument, "variation delta must be finite");
  m.run(variationDelta, Eigen::Affine3d::Identity());
}

void WidgetModel::updateGesture(const Eigen::Affine3d& worldMotion) {
  Impl& m = *impl_;
  if (!m.gesture) fail(WidgetErrorCode::GestureState, "updateGesture without beginGesture");
  if (m.nodes[m.gesture->target.value].type == WidgetType::Affine)
    fail(WidgetErrorCode::GestureState, "affine widget '" + m.label(m.gesture->target) + " takes a variation delta");
  if (!finite(worldMotion.matrix()) || std::abs(worldMotion.linear().determinant()) < 1e-300)
    fail(WidgetErrorCode::InvalidArgument, "world motion must be finite and invertible");
  m.run(0.0, worldMotion);
}

void WidgetModel::endGesture() {
  if (!impl_->gesture) fail(WidgetErrorCode::GestureState, "endGesture without beginGesture");
  impl_->gesture.reset();  // the points are where the last update put them: nothing changes
}

void WidgetModel::cancelGesture() {
  Impl& m = *impl_;
  if (!m.gesture) fail(WidgetErrorCode::GestureState, "cancelGesture without beginGesture");
  m.resetToStart();
  m.touch();
  m.markGesture();
  m.gesture.reset();
}

bool WidgetModel::gestureActive() const { return impl_->gesture.has_value(); }
std::optional<WidgetId> WidgetModel::gestureWidget() const {
  if (!impl_->gesture) return std::nullopt;
  return impl_->gesture->target;
}
std::vector<WidgetId> WidgetModel::gestureVisitOrder() const {
  std::vector<WidgetId> out;
  if (impl_->gesture)
    for (const auto& s : impl_->gesture->steps) out.push_back(s.node);
  return out;
}

// ---- rays ---------------------------------------------------------------------------------------
std::optional<PickResult> WidgetModel::pick(const Ray& ray, const PickOptions& options) const {
  const Impl& m = *impl_;
  const double tol = options.tolerance;
  const Eigen::Vector3d dir = ray.direction.normalized();
  std::optional<PickResult> best;
  int bestRank = 0;
  auto offer = [&](WidgetId id, double t, int rank) {
    // Nearest wins; within the tolerance an affine glyph beats a cell, a cell beats a lattice.
    if (!best || t < best->t - tol || (t <= best->t + tol && rank < bestRank) || (t < best->t && rank == bestRank)) {
      best = PickResult{id, t, ray.origin + t * dir};
      bestRank = rank;
    }
  };
  auto quad = [&](WidgetId id, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d, int rank) {
    if (auto t = intersectTriangle(ray, a, b, c)) offer(id, *t, rank);
    if (auto t = intersectTriangle(ray, a, c, d)) offer(id, *t, rank);
  };
  auto sphere = [&](WidgetId id, const Eigen::Vector3d& p, double radius, int rank) {
    auto h = closestRaySegment(ray, p, p);
    if (h && h->distance <= radius) offer(id, h->t, rank);
  };
  for (const auto& n : m.nodes) {
    if (!n.alive) continue;
    if (n.type == WidgetType::Affine && options.affines) {
      const WidgetFrame f = affineFrame(n.id);
      const Eigen::Vector3d o = f.frame.translation();
      const Eigen::Matrix3d r = f.frame.linear();
      switch (n.kind) {
        case AffineKind::Translate: {
          auto h = closestRaySegment(ray, o, o + GlyphShape::arrowLength * f.size * r.col(0));
          if (h && h->distance <= tol + GlyphShape::pickThickness * f.size) offer(n.id, h->t, 0);
          break;
        }
        case AffineKind::Rotate: {
          if (auto t = intersectPlane(ray, o, r.col(2))) {
            const double rad = (ray.origin + *t * dir - o).norm();
            if (std::abs(rad - GlyphShape::ringRadius * f.size) <= tol + GlyphShape::pickThickness * f.size)
              offer(n.id, *t, 0);
          }
          break;
        }
        case AffineKind::Scale: {
          const double half = GlyphShape::cubeHalfWidth * f.size + tol;
          const Eigen::Vector3d lo = r.transpose() * (ray.origin - o);
          const Eigen::Vector3d ld = r.transpose() * dir;
          double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
          bool hit = true;
          for (int a = 0; a < 3 && hit; ++a) {
            if (std::abs(ld[a]) < 1e-15) {
              hit = std::abs(lo[a]) <= half;
            } else {
              double ta = (-half - lo[a]) / ld[a], tb = (half - lo[a]) / ld[a];
              if (ta > tb) std::swap(ta, tb);
              t0 = std::max(t0, ta);
              t1 = std::min(t1, tb);
              hit = t0 <= t1;
            }
          }
          if (hit) offer(n.id, t0, 0);
          break;
        }
      }
    } else if (n.type == WidgetType::Cell && options.cells) {
      const Eigen::MatrixX3d p = cellWorldPoints(n.id);
      auto row = [&](Eigen::Index i) -> Eigen::Vector3d { return p.row(i).transpose(); };
      switch (n.spec.kind) {
        case CellKind::Edge: {
          auto h = closestRaySegment(ray, row(0), row(1));
          if (h && h->distance <= tol) offer(n.id, h->t, 1);
          break;
        }
        case CellKind::Face: quad(n.id, row(0), row(1), row(2), row(3), 1); break;
        case CellKind::Slab: {
          const Eigen::Vector3i& c = m.nodes[n.lattice.value].counts;
          const int na = c[(n.spec.axis + 1) % 3], nc = c[(n.spec.axis + 2) % 3];
          for (int ic = 0; ic + 1 < nc; ++ic)
            for (int ia = 0; ia + 1 < na; ++ia)
              quad(n.id, row(ic * na + ia), row(ic * na + ia + 1), row((ic + 1) * na + ia + 1), row((ic + 1) * na + ia), 1);
          break;
        }
        case CellKind::Box: {
          static constexpr int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
          for (const auto& f : faces) quad(n.id, row(f[0]), row(f[1]), row(f[2]), row(f[3]), 1);
          break;
        }
        case CellKind::Point:
        case CellKind::Custom:
          for (Eigen::Index i = 0; i < p.rows(); ++i) sphere(n.id, row(i), tol, 1);
          break;
      }
    } else if (n.type == WidgetType::Lattice && options.lattices) {
      const Eigen::MatrixX3d p = worldControlPoints(n.id);
      const Eigen::Vector3d lo = p.colwise().minCoeff().transpose().array() - tol;
      const Eigen::Vector3d hi = p.colwise().maxCoeff().transpose().array() + tol;
      double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
      bool hit = true;
      for (int a = 0; a < 3 && hit; ++a) {
        if (std::abs(dir[a]) < 1e-15) {
          hit = ray.origin[a] >= lo[a] && ray.origin[a] <= hi[a];
        } else {
          double ta = (lo[a] - ray.origin[a]) / dir[a], tb = (hi[a] - ray.origin[a]) / dir[a];
          if (ta > tb) std::swap(ta, tb);
          t0 = std::max(t0, ta);
          t1 = std::min(t1, tb);
          hit = t0 <= t1;
        }
      }
      if (hit) offer(n.id, t0, 2);
    }
  }
  return best;
}

void WidgetModel::beginDrag(WidgetId id, const Ray& ray) {
  Impl& m = *impl_;
  const Impl::Node& n = m.node(id);
  if (m.gesture) fail(WidgetErrorCode::GestureState, "a gesture on '" + m.label(m.gesture->target) + " is already active");
  Impl::Drag d;
  const Eigen::Vector3d dir = ray.direction.normalized();
  auto planePoint = [&](const Eigen::Vector3d& o, const Eigen::Vector3d& normal) -> Eigen::Vector3d {
    if (auto t = intersectPlane(ray, o, normal)) return ray.origin + *t * dir;
    // Edge-on: the ray point closest to o, projected into the plane.
    const Eigen::Vector3d p = ray.origin + std::max(0.0, (o - ray.origin).dot(dir)) * dir;
    return p - (p - o).dot(normal) * normal;
  };
  if (n.type == WidgetType::Affine) {
    const WidgetFrame f = affineFrame(id);
    d.frame = f.frame;
    d.origin = f.frame.translation();
    switch (n.kind) {
      case AffineKind::Translate: {
        d.mode = Impl::DragMode::Axis;
        d.axis = f.frame.linear().col(0);
        auto s = closestLineParameter(ray, d.origin, d.axis);
        if (!s) fail(WidgetErrorCode::InvalidArgument, "the ray runs along the translate axis: no drag direction");
        d.s0 = *s;
        break;
      }
      case AffineKind::Rotate: {
        d.mode = Impl::DragMode::Ring;
        d.axis = f.frame.linear().col(2);
        const Eigen::Vector3d v = f.frame.linear().transpose() * (planePoint(d.origin, d.axis) - d.origin);
        d.lastAngle = std::atan2(v.y(), v.x());
        break;
      }
      case AffineKind::Scale: {
        d.mode = Impl::DragMode::Radial;
        d.axis = dir;
        d.grab = planePoint(d.origin, d.axis);
        d.s0 = (d.grab - d.origin).norm();
        if (d.s0 <= 1e-12) fail(WidgetErrorCode::InvalidArgument, "grab the scale glyph off its centre");
        break;
      }
    }
  } else {
    d.mode = Impl::DragMode::Plane;
    d.axis = dir;
    const Eigen::Vector3d anchor = n.type == WidgetType::Cell ? cellFrame(id).frame.translation()
                                                              : Eigen::Vector3d(latticeFrame(id) * Eigen::Vector3d(0.5, 0.5, 0.5));
    auto t = intersectPlane(ray, anchor, dir);
    d.grab = ray.origin + (t ? *t : 0.0) * dir;
    d.origin = d.grab;
  }
  m.begin(id);
  m.gesture->drag = d;
}

void WidgetModel::dragTo(const Ray& ray) {
  Impl& m = *impl_;
  if (!m.gesture || !m.gesture->drag) fail(WidgetErrorCode::GestureState, "dragTo without beginDrag");
  Impl::Drag& d = *m.gesture->drag;
  const Eigen::Vector3d dir = ray.direction.normalized();
  switch (d.mode) {
    case Impl::DragMode::Axis: {
      if (auto s = closestLineParameter(ray, d.origin, d.axis)) d.lastDelta = *s - d.s0;
      updateGesture(d.lastDelta);
      break;
    }
    case Impl::DragMode::Ring: {
      if (auto t = intersectPlane(ray, d.origin, d.axis)) {
        const Eigen::Vector3d v = d.frame.linear().transpose() * (ray.origin + *t * dir - d.origin);
        if (v.head<2>().norm() > 1e-12) {
          const double a = std::atan2(v.y(), v.x());
          d.accumulated += wrapAngle(a - d.lastAngle);  // unwrap: several turns accumulate
          d.lastAngle = a;
        }
      }
      updateGesture(d.accumulated);
      break;
    }
    case Impl::DragMode::Radial: {
      if (auto t = intersectPlane(ray, d.origin, d.axis)) {
        const double r = (ray.origin + *t * dir - d.origin).norm();
        if (r > 1e-12) d.lastDelta = std::log(r / d.s0);
      }
      updateGesture(d.lastDelta);
      break;
    }
    case Impl::DragMode::Plane: {
      if (auto t = intersectPlane(ray, d.grab, d.axis)) {
        d.lastMotion = Eigen::Affine3d::Identity();
        d.lastMotion.translation() = ray.origin + *t * dir - d.grab;
      }
      updateGesture(d.lastMotion);
      break;
    }
  }
}

// ---- scripting ------------------------------------------------------------------------------------
void WidgetModel::applyVariation(WidgetId affine, double delta) {
  impl_->node(affine, WidgetType::Affine);
  if (!std::isfinite(delta)) fail(WidgetErrorCode::InvalidArgument, "variation delta must be finite");
  beginGesture(affine);
  updateGesture(delta);
  endGesture();
}

void WidgetModel::setVariation(WidgetId affine, double value) {
  applyVariation(affine, value - impl_->node(affine, WidgetType::Affine).variation);
}

void WidgetModel::applyMotion(WidgetId id, const Eigen::Affine3d& worldMotion) {
  if (impl_->node(id).type == WidgetType::Affine)
    fail(WidgetErrorCode::InvalidArgument, "affine widget '" + impl_->label(id) + " takes a variation: use applyVariation");
  if (!finite(worldMotion.matrix()) || std::abs(worldMotion.linear().determinant()) < 1e-300)
    fail(WidgetErrorCode::InvalidArgument, "world motion must be finite and invertible");
  beginGesture(id);
  updateGesture(worldMotion);
  endGesture();
}

// ---- state and data -------------------------------------------------------------------------------
WidgetModelState WidgetModel::captureState() const {
  WidgetModelState s;
  for (const auto& n : impl_->nodes) {
    if (!n.alive) continue;
    if (n.type == WidgetType::Lattice) {
      s.controlPoints.emplace_back(n.id, n.control);
      s.latticeFrames.emplace_back(n.id, n.frame);
    } else if (n.type == WidgetType::Affine) {
      s.variations.emplace_back(n.id, n.variation);
    }
  }
  return s;
}

void WidgetModel::restoreState(const WidgetModelState& s) {
  Impl& m = *impl_;
  m.requireNoGesture("restoring a state");
  for (const auto& [id, p] : s.controlPoints) {
    const auto& n = m.node(id, WidgetType::Lattice);
    if (p.rows() != n.control.rows())
      fail(WidgetErrorCode::InvalidArgument, "state holds " + std::to_string(p.rows()) + " points for lattice '" +
                                                 m.label(id) + ", expected " + std::to_string(n.control.rows()));
  }
  for (const auto& [id, f] : s.latticeFrames) m.node(id, WidgetType::Lattice);
  for (const auto& [id, v] : s.variations) m.node(id, WidgetType::Affine);
  // Only what differs is written and stamped: an undo of a drag re-embeds nothing.
  m.touch();
  for (const auto& [id, p] : s.controlPoints)
    if (Impl::Node& n = m.nodes[id.value]; n.control != p) {
      n.control = p;
      m.markControl(id);
    }
  for (const auto& [id, f] : s.latticeFrames)
    if (Impl::Node& n = m.nodes[id.value]; n.frame.matrix() != f.matrix()) {
      n.frame = f;
      m.markRest(id);
    }
  for (const auto& [id, v] : s.variations)
    if (Impl::Node& n = m.nodes[id.value]; n.variation != v) {
      n.variation = v;
      m.markWidget(id);
    }
}

WidgetModelData WidgetModel::toData() const {
  WidgetModelData d;
  for (const auto& n : impl_->nodes) {
    if (!n.alive) continue;
    switch (n.type) {
      case WidgetType::Lattice:
        d.lattices.push_back(LatticeData{n.id, n.name, n.counts, n.rest, n.control, n.frame, n.settings, n.children});
        break;
      case WidgetType::Cell: d.cells.push_back(CellData{n.id, n.name, n.lattice, n.spec}); break;
      case WidgetType::Affine: d.affines.push_back(AffineData{n.id, n.name, n.kind, n.placement, n.variation, n.glyph}); break;
    }
  }
  for (const auto& b : impl_->bindings)
    if (b) d.bindings.push_back(*b);
  d.rootOrder = impl_->roots;
  return d;
}

WidgetModel WidgetModel::fromData(const WidgetModelData& data) {
  WidgetModel model;
  Impl& m = *model.impl_;
  std::string where;
  auto at = [&](std::string path) { where = std::move(path); };
  auto bad = [&](WidgetErrorCode code, const std::string& message) -> void { throw WidgetError(code, message, where); };
  try {
    auto claim = [&](WidgetId id, WidgetType type, const std::string& name) -> Impl::Node& {
      if (!id.valid() || id.value > 10'000'000) bad(WidgetErrorCode::InvalidArgument, "invalid widget id");
      if (id.value < m.nodes.size() && m.nodes[id.value].alive)
        bad(WidgetErrorCode::InvalidArgument, "duplicate widget id '" + toString(id) + "'");
      if (name.empty()) bad(WidgetErrorCode::InvalidArgument, "widget name must not be empty");
      if (m.names.count(name)) bad(WidgetErrorCode::InvalidArgument, "widget name '" + name + "' is used twice");
      return m.emplace(id, type, name);
    };
    for (std::size_t i = 0; i < data.lattices.size(); ++i) {
      const LatticeData& l = data.lattices[i];
      const std::string base = "/lattices/" + std::to_string(i);
      at(base + "/counts");
      const std::string counts =
          "(" + std::to_string(l.counts.x()) + ", " + std::to_string(l.counts.y()) + ", " + std::to_string(l.counts.z()) + ")";
      if ((l.counts.array() < 2).any())
        bad(WidgetErrorCode::InvalidArgument, "lattice needs >= 2 points per axis, got " + counts);
      if (static_cast<double>(l.counts.x()) * l.counts.y() * l.counts.z() > 1e8)
        bad(WidgetErrorCode::InvalidArgument, "lattice has too many control points (at most 1e8): " + counts);
      const Eigen::Index n = static_cast<Eigen::Index>(l.counts.prod());
      at(base + "/rest");
      if (l.restPoints.rows() != n || !finite(l.restPoints))
        bad(WidgetErrorCode::InvalidArgument, "expected " + std::to_string(n) + " finite rest points, got " + std::to_string(l.restPoints.rows()));
      at(base + "/points");
      if (l.controlPoints.rows() != n || !finite(l.controlPoints))
        bad(WidgetErrorCode::InvalidArgument, "expected " + std::to_string(n) + " finite control points, got " + std::to_string(l.controlPoints.rows()));
      at(base + "/frame");
      if (!finite(l.frame.matrix()) || std::abs(l.frame.linear().determinant()) < 1e-300)
        bad(WidgetErrorCode::InvalidArgument, "frame must be finite and invertible");
      at(base + "/id");
      Impl::Node& node = claim(l.id, WidgetType::Lattice, l.name);
      node.counts = l.counts;
      node.rest = l.restPoints;
      node.control = l.controlPoints;
      node.frame = l.frame;
      node.settings = l.settings;
    }
    for (std::size_t i = 0; i < data.lattices.size(); ++i) {
      at("/lattices/" + std::to_string(i));
      model.setLatticeSettings(data.lattices[i].id, data.lattices[i].settings);
    }
    for (std::size_t i = 0; i < data.cells.size(); ++i) {
      const CellData& c = data.cells[i];
      const std::string base = "/cells/" + std::to_string(i);
      at(base + "/lattice");
      const Impl::Node& lat = m.node(c.lattice, WidgetType::Lattice);
      at(base);
      std::vector<Eigen::Index> indices = cellPointIndices(lat.counts, c.spec);
      Eigen::MatrixX3d rest(static_cast<Eigen::Index>(indices.size()), 3);
      for (std::size_t r = 0; r < indices.size(); ++r) rest.row(static_cast<Eigen::Index>(r)) = lat.rest.row(indices[r]);
      const Eigen::Isometry3d frame = widgets::cellRestFrame(c.spec, lat.counts, rest);
      at(base + "/id");
      Impl::Node& node = claim(c.id, WidgetType::Cell, c.name);
      node.lattice = c.lattice;
      node.spec = c.spec;
      node.indices = std::move(indices);
      node.restCellPoints = std::move(rest);
      node.restFrame = frame;
      m.nodes[c.lattice.value].cells.push_back(c.id);
    }
    for (std::size_t i = 0; i < data.affines.size(); ++i) {
      const AffineData& a = data.affines[i];
      const std::string base = "/affines/" + std::to_string(i);
      at(base + "/placement");
      if (!finite(a.placement.matrix()) || std::abs(a.placement.linear().determinant()) < 1e-300)
        bad(WidgetErrorCode::InvalidArgument, "placement must be finite and invertible");
      at(base + "/variation");
      if (!std::isfinite(a.variation)) bad(WidgetErrorCode::InvalidArgument, "variation must be finite");
      at(base + "/glyph");
      if (a.glyph.shape.empty() || !(a.glyph.size > 0.0) || !std::isfinite(a.glyph.size) || !finite(a.glyph.partPlacement.matrix()))
        bad(WidgetErrorCode::InvalidArgument, "glyph needs a shape name, a positive size and a finite part placement");
      at(base + "/id");
      Impl::Node& node = claim(a.id, WidgetType::Affine, a.name);
      node.kind = a.kind;
      node.placement = a.placement;
      node.variation = a.variation;
      node.glyph = a.glyph;
    }
    m.roots.clear();
    for (const LatticeData& l : data.lattices) m.roots.push_back(l.id);
    for (std::size_t i = 0; i < data.bindings.size(); ++i) {
      const Binding& b = data.bindings[i];
      const std::string base = "/bindings/" + std::to_string(i);
      at(base + "/id");
      if (!b.id.valid() || b.id.value > 10'000'000) bad(WidgetErrorCode::InvalidArgument, "invalid binding id");
      if (b.id.value < m.bindings.size() && m.bindings[b.id.value])
        bad(WidgetErrorCode::InvalidArgument, "duplicate binding id '" + toString(b.id) + "'");
      at(base + "/from");
      m.node(b.from);
      at(base + "/to");
      m.node(b.to);
      at(base);
      BindingOptions o;
      o.rule = b.rule;
      o.mask = b.mask;
      o.oneWay = b.oneWay;
      Binding nb = m.prepareBinding(b.from, b.to, o);
      if (nb.kind != b.kind || nb.from != b.from || nb.to != b.to)
        bad(WidgetErrorCode::InvalidBinding, "binding kind '" + std::string(bindingKindName(b.kind)) + "' from '" + toString(b.from) +
                                                 "' to '" + toString(b.to) + "' does not match the widgets (expected '" +
                                                 std::string(bindingKindName(nb.kind)) + "' from '" + toString(nb.from) + "' to '" +
                                                 toString(nb.to) + "')");
      m.insertBinding(nb, b.id);
    }
    // Sibling order: the data's lists must be permutations of the hierarchy the bindings built.
    auto sameSet = [](std::vector<WidgetId> a, std::vector<WidgetId> b) {
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      return a == b;
    };
    at("/rootOrder");
    if (!sameSet(data.rootOrder, m.roots))
      bad(WidgetErrorCode::InvalidArgument, "root order must list exactly the lattices without a parent cell");
    m.roots = data.rootOrder;
    for (std::size_t i = 0; i < data.lattices.size(); ++i) {
      at("/lattices/" + std::to_string(i) + "/children");
      Impl::Node& node = m.nodes[data.lattices[i].id.value];
      if (!sameSet(data.lattices[i].children, node.children))
        bad(WidgetErrorCode::InvalidArgument, "children must list exactly the lattices bound to this lattice's cells");
      node.children = data.lattices[i].children;
    }
  } catch (const WidgetError& e) {
    if (!e.where().empty()) throw;
    throw WidgetError(e.code(), e.message(), where);
  }
  m.touch();
  return model;
}

}  // namespace ffdkit::widgets
