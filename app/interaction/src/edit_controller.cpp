#include "ffdkit/interaction/edit_controller.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "ffdkit/ffd/fold_check.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/document_delta.h"

namespace ffdkit::app {

using widgets::WidgetId;
using widgets::WidgetType;

namespace {

/// The motion `m` (made about `pivot`) made about `centre` instead: the same linear part, and
/// the pivot's own displacement (Blender's individual origins).
Eigen::Affine3d aboutCentre(const Eigen::Affine3d& m, const Eigen::Vector3d& pivot, const Eigen::Vector3d& centre) {
  Eigen::Affine3d out = Eigen::Affine3d::Identity();
  out.linear() = m.linear();
  out.translation() = centre - m.linear() * centre + (m * pivot - pivot);
  return out;
}

const char* verb(TransformMode mode) {
  return mode == TransformMode::Move ? "Move" : mode == TransformMode::Rotate ? "Turn" : "Size";
}

}  // namespace

EditController::EditController(scenes::Scene& scene, scenes::SceneDeformer& deformer, scenes::CommandStack& commands,
                               InteractionController& widgets)
    : scene_(scene), deformer_(deformer), commands_(commands), widgets_(widgets) {}

// ---- edit mode ---------------------------------------------------------------------------

void EditController::enter(WidgetId lattice) {
  if (!scene_.widgets.contains(lattice) || scene_.widgets.type(lattice) != WidgetType::Lattice)
    throw std::invalid_argument("select a lattice to edit its points");
  cancel();
  selection_.emplace(lattice, scene_.widgets.counts(lattice));
  hoveredHandle_.reset();
  notify();
}

void EditController::exit() {
  if (!selection_) return;
  cancel();
  selection_.reset();
  hoveredHandle_.reset();
  notify();
}

bool EditController::editing() const {
  if (!selection_) return false;
  const auto& m = scene_.widgets;
  const WidgetId id = selection_->lattice();
  return m.contains(id) && m.type(id) == WidgetType::Lattice && m.counts(id) == selection_->counts();
}

WidgetId EditController::lattice() const {
  if (!selection_) throw std::logic_error("not in a lattice's edit mode");
  return selection_->lattice();
}

const PointSelection& EditController::points() const {
  if (!selection_) throw std::logic_error("not in a lattice's edit mode");
  return *selection_;
}

Eigen::MatrixX3d EditController::worldPoints() const { return scene_.widgets.worldControlPoints(lattice()); }

std::optional<Eigen::Index> EditController::pointUnder(const widgets::Ray& ray, double tolerance) const {
  if (!editing()) return std::nullopt;
  const Eigen::Vector3d dir = ray.direction.normalized();
  const Eigen::MatrixX3d points = worldPoints();
  std::optional<Eigen::Index> best;
  double bestT = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d v = points.row(i).transpose() - ray.origin;
    const double t = v.dot(dir);
    if (t < 0.0 || t >= bestT || (v - t * dir).norm() > tolerance) continue;
    bestT = t;
    best = i;
  }
  return best;
}

bool EditController::click(const widgets::Ray& ray, double tolerance, SelectMode mode) {
  if (!editing()) return false;
  const auto hit = pointUnder(ray, tolerance);
  if (!hit) return false;
  selection_->pick(*hit, mode);
  notify();
  return true;
}

void EditController::pickMany(const std::vector<Eigen::Index>& indices, SelectMode mode) {
  if (!editing()) throw std::logic_error("not in a lattice's edit mode");
  selection_->pickMany(indices, mode);
  notify();
}

void EditController::selectAll() {
  if (!editing()) return;
  selection_->selectAll();
  notify();
}

void EditController::selectNone() {
  if (!editing()) return;
  selection_->selectNone();
  notify();
}

void EditController::invert() {
  if (!editing()) return;
  selection_->invert();
  notify();
}

void EditController::selectLinked(int axis, bool plane) {
  if (!editing()) return;
  selection_->selectLinked(axis, plane);
  notify();
}

// ---- transforms --------------------------------------------------------------------------

