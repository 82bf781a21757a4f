#include "widget_model_impl.h"

#include <cmath>

namespace ffdkit::widgets {

// ---- state and data -------------------------------------------------------------------------------
WidgetModelState WidgetModel::captureState() const {
  WidgetModelState s;
  for (const auto& n : impl_->nodes) {
    if (!n.alive) continue;
    if (n.type == WidgetType::Lattice) {
      s.controlPoints.emplace_back(n.id, n.control);
      s.weights.emplace_back(n.id, n.weights);
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
  for (const auto& [id, w] : s.weights) {
    const auto& n = m.node(id, WidgetType::Lattice);
    if (w.size() != 0 && (w.size() != n.control.rows() || !(w.array() > 0.0).all() || !w.allFinite()))
      fail(WidgetErrorCode::InvalidArgument, "state holds " + std::to_string(w.size()) + " weights for lattice '" +
                                                 m.label(id) + ", expected " + std::to_string(n.control.rows()) + " finite weights > 0");
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
  for (const auto& [id, w] : s.weights)
    if (Impl::Node& n = m.nodes[id.value]; n.weights.size() != w.size() || n.weights != w) {
      n.weights = w;
      m.markControl(id);
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
        d.lattices.push_back(LatticeData{n.id, n.name, n.counts, n.rest, n.control, n.frame, n.settings, n.children, n.weights});
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
          std::string("(") + std::to_string(l.counts.x()) + ", " + std::to_string(l.counts.y()) + ", " +
          std::to_string(l.counts.z()) + ")";
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
      at(base + "/weights");
      if (l.weights.size() != 0 && l.weights.size() != n)
        bad(WidgetErrorCode::InvalidArgument, "expected " + std::to_string(n) + " weights, got " + std::to_string(l.weights.size()));
      for (Eigen::Index k = 0; k < l.weights.size(); ++k)
        if (!(std::isfinite(l.weights[k]) && l.weights[k] > 0.0)) {
          at(base + "/weights/" + std::to_string(k));
          bad(WidgetErrorCode::InvalidArgument, "weight " + std::to_string(k) + " must be finite and > 0, got " + std::to_string(l.weights[k]));
        }
      at(base + "/frame");
      if (!detail::finiteAndInvertible(l.frame))
        bad(WidgetErrorCode::InvalidArgument, "frame must be finite and invertible");
      at(base + "/id");
      Impl::Node& node = claim(l.id, WidgetType::Lattice, l.name);
      node.counts = l.counts;
      node.rest = l.restPoints;
      node.control = l.controlPoints;
      node.weights = (l.weights.array() == 1.0).all() ? Eigen::VectorXd() : l.weights;
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
      Eigen::MatrixX3d rest = detail::gatherRows(lat.rest, indices);
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
      if (!detail::finiteAndInvertible(a.placement))
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
