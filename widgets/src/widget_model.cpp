#include "widget_model_impl.h"

#include <cmath>

#include "ffdkit/ffd/cylindrical_lattice.h"
#include "ffdkit/ffd/embedding.h"

namespace ffdkit::widgets {

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
  Eigen::MatrixX3d rest = detail::gatherRows(lat.rest, indices);
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
  if (!detail::finiteAndInvertible(options.placement))
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
  if (!detail::finiteAndInvertible(placement))
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

ffd::Lattice WidgetModel::ffdLattice(WidgetId lattice) const {
  const Impl::Node& n = impl_->node(lattice, WidgetType::Lattice);
  return Impl::makeFfd(n.counts, n.settings, n.rest, n.control, impl_->latticeFrame(n), n.weights);
}

void WidgetModel::setLatticeFrame(WidgetId lattice, const Eigen::Affine3d& frame) {
  Impl& m = *impl_;
  m.requireNoGesture("setting a lattice frame");
  Impl::Node& n = m.node(lattice, WidgetType::Lattice);
  if (n.parentBinding.valid())
    fail(WidgetErrorCode::InvalidArgument, "lattice '" + m.label(lattice) + " follows cell '" +
                                               m.label(m.bindings[n.parentBinding.value]->from) + ": unbind it to set its frame");
  if (!detail::finiteAndInvertible(frame))
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
  Impl::Node& n = m.node(lattice, WidgetType::Lattice);
  if (points.rows() != n.control.rows() || !finite(points))
    fail(WidgetErrorCode::InvalidArgument, "control points must be " + std::to_string(n.control.rows()) +
                                               " x 3 finite values, got " + std::to_string(points.rows()) + " x 3");
  // During a gesture only the points it does not move may change (a correction of the others
  // after each step: the app's Keep Volume / Keep Centre); each step re-applies the gesture's own
  // points from their start, and cancelGesture() restores only those.
  if (m.gesture)
    for (const auto& [id, indices] : m.gesture->affected)
      if (id == lattice)
        for (Eigen::Index i : indices)
          if (points.row(i) != n.control.row(i))
            fail(WidgetErrorCode::GestureState, "setting control point " + std::to_string(i) + " of '" + m.label(lattice) +
                                                    ", which the gesture on " + toString(m.gesture->target) +
                                                    " moves, is not allowed during it");
  n.control = points;
  m.touch();
  m.markControl(lattice);
}

void WidgetModel::resetLattice(WidgetId lattice) {
  Impl& m = *impl_;
  m.requireNoGesture("resetting a lattice");
  Impl::Node& n = m.node(lattice, WidgetType::Lattice);
  n.control = n.rest;
  n.weights.resize(0);
  m.touch();
  m.markControl(lattice);
  for (WidgetId c : n.cells)
    for (WidgetId a : m.nodes[c.value].affines) {
      m.nodes[a.value].variation = 0.0;
      m.markWidget(a);
    }
}

namespace {

// Weights as the model stores them: checked (count, finite, > 0; the message names the first bad
// one), and empty when every weight is 1.
Eigen::VectorXd storedWeights(Eigen::Index count, const Eigen::Ref<const Eigen::VectorXd>& weights) {
  if (weights.size() != count)
    fail(WidgetErrorCode::InvalidArgument, "expected " + std::to_string(count) + " weights, got " + std::to_string(weights.size()));
  for (Eigen::Index i = 0; i < weights.size(); ++i)
    if (!(std::isfinite(weights[i]) && weights[i] > 0.0))
      fail(WidgetErrorCode::InvalidArgument,
           "weight " + std::to_string(i) + " must be finite and > 0, got " + std::to_string(weights[i]));
  if ((weights.array() == 1.0).all()) return {};
  return weights;
}

}  // namespace

void WidgetModel::setWeights(WidgetId lattice, const Eigen::Ref<const Eigen::VectorXd>& weights) {
  Impl& m = *impl_;
  m.requireNoGesture("setting weights");
  Impl::Node& n = m.node(lattice, WidgetType::Lattice);
  Eigen::VectorXd stored = storedWeights(n.control.rows(), weights);
  if (stored.size() == n.weights.size() && stored == n.weights) return;
  n.weights = std::move(stored);
  m.touch();
  m.markControl(lattice);
}

void WidgetModel::setWeight(WidgetId lattice, Eigen::Index point, double weight) {
  const Impl::Node& n = impl_->node(lattice, WidgetType::Lattice);
  if (point < 0 || point >= n.control.rows())
    fail(WidgetErrorCode::InvalidArgument, "point " + std::to_string(point) + " outside [0, " +
                                               std::to_string(n.control.rows()) + ") of lattice '" + impl_->label(lattice));
  Eigen::VectorXd all = weights(lattice);
  all[point] = weight;
  setWeights(lattice, all);
}

}  // namespace ffdkit::widgets