void EditController::setMirror(std::optional<int> axis) {
  if (axis && (*axis < 0 || *axis > 2)) throw std::invalid_argument("mirror axis must be i, j or k (0, 1, 2)");
  mirror_ = axis;
  notify();
}

void EditController::setPivot(PivotChoice pivot) {
  pivot_ = pivot;
  notify();
}

std::vector<WidgetId> EditController::movableWidgets() const {
  const auto& m = scene_.widgets;
  const std::vector<WidgetId>& selected = widgets_.selection();
  // An item on a selected lattice (or below one in the tree) moves with that lattice's frame:
  // moving it again would move it twice.
  auto carried = [&](WidgetId id) {
    std::optional<WidgetId> lattice;
    if (m.type(id) == WidgetType::Lattice) lattice = m.parentLattice(id);
    else if (m.type(id) == WidgetType::Cell || m.attachedCell(id)) lattice = m.latticeOf(id);
    for (; lattice; lattice = m.parentLattice(*lattice))
      if (std::find(selected.begin(), selected.end(), *lattice) != selected.end()) return true;
    return false;
  };
  std::vector<WidgetId> out;
  for (WidgetId id : selected) {
    if (!m.contains(id)) continue;
    if (m.type(id) == WidgetType::Lattice && m.parentCell(id)) continue;
    if (carried(id)) continue;
    out.push_back(id);
  }
  return out;
}

std::optional<std::string> EditController::refusal() const {
  if (editing()) {
    if (selection_->empty()) return std::string("select points first (click, Shift+click, drag a box, A for all)");
    return std::nullopt;
  }
  const auto& m = scene_.widgets;
  for (WidgetId id : widgets_.selection())
    if (m.contains(id) && m.type(id) == WidgetType::Lattice && m.parentCell(id))
      return "'" + m.name(id) + "' is a child lattice: its frame follows its parent cell";
  if (movableWidgets().size() < 2)
    return std::string("select two or more widgets (Ctrl+click), or press Tab to edit a lattice's points");
  return std::nullopt;
}

std::vector<EditController::Target> EditController::targets() const {
  std::vector<Target> out;
  if (refusal()) return out;
  const auto& m = scene_.widgets;
  // Points of one lattice are one target (cells that share points move them once).
  std::map<WidgetId, std::size_t> pointTarget;
  auto addPoints = [&](WidgetId lattice, const std::vector<Eigen::Index>& indices,
                       const std::optional<Eigen::Vector3d>& centre) {
    auto [it, added] = pointTarget.emplace(lattice, out.size());
    if (added) {
      Target t;
      t.kind = Target::Kind::Points;
      t.id = lattice;
      t.startPoints = m.controlPoints(lattice);
      out.push_back(std::move(t));
    }
    Target& t = out[it->second];
    const Eigen::MatrixX3d world = m.worldControlPoints(lattice);
    for (Eigen::Index i : indices) {
      if (std::find(t.indices.begin(), t.indices.end(), i) != t.indices.end()) continue;
      t.indices.push_back(i);
      t.centres.push_back(centre.value_or(Eigen::Vector3d(world.row(i).transpose())));
    }
  };
  if (editing()) {
    addPoints(selection_->lattice(), selection_->indices(), std::nullopt);
    const Eigen::MatrixX3d world = worldPoints();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (Eigen::Index i : selection_->indices()) sum += world.row(i).transpose();
    out.front().centre = sum / static_cast<double>(selection_->count());
    if (selection_->active()) out.front().activeCentre = world.row(*selection_->active()).transpose();
    if (mirror_) {
      // Each selected point's image across the mid-plane normal to index axis `a` (unless it is
      // selected itself or is its own image).
      Target& t = out.front();
      const int a = *mirror_;
      const double mid = m.restPoints(t.id).col(a).mean();
      t.reflection.linear()(a, a) = -1.0;
      t.reflection.translation()(a) = 2.0 * mid;
      for (std::size_t n = 0; n < t.indices.size(); ++n) {
        Eigen::Vector3i g = selection_->gridIndex(t.indices[n]);
        g(a) = selection_->counts()(a) - 1 - g(a);
        const Eigen::Index image = selection_->flatIndex(g);
        if (image != t.indices[n] && !selection_->contains(image)) t.images.emplace_back(image, n);
      }
    }
    return out;
  }
  for (WidgetId id : movableWidgets()) {
    switch (m.type(id)) {
      case WidgetType::Affine: {
        Target t;
        t.kind = Target::Kind::Placement;
        t.id = id;
        t.start = m.placement(id);
        t.base = m.placementBase(id);
        t.centre = m.affineFrame(id).frame.translation();
        out.push_back(std::move(t));
        break;
      }
      case WidgetType::Lattice: {
        Target t;
        t.kind = Target::Kind::Frame;
        t.id = id;
        t.start = m.latticeFrame(id);
        t.centre = m.worldRestPoints(id).colwise().mean().transpose();
        out.push_back(std::move(t));
        break;
      }
      case WidgetType::Cell: {
        const Eigen::Vector3d centre = m.cellWorldPoints(id).colwise().mean().transpose();
        addPoints(m.latticeOf(id), m.cellIndices(id), centre);
        out[pointTarget[m.latticeOf(id)]].centre = centre;
        break;
      }
    }
  }
  return out;
}

