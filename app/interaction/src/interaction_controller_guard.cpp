// The interaction controller, Keep Volume / Keep Centre and the fold-over tint during drags: after
// each step of any drag (a glyph, a cell, a lattice, a transformer handle, an object point) the
// shape guard corrects the control points the drag leaves free, and the lattices the drag moved
// get their fold-over verdicts (ffd::checkFolding) again.
#include <algorithm>
#include <cmath>
#include <limits>

#include "ffdkit/ffd/direct_manipulation.h"
#include "ffdkit/ffd/fold_check.h"
#include "ffdkit/interaction/interaction_controller.h"

namespace ffdkit::app {

using widgets::WidgetId;
using widgets::WidgetType;

namespace {

std::pair<std::uint64_t, std::uint64_t> revisionsOf(const widgets::WidgetModel& m, WidgetId lattice) {
  return {m.controlRevision(lattice), m.frameRevision(lattice)};
}

}  // namespace

void InteractionController::recordDragStart() {
  const auto& m = scene_.widgets;
  dragRevisions_.clear();
  for (WidgetId lattice : m.widgets(WidgetType::Lattice)) dragRevisions_[lattice] = revisionsOf(m, lattice);
  guardSteps_.clear();
}

std::map<WidgetId, std::vector<bool>> InteractionController::gestureMovedPoints() const {
  const auto& m = scene_.widgets;
  std::map<WidgetId, std::vector<bool>> moved;
  // The widget model's gesture resets and re-applies the points of the cells it visits at every
  // step (WidgetModel::updateGesture); every other point keeps what the guard gave it.
  for (WidgetId id : m.gestureVisitOrder()) {
    if (!m.contains(id) || m.type(id) != WidgetType::Cell) continue;
    const WidgetId lattice = m.latticeOf(id);
    std::vector<bool>& flags = moved[lattice];
    if (flags.empty()) flags.assign(static_cast<std::size_t>(m.controlPoints(lattice).rows()), false);
    for (Eigen::Index i : m.cellIndices(id)) flags[static_cast<std::size_t>(i)] = true;
  }
  return moved;
}

void InteractionController::guardStep() {
  if (objectGrab_) return;  // guardObjectStep, from drag()
  guardSteps_.clear();
  if (guard_.empty()) return;
  const auto& m = scene_.widgets;
  const std::map<WidgetId, std::vector<bool>> moved = gestureMovedPoints();
  for (WidgetId lattice : m.widgets(WidgetType::Lattice)) {
    const auto start = dragRevisions_.find(lattice);
    if (start != dragRevisions_.end() && start->second == revisionsOf(m, lattice)) continue;  // not moved
    // Free: the points this drag does not move (all of them when it moves the lattice's frame).
    std::vector<bool> free(static_cast<std::size_t>(m.controlPoints(lattice).rows()), true);
    if (const auto it = moved.find(lattice); it != moved.end())
      for (std::size_t i = 0; i < free.size(); ++i) free[i] = !it->second[i];
    for (ShapeGuardStep& step : guard_.correct(scene_, lattice, free)) guardSteps_.push_back(std::move(step));
  }
}

void InteractionController::guardObjectStep(const Eigen::Vector3d& target) {
  guardSteps_.clear();
  if (guard_.empty()) return;
  const ObjectGrab& g = *objectGrab_;
  auto& m = scene_.widgets;
  const std::vector<bool> free(static_cast<std::size_t>(g.controlStart.rows()), true);
  const Eigen::Matrix3d localToWorld = g.worldToLocal.inverse();
  // The grabbed point (inside its lattice, the later stages leave it alone) is linear in the
  // control points: x'(P) = grab + F sum_i b_i (P_i - P_start,i).
  auto grabbedAt = [&](const Eigen::MatrixX3d& control) {
    Eigen::Vector3d local = Eigen::Vector3d::Zero();
    for (const ffd::BasisWeight& b : g.basis)
      local += b.weight * (control.row(b.point) - g.controlStart.row(b.point)).transpose();
    return Eigen::Vector3d(g.grab + localToWorld * local);
  };
  const double size = std::max(1.0, localToWorld.norm());
  // Alternating projections: the guard's least-norm correction (volume, centre: every control
  // point free) and the drag's least-norm change that puts the grabbed point back on the pointer.
  // Both are projections onto the constraint sets; they converge to a point of both.
  constexpr int kMaxRounds = 200;
  std::vector<ShapeGuardStep> steps;
  for (int round = 0; round < kMaxRounds; ++round) {
    steps = guard_.correct(scene_, g.lattice, free);
    if (steps.empty() || std::any_of(steps.begin(), steps.end(), [](const ShapeGuardStep& s) { return !s.problem.empty(); }))
      break;
    const Eigen::MatrixX3d control = m.controlPoints(g.lattice);
    const Eigen::Vector3d miss = target - grabbedAt(control);
    if (miss.norm() <= 1e-13 * size) break;
    m.setControlPoints(g.lattice, control + g.weights * (g.worldToLocal * miss).transpose());
    if (round + 1 == kMaxRounds) {
      steps = guard_.correct(scene_, g.lattice, free);  // the shape's constraints last: they hold exactly
      for (ShapeGuardStep& s : steps)
        if (s.problem.empty())
          s.problem = "the grabbed point is " + std::to_string((target - grabbedAt(m.controlPoints(g.lattice))).norm()) +
                      " off the pointer (its constraint and the kept shape's pull apart)";
    }
  }
  guardSteps_ = std::move(steps);
}

void InteractionController::watchMovedLattices() {
  const auto& m = scene_.widgets;
  for (WidgetId lattice : m.widgets(WidgetType::Lattice)) {
    const auto start = dragRevisions_.find(lattice);
    if (start != dragRevisions_.end() && start->second == revisionsOf(m, lattice)) continue;
    // A lattice new to the watch gets its verdicts at the next updateFoldTints.
    foldWatch_.try_emplace(lattice, std::numeric_limits<std::uint64_t>::max(), std::numeric_limits<std::uint64_t>::max());
  }
}

void InteractionController::updateFoldTints() {
  const auto& m = scene_.widgets;
  std::erase_if(foldWatch_, [&](const auto& entry) { return !m.contains(entry.first) || m.type(entry.first) != WidgetType::Lattice; });
  std::erase_if(foldTints_, [&](const FoldTint& tint) { return !foldWatch_.contains(tint.lattice); });
  std::erase_if(certified_, [&](const CertifiedLattice& c) { return !foldWatch_.contains(c.lattice); });
  for (auto& watched : foldWatch_) {
    // Named copies, not a structured binding: the lambdas below capture the lattice, and clang
    // before 16 (the sanitizer stages' compiler) cannot capture a structured binding.
    const WidgetId lattice = watched.first;
    auto& known = watched.second;
    const auto now = revisionsOf(m, lattice);
    if (known == now) continue;  // unchanged: its verdicts stand
    known = now;
    std::erase_if(certified_, [&](const CertifiedLattice& c) { return c.lattice == lattice; });
    const auto old = std::find_if(foldTints_.begin(), foldTints_.end(), [&](const FoldTint& f) { return f.lattice == lattice; });
    ffd::FoldCheckResult result;
    try {
      result = ffd::checkFolding(m.ffdLattice(lattice));
    } catch (const ffd::LatticeError&) {
      // A lattice the check cannot bound (an axis of degree over 10): no tint. The tint is a hint;
      // its failure must not fail the edit, drag or undo that changed the lattice.
      if (old != foldTints_.end()) foldTints_.erase(old);
      continue;
    }
    if (result.certifiedPositive()) {
      if (old != foldTints_.end()) foldTints_.erase(old);
      certified_.push_back({lattice, now.first, now.second});
      continue;
    }
    FoldTint tint{lattice, result.cellCounts, result.cells};
    if (old != foldTints_.end()) *old = std::move(tint);
    else foldTints_.push_back(std::move(tint));
  }
}

}  // namespace ffdkit::app
