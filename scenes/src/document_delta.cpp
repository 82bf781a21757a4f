#include "ffdkit/scenes/document_delta.h"

#include <algorithm>
#include <map>

#include "ffdkit/scenes/scene_changes.h"

namespace ffdkit::scenes {
namespace {

using widgets::WidgetId;

std::size_t matrixBytes(const Eigen::MatrixX3d& m) { return sizeof(double) * std::size_t(m.size()); }

std::size_t stateBytes(const widgets::WidgetModelState& s) {
  std::size_t bytes = sizeof(s);
  for (const auto& [id, points] : s.controlPoints) bytes += sizeof(id) + sizeof(points) + matrixBytes(points);
  for (const auto& [id, weights] : s.weights) bytes += sizeof(id) + sizeof(weights) + sizeof(double) * weights.size();
  bytes += s.latticeFrames.size() * sizeof(s.latticeFrames.front());
  bytes += s.variations.size() * sizeof(std::pair<WidgetId, double>);
  return bytes;
}

bool same(const widgets::LatticeData& a, const widgets::LatticeData& b) {
  return a.name == b.name && a.counts == b.counts && a.restPoints.rows() == b.restPoints.rows() &&
         a.restPoints == b.restPoints && a.controlPoints.rows() == b.controlPoints.rows() &&
         a.controlPoints == b.controlPoints && a.weights.size() == b.weights.size() && a.weights == b.weights &&
         a.frame.matrix() == b.frame.matrix() && widgets::sameLatticeSettings(a.settings, b.settings) && a.children == b.children;
}
bool same(const widgets::CellData& a, const widgets::CellData& b) {
  return a.name == b.name && a.lattice == b.lattice && a.spec == b.spec;
}
bool same(const widgets::AffineData& a, const widgets::AffineData& b) {
  return a.name == b.name && a.kind == b.kind && a.placement.matrix() == b.placement.matrix() &&
         a.variation == b.variation && a.glyph == b.glyph;
}
bool same(const widgets::Binding& a, const widgets::Binding& b) { return a == b; }

template <class Record>
void diff(const std::vector<Record>& before, const std::vector<Record>& after, ModelPatch::Changes<Record>& out) {
  std::map<decltype(Record::id), const Record*> old;
  for (const Record& r : before) old[r.id] = &r;
  for (const Record& r : after) {
    auto it = old.find(r.id);
    if (it == old.end()) {
      out.emplace_back(std::nullopt, r);
      continue;
    }
    if (!same(*it->second, r)) out.emplace_back(*it->second, r);
    old.erase(it);
  }
  for (const auto& [id, r] : old) out.emplace_back(*r, std::nullopt);
}

// Swaps the records of `changes` into `records` (id order kept).
template <class Record>
void patch(std::vector<Record>& records, const ModelPatch::Changes<Record>& changes, bool forward) {
  for (const auto& [before, after] : changes) {
    const std::optional<Record>& from = forward ? before : after;
    const std::optional<Record>& to = forward ? after : before;
    const auto id = from ? from->id : to->id;
    std::erase_if(records, [&](const Record& r) { return r.id == id; });
    if (to) records.insert(std::upper_bound(records.begin(), records.end(), *to,
                                            [](const Record& a, const Record& b) { return a.id < b.id; }),
                           *to);
  }
}

std::size_t recordBytes(const widgets::LatticeData& r) {
  return sizeof(r) + r.name.size() + matrixBytes(r.restPoints) + matrixBytes(r.controlPoints) +
         sizeof(double) * static_cast<std::size_t>(r.weights.size()) + r.children.size() * sizeof(WidgetId);
}
std::size_t recordBytes(const widgets::CellData& r) { return sizeof(r) + r.name.size() + r.spec.indices.size() * sizeof(r.spec.indices.front()); }
std::size_t recordBytes(const widgets::AffineData& r) { return sizeof(r) + r.name.size() + r.glyph.shape.size(); }
std::size_t recordBytes(const widgets::Binding& r) { return sizeof(r); }

template <class Record>
std::size_t changesBytes(const ModelPatch::Changes<Record>& changes) {
  std::size_t bytes = 0;
  for (const auto& [before, after] : changes)
    bytes += sizeof(before) + sizeof(after) + (before ? recordBytes(*before) : 0) + (after ? recordBytes(*after) : 0);
  return bytes;
}

std::size_t attachmentsBytes(const std::vector<Attachment>& list) {
  std::size_t bytes = list.size() * sizeof(Attachment);
  for (const Attachment& a : list) bytes += a.objects.size() * sizeof(ObjectId);
  return bytes;
}

}  // namespace

std::size_t StateDelta::bytes() const { return stateBytes(before) + stateBytes(after); }

StateDelta stateDelta(const widgets::WidgetModelState& before, const widgets::WidgetModelState& after) {
  StateDelta d;
  for (std::size_t i = 0; i < std::min(before.controlPoints.size(), after.controlPoints.size()); ++i) {
    const auto& [id, p] = before.controlPoints[i];
    const auto& q = after.controlPoints[i].second;
    if (p.rows() != q.rows() || p != q) {
      d.before.controlPoints.emplace_back(id, p);
      d.after.controlPoints.emplace_back(id, q);
    }
  }
  for (std::size_t i = 0; i < std::min(before.weights.size(), after.weights.size()); ++i) {
    const auto& [id, w] = before.weights[i];
    const auto& x = after.weights[i].second;
    if (w.size() != x.size() || w != x) {
      d.before.weights.emplace_back(id, w);
      d.after.weights.emplace_back(id, x);
    }
  }
  for (std::size_t i = 0; i < std::min(before.latticeFrames.size(), after.latticeFrames.size()); ++i)
    if (before.latticeFrames[i].second.matrix() != after.latticeFrames[i].second.matrix()) {
      d.before.latticeFrames.push_back(before.latticeFrames[i]);
      d.after.latticeFrames.push_back(after.latticeFrames[i]);
    }
  for (std::size_t i = 0; i < std::min(before.variations.size(), after.variations.size()); ++i)
    if (before.variations[i].second != after.variations[i].second) {
      d.before.variations.push_back(before.variations[i]);
      d.after.variations.push_back(after.variations[i]);
    }
  return d;
}

std::size_t ModelPatch::bytes() const {
  std::size_t total = sizeof(*this) + changesBytes(lattices) + changesBytes(cells) + changesBytes(affines) +
                      changesBytes(bindings);
  if (rootOrder) total += (rootOrder->first.size() + rootOrder->second.size()) * sizeof(WidgetId);
  return total;
}

ModelPatch modelPatch(const widgets::WidgetModelData& before, const widgets::WidgetModelData& after) {
  ModelPatch p;
  diff(before.lattices, after.lattices, p.lattices);
  diff(before.cells, after.cells, p.cells);
  diff(before.affines, after.affines, p.affines);
  diff(before.bindings, after.bindings, p.bindings);
  if (before.rootOrder != after.rootOrder) p.rootOrder = std::pair(before.rootOrder, after.rootOrder);
  return p;
}

void applyPatch(widgets::WidgetModel& model, const ModelPatch& p, bool forward) {
  if (p.empty()) return;
  widgets::WidgetModelData data = model.toData();
  patch(data.lattices, p.lattices, forward);
  patch(data.cells, p.cells, forward);
  patch(data.affines, p.affines, forward);
  patch(data.bindings, p.bindings, forward);
  if (p.rootOrder) data.rootOrder = forward ? p.rootOrder->second : p.rootOrder->first;
  // In place: the model stays one instance and stamps only the records that differ.
  model.assignData(data);
}

std::size_t SceneDelta::bytes() const {
  return sizeof(*this) + widgets.bytes() + (attachments ? attachmentsBytes(attachments->first) + attachmentsBytes(attachments->second) : 0);
}

void applySceneDelta(Scene& scene, const SceneDelta& delta, bool forward) {
  applyPatch(scene.widgets, delta.widgets, forward);
  if (delta.attachments) {
    scene.setAttachments(forward ? delta.attachments->second : delta.attachments->first);
  }
}

}  // namespace ffdkit::scenes