std::optional<Eigen::Vector3d> EditController::pivotPoint() const {
  if (live_) return live_->pivot;
  const std::vector<Target> all = targets();
  if (all.empty()) return std::nullopt;
  if (editing()) {
    const Target& t = all.front();
    return pivot_ == PivotChoice::Active && t.activeCentre ? *t.activeCentre : t.centre;
  }
  if (pivot_ == PivotChoice::Active) {
    // The last widget picked: the end of the widget selection.
    const WidgetId last = movableWidgets().back();
    const auto& m = scene_.widgets;
    switch (m.type(last)) {
      case WidgetType::Affine: return m.affineFrame(last).frame.translation();
      case WidgetType::Lattice: return m.worldRestPoints(last).colwise().mean().transpose();
      case WidgetType::Cell: return m.cellWorldPoints(last).colwise().mean().transpose();
    }
  }
  // Median: the mean of the items' centres (each cell and widget counts once).
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  const auto& m = scene_.widgets;
  for (WidgetId id : movableWidgets()) {
    switch (m.type(id)) {
      case WidgetType::Affine: sum += m.affineFrame(id).frame.translation(); break;
      case WidgetType::Lattice: sum += m.worldRestPoints(id).colwise().mean().transpose(); break;
      case WidgetType::Cell: sum += m.cellWorldPoints(id).colwise().mean().transpose(); break;
    }
    ++n;
  }
  return sum / n;
}

std::optional<Transformer> EditController::transformer() const {
  if (live_ && live_->handle) return live_->transformer;
  const auto pivot = pivotPoint();
  if (!pivot) return std::nullopt;
  Transformer t;
  t.frame.translation() = *pivot;
  t.uniformSize = false;
  // Sized to the lattice in the edit mode, to the spread of the items otherwise.
  const auto& m = scene_.widgets;
  Eigen::AlignedBox3d box;
  if (editing()) {
    const Eigen::MatrixX3d rest = m.worldRestPoints(lattice());
    for (Eigen::Index i = 0; i < rest.rows(); ++i) box.extend(Eigen::Vector3d(rest.row(i).transpose()));
  } else {
    for (const Target& target : targets()) {
      box.extend(target.centre);
      for (const auto& c : target.centres) box.extend(c);
    }
  }
  t.size = std::max(0.25 * box.diagonal().norm(), 0.25);
  return t;
}

bool EditController::hover(const widgets::Ray& ray, double tolerance) {
  if (live_) return false;
  std::optional<TransformerHandle> handle;
  if (const auto t = transformer(); t && !pointUnder(ray, tolerance)) handle = pickTransformer(*t, ray, tolerance);
  if (handle == hoveredHandle_) return false;
  hoveredHandle_ = handle;
  notify();
  return true;
}

