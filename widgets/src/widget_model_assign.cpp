// WidgetModel::assignData: the model takes other data in place (an undo or redo of a structural
// edit), keeping its instance and revision history and stamping only what differs, so that its
// consumers (the deformer, the view, the outliner) update only the widgets concerned.
#include "widget_model_impl.h"

namespace ffdkit::widgets {
namespace {

bool sameMatrix(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) { return a.rows() == b.rows() && a == b; }

// (Templates: WidgetModel::Impl::Node is private to the model.)
// A widget's own data (what WidgetModel::widgetRevision covers).
template <class Node>
bool sameOwnData(const Node& a, const Node& b) {
  switch (a.type) {
    case WidgetType::Lattice: return a.name == b.name && sameLatticeSettings(a.settings, b.settings);
    case WidgetType::Cell: return a.name == b.name && a.lattice == b.lattice && a.spec == b.spec && a.indices == b.indices;
    case WidgetType::Affine:
      return a.name == b.name && a.kind == b.kind && a.placement.matrix() == b.placement.matrix() &&
             a.variation == b.variation && a.glyph == b.glyph && a.attachment == b.attachment;
  }
  return false;
}

// A lattice's own rest lattice in the world (what WidgetModel::frameRevision covers, the parent's
// part aside): frame or placement, counts, rest points, bases and outside policy, parent binding.
template <class Node>
bool sameRest(const Node& a, const Node& b) {
  return a.counts == b.counts && sameMatrix(a.rest, b.rest) && a.frame.matrix() == b.frame.matrix() &&
         sameLatticeSettings(a.settings, b.settings) && a.parentBinding == b.parentBinding;
}

// The tree shape around a widget (WidgetChanges::structure).
template <class Node>
bool sameLinks(const Node& a, const Node& b) {
  return a.bindings == b.bindings && a.children == b.children && a.cells == b.cells && a.affines == b.affines &&
         a.lattice == b.lattice && a.indices == b.indices;
}

}  // namespace

void WidgetModel::assignData(const WidgetModelData& data) {
  Impl& was = *impl_;
  was.requireNoGesture("assigning data");
  WidgetModel next = fromData(data);  // validates everything; throws with this model unchanged
  Impl& now = *next.impl_;
  now.instance = was.instance;
  now.revision = was.revision + 1;
  now.structureRevision = was.structureRevision;
  const std::uint64_t r = now.revision;
  bool structure = was.roots != now.roots;
  const std::size_t nodeCount = std::max(was.nodes.size(), now.nodes.size());
  for (std::size_t i = 0; i < nodeCount; ++i) {
    const Impl::Node* before = i < was.nodes.size() && was.nodes[i].alive ? &was.nodes[i] : nullptr;
    Impl::Node* after = i < now.nodes.size() && now.nodes[i].alive ? &now.nodes[i] : nullptr;
    if (after == nullptr) {
      structure = structure || before != nullptr;
      continue;
    }
    if (before == nullptr || before->type != after->type) {
      structure = true;
      after->ownRevision = after->controlRevision = after->restRevision = r;
      continue;
    }
    after->ownRevision = sameOwnData(*before, *after) ? before->ownRevision : r;
    // Weights count as control data (setWeights stamps controlRevision): an undo of a weight edit re-deforms.
    const bool sameWeights = before->weights.size() == after->weights.size() && before->weights == after->weights;
    after->controlRevision = sameMatrix(before->control, after->control) && sameWeights ? before->controlRevision : r;
    after->restRevision = after->type != WidgetType::Lattice || sameRest(*before, *after) ? before->restRevision : r;
    structure = structure || !sameLinks(*before, *after);
  }
  const std::size_t bindingCount = std::max(was.bindings.size(), now.bindings.size());
  now.bindingRevisions.assign(bindingCount, 0);
  for (std::size_t i = 0; i < bindingCount; ++i) {
    const std::optional<Binding>* before = i < was.bindings.size() ? &was.bindings[i] : nullptr;
    const std::optional<Binding>* after = i < now.bindings.size() ? &now.bindings[i] : nullptr;
    const bool hadOne = before != nullptr && before->has_value();
    const bool hasOne = after != nullptr && after->has_value();
    if (hadOne != hasOne) structure = true;
    if (!hasOne) continue;
    const BindingId id{static_cast<std::uint32_t>(i)};
    if (hadOne && **before == **after) {
      now.bindingRevisions[i] = was.bindingRevision(id);
    } else {
      now.bindingRevisions[i] = r;
      structure = structure || !hadOne || (*before)->from != (*after)->from || (*before)->to != (*after)->to ||
                  (*before)->kind != (*after)->kind;
    }
  }
  if (structure) now.structureRevision = r;
  impl_ = std::move(next.impl_);
}

}  // namespace ffdkit::widgets
