#include "widget_model_impl.h"

namespace ffdkit::widgets {

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

Eigen::VectorXd WidgetModel::weights(WidgetId lattice) const {
  const Impl::Node& n = impl_->node(lattice, WidgetType::Lattice);
  return n.weights.size() > 0 ? n.weights : Eigen::VectorXd::Ones(n.control.rows());
}

bool WidgetModel::isRational(WidgetId lattice) const { return impl_->node(lattice, WidgetType::Lattice).weights.size() > 0; }
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

}  // namespace ffdkit::widgets