void EditController::startLive(std::vector<Target> all, const std::string& verbText) {
  Live live;
  live.before = scene_.widgets.captureState();
  live.verb = verbText;
  std::size_t points = 0;
  for (const Target& t : all) points += t.indices.size();
  if (editing()) {
    live.what = std::to_string(points) + (points == 1 ? " point of " : " points of ") + scene_.widgets.name(lattice());
    if (!all.empty() && !all.front().images.empty()) live.what += " (mirrored)";
  } else {
    live.what = std::to_string(movableWidgets().size()) + " widgets";
  }
  live.pivot = *pivotPoint();
  live.targets = std::move(all);
  if (editing() && soft_.enabled)
    for (Target& t : live.targets)
      if (t.kind == Target::Kind::Points) softenTarget(t);
  live_ = std::move(live);
}

void EditController::softenTarget(Target& t) const {
  t.soft.clear();
  if (!soft_.enabled) return;
  const auto& m = scene_.widgets;
  const Eigen::MatrixX3d world = (t.startPoints * m.latticeFrame(t.id).linear().transpose()).rowwise() +
                                 m.latticeFrame(t.id).translation().transpose();
  const Eigen::VectorXd weights = softSelectionWeights(soft_, world, m.counts(t.id), t.indices);
  std::vector<bool> fixed(static_cast<std::size_t>(world.rows()), false);
  for (Eigen::Index i : t.indices) fixed[static_cast<std::size_t>(i)] = true;
  for (const auto& image : t.images) fixed[static_cast<std::size_t>(image.first)] = true;
  for (Eigen::Index i = 0; i < world.rows(); ++i)
    if (!fixed[static_cast<std::size_t>(i)] && weights(i) > 0.0) t.soft.emplace_back(i, weights(i));
}

void EditController::setSoftSelection(const SoftSelection& soft) {
  if (!(soft.radius > 0.0) || !std::isfinite(soft.radius))
    throw std::invalid_argument("the soft selection's radius must be positive, got " + std::to_string(soft.radius));
  soft_ = soft;
  if (live_ && editing()) {
    for (Target& t : live_->targets)
      if (t.kind == Target::Kind::Points) softenTarget(t);
    apply(live_->motion);
    return;
  }
  notify();
}

void EditController::scaleSoftRadius(double factor) {
  if (!(factor > 0.0)) throw std::invalid_argument("the soft selection's radius factor must be positive");
  SoftSelection soft = soft_;
  soft.radius *= factor;
  setSoftSelection(soft);
}

Eigen::VectorXd EditController::softWeights() const {
  if (!editing()) return {};
  const auto& m = scene_.widgets;
  if (live_)
    for (const Target& t : live_->targets)
      if (t.kind == Target::Kind::Points && t.id == lattice()) {
        Eigen::VectorXd w = Eigen::VectorXd::Zero(t.startPoints.rows());
        for (Eigen::Index i : t.indices) w(i) = 1.0;
        for (const auto& [i, weight] : t.soft) w(i) = weight;
        return w;
      }
  return softSelectionWeights(soft_, m.worldControlPoints(lattice()), m.counts(lattice()), selection_->indices());
}

bool EditController::pressHandle(const widgets::Ray& ray, double tolerance) {
  if (live_) return false;
  const auto t = transformer();
  if (!t) return false;
  const auto handle = pickTransformer(*t, ray, tolerance);
  if (!handle) return false;
  const int group = static_cast<int>(*handle) / 3;
  startLive(targets(), group == 0 ? "Move" : group == 1 ? "Turn" : "Size");
  live_->handle.emplace(*t, *handle, ray);
  live_->transformer = *t;
  hoveredHandle_ = handle;
  notify();
  return true;
}

void EditController::beginModal(TransformMode mode, const widgets::Ray& ray, const Eigen::Vector3d& viewDirection) {
  if (live_) cancel();
  if (const auto why = refusal()) throw std::invalid_argument(*why);
  if (editing() && pivot_ == PivotChoice::Individual && mode != TransformMode::Move)
    throw std::invalid_argument(std::string(mode == TransformMode::Rotate ? "turning" : "sizing") +
                                " points about their individual origins leaves them in place: choose the median "
                                "or the active point as pivot");
  startLive(targets(), verb(mode));
  modal_.emplace(mode, live_->pivot, ray, viewDirection);
  notify();
}

void EditController::update(const widgets::Ray& ray, bool snap) {
  if (!live_) return;
  if (modal_) {
    apply(modal_->motion(ray, snap));
    return;
  }
  if (live_->typed) return;  // the typed value rules
  TransformerDrag& drag = *live_->handle;
  Eigen::Affine3d motion = drag.motion(ray);
  if (snap) {
    const int group = static_cast<int>(drag.handle()) / 3;
    const SnapSteps steps;
    const double step = group == 0 ? steps.distance : group == 1 ? steps.degrees * std::numbers::pi / 180.0 : steps.factor;
    motion = drag.motionFor(std::max(group == 2 ? step : -std::numeric_limits<double>::infinity(),
                                     std::round(drag.value() / step) * step));
  }
  apply(motion);
}

bool EditController::setDragValue(double value) {
  if (!live_ || !live_->handle || !std::isfinite(value)) return false;
  if (static_cast<int>(live_->handle->handle()) / 3 == 2 && !(value > 0.0)) return false;
  live_->typed = value;
  apply(live_->handle->motionFor(value));
  return true;
}

std::optional<TransformerHandle> EditController::draggedHandle() const {
  if (!live_ || !live_->handle) return std::nullopt;
  return live_->handle->handle();
}

void EditController::apply(const Eigen::Affine3d& motion) {
  auto& m = scene_.widgets;
  const Eigen::Vector3d pivot = live_->pivot;
  const bool individual = pivot_ == PivotChoice::Individual;
  std::optional<WidgetId> active;
  for (const Target& t : live_->targets) {
    switch (t.kind) {
      case Target::Kind::Points: {
        const Eigen::Affine3d frame = m.latticeFrame(t.id);
        const Eigen::Affine3d toLocal = frame.inverse();
        Eigen::MatrixX3d points = t.startPoints;
        auto ownMotion = [&](std::size_t n) { return individual ? aboutCentre(motion, pivot, t.centres[n]) : motion; };
        for (std::size_t n = 0; n < t.indices.size(); ++n) {
          const Eigen::Index i = t.indices[n];
          const Eigen::Vector3d world = frame * Eigen::Vector3d(t.startPoints.row(i).transpose());
          points.row(i) = (toLocal * (ownMotion(n) * world)).transpose();
        }
        // Mirror images: moved by S M S in the lattice's local coordinates (S the reflection
        // there), M the world motion brought into them.
        for (const auto& [image, n] : t.images) {
          const Eigen::Affine3d local = toLocal * ownMotion(n) * frame;
          const Eigen::Vector3d start = t.startPoints.row(image).transpose();
          points.row(image) = (t.reflection * (local * (t.reflection * start))).transpose();
        }
        // Soft selection: the unselected points within the radius, each by its part of the motion.
        for (const auto& [i, weight] : t.soft) {
          const Eigen::Vector3d world = frame * Eigen::Vector3d(t.startPoints.row(i).transpose());
          points.row(i) = (toLocal * (partialMotion(motion, pivot, weight) * world)).transpose();
        }
        m.setControlPoints(t.id, points);
        active = t.id;
        break;
      }
      case Target::Kind::Frame:
        m.setLatticeFrame(t.id, (individual ? aboutCentre(motion, pivot, t.centre) : motion) * t.start);
        break;
      case Target::Kind::Placement: {
        // F' = M * F with F = base * placement (WidgetModel::placementBase).
        const Eigen::Affine3d own = individual ? aboutCentre(motion, pivot, t.centre) : motion;
        m.setPlacement(t.id, t.base.inverse() * own * t.base * t.start);
        break;
      }
    }
  }
  live_->motion = motion;
  guardStep();
  deformer_.beginGesture(live_->targets.size() == 1 ? active : std::nullopt);  // this step's active lattice
  notify();
}

void EditController::guardStep() {
  guardSteps_.clear();
  if (shapeGuard().empty()) return;
  for (const Target& t : live_->targets) {
    if (t.kind != Target::Kind::Points) continue;
    // Free: the points this transform does not move (selected, mirrored or softly moved ones).
    std::vector<bool> free(static_cast<std::size_t>(t.startPoints.rows()), true);
    for (Eigen::Index i : t.indices) free[static_cast<std::size_t>(i)] = false;
    for (const auto& image : t.images) free[static_cast<std::size_t>(image.first)] = false;
    for (const auto& soft : t.soft) free[static_cast<std::size_t>(soft.first)] = false;
    // apply() set every point from the transform's start: the free ones are where they were
    // before it, and the correction is the least-norm change from there (no drift over the steps).
    for (ShapeGuardStep& step : shapeGuard().correct(scene_, t.id, free)) guardSteps_.push_back(std::move(step));
  }
}

void EditController::updateFoldTints() {
  const auto& m = scene_.widgets;
  std::vector<widgets::WidgetId> lattices;
  if (editing()) lattices.push_back(lattice());
  if (live_)
    for (const Target& t : live_->targets)
      if (t.kind != Target::Kind::Placement && std::find(lattices.begin(), lattices.end(), t.id) == lattices.end())
        lattices.push_back(t.id);
  std::vector<FoldTint> tints;
  std::vector<CertifiedLattice> certified;
  std::map<widgets::WidgetId, std::pair<std::uint64_t, std::uint64_t>> revisions;
  for (widgets::WidgetId id : lattices) {
    if (!m.contains(id) || m.type(id) != WidgetType::Lattice) continue;
    const std::pair<std::uint64_t, std::uint64_t> now{m.controlRevision(id), m.frameRevision(id)};
    revisions[id] = now;
    const auto known = foldRevisions_.find(id);
    const auto old = std::find_if(foldTints_.begin(), foldTints_.end(), [&](const FoldTint& f) { return f.lattice == id; });
    if (known != foldRevisions_.end() && known->second == now) {  // unchanged: the verdicts stand
      if (old != foldTints_.end()) tints.push_back(*old);
      for (const CertifiedLattice& c : certified_)
        if (c.lattice == id) certified.push_back(c);
      continue;
    }
    ffd::FoldCheckResult result;
    try {
      result = ffd::checkFolding(m.ffdLattice(id));
    } catch (const ffd::LatticeError&) {
      continue;  // a lattice the check cannot bound (an axis of degree over 10): no tint, not a failed edit
    }
    if (result.certifiedPositive()) {
      certified.push_back({id, now.first, now.second});
      continue;
    }
    tints.push_back(FoldTint{id, result.cellCounts, result.cells});
  }
  foldTints_ = std::move(tints);
  certified_ = std::move(certified);
  foldRevisions_ = std::move(revisions);
}

void EditController::confirm() {
  if (!live_) return;
  Live live = std::move(*live_);
  live_.reset();
  modal_.reset();
  auto& m = scene_.widgets;
  auto delta = std::make_shared<const scenes::StateDelta>(scenes::stateDelta(live.before, m.captureState()));
  // Placements are not part of the model's state: the command holds those that changed.
  struct Placed {
    WidgetId id;
    Eigen::Affine3d before, after;
  };
  auto placed = std::make_shared<std::vector<Placed>>();
  for (const Target& t : live.targets)
    if (t.kind == Target::Kind::Placement && m.placement(t.id).matrix() != t.start.matrix())
      placed->push_back({t.id, t.start, m.placement(t.id)});
  deformer_.endGesture();  // the next evaluation is exact
  if (delta->empty() && placed->empty()) {
    notify();
    return;
  }
  // The animated channels' values when the transform began (before) and ended (after): an undo or
  // redo after a frame change writes the points back as at the edit's frame and carries them to
  // the frame shown (scenes::restoreAtEditValues).
  auto animated = std::make_shared<const scenes::StateDelta>(
      scenes::StateDelta{scenes::animatedPart(scene_, live.before), scenes::animatedState(scene_)});
  const std::uint64_t madeAt = widgets_.animationApplications();
  auto carried = std::make_shared<std::optional<scenes::CarriedStep>>();  // makes an undo's redo exact
  auto restore = [this, delta, placed, animated, madeAt, carried](bool forward) {
    scenes::restoreAtEditValues(scene_, forward ? animated->before : animated->after,
                                widgets_.animationAppliedSince(madeAt), [&] {
                                  scene_.widgets.restoreState(forward ? delta->after : delta->before);
                                  for (const Placed& p : *placed)
                                    scene_.widgets.setPlacement(p.id, forward ? p.after : p.before);
                                }, carried.get());
    widgets_.refresh();
    notify();
  };
  try {
    notify();  // evaluates the result (headless at once; the window at its next frame)
  } catch (...) {
    // A result that cannot be evaluated is taken back, with no step: as a refused edit.
    scene_.widgets.restoreState(live.before);
    for (const Placed& p : *placed) scene_.widgets.setPlacement(p.id, p.before);
    widgets_.refresh();
    throw;
  }
  // The step is pushed once the change holds: a throw above leaves no step whose undo would
  // undo nothing, and keeps the steps that could be redone.
  commands_.push(scenes::Command{live.verb + " " + live.what, [restore] { restore(false); }, [restore] { restore(true); },
                                 "", delta->bytes() + animated->bytes() + placed->size() * sizeof(Placed)});
}

void EditController::cancel() {
  if (!live_) return;
  Live live = std::move(*live_);
  live_.reset();
  modal_.reset();
  deformer_.endGesture();
  scene_.widgets.restoreState(live.before);
  for (const Target& t : live.targets)
    if (t.kind == Target::Kind::Placement) scene_.widgets.setPlacement(t.id, t.start);
  widgets_.refresh();
  notify();
}

std::string EditController::describe() const {
  if (!live_) return "";
  if (modal_) return modal_->describe();
  const TransformerDrag& drag = *live_->handle;
  const int group = static_cast<int>(drag.handle()) / 3;
  const double value = live_->typed.value_or(drag.value());
  char text[96];
  if (group == 0) std::snprintf(text, sizeof text, "%s %.3f", transformerHandleName(drag.handle()), value);
  if (group == 1)
    std::snprintf(text, sizeof text, "%s %.1f°", transformerHandleName(drag.handle()), value * 180.0 / std::numbers::pi);
  if (group == 2) std::snprintf(text, sizeof text, "%s x%.3f", transformerHandleName(drag.handle()), value);
  return text;
}

// ---- make cell ---------------------------------------------------------------------------

CellFromSelection EditController::cellFor(std::optional<widgets::CellKind> kind) const {
  const PointSelection& s = points();
  if (kind) return cellFromSelection(s.counts(), s.indices(), *kind);
  CellFromSelection out;
  out.spec = classifySelection(s.counts(), s.indices());
  if (!out.spec)
    out.why = s.empty() ? "no point is selected"
                        : std::to_string(s.count()) + " points that are no point, edge, face, slab or box";
  return out;
}

WidgetId EditController::makeCell(const widgets::CellSpec& spec) { return widgets_.addCell(lattice(), spec); }

ViewHighlights EditController::highlights(ViewHighlights h) const {
  // The controller's tints (lattices its drags moved) with this object's (the edited lattice and
  // the lattices a transform moves): one per lattice, the same verdicts either way.
  for (const FoldTint& tint : foldTints_)
    if (std::none_of(h.foldTints.begin(), h.foldTints.end(), [&](const FoldTint& f) { return f.lattice == tint.lattice; }))
      h.foldTints.push_back(tint);
  for (const CertifiedLattice& c : certified_)
    if (std::find(h.certified.begin(), h.certified.end(), c) == h.certified.end()) h.certified.push_back(c);
  if (live_ && editing() && soft_.enabled) h.softRadius = SoftRadius{live_->pivot, soft_.radius};
  if (editing() && scene_.widgets.contains(lattice()))
    for (Eigen::Index i : selection_->indices()) h.selectedPoints.push_back({lattice(), i});
  // In the edit mode the points' transformer replaces the lattice's; outside, a group's shows
  // where the controller has none (two or more widgets selected).
  if (const auto t = transformer(); t || editing()) {
    h.transformer = t;
    h.transformerHandle = live_ && live_->handle ? std::optional(live_->handle->handle()) : hoveredHandle_;
    if (!t) h.transformerHandle.reset();
  }
  return h;
}

void EditController::notify() {
  widgets_.evaluateChanges();  // what the step changed, once (at once, or at the window's next frame)
  shapeGuard().prune(scene_);
  updateFoldTints();
  if (onChanged) onChanged();
}

}  // namespace ffdkit::app
