#include "widget_model_impl.h"

namespace ffdkit::widgets {

// Gesture propagation (Kuriyama 1996, secs. 6.2.1, 6.2.2): breadth-first over the bindings, from
// the gesture start.

WidgetModel::Impl::Step WidgetModel::Impl::makeStep(WidgetId id, int parent, BindingId via, bool forward) const {
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

void WidgetModel::Impl::begin(WidgetId target) {
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

void WidgetModel::Impl::resetToStart() {
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

void WidgetModel::Impl::run(double delta, const Eigen::Affine3d& motion) {
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
  if (!detail::finiteAndInvertible(worldMotion))
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
  if (!detail::finiteAndInvertible(worldMotion))
    fail(WidgetErrorCode::InvalidArgument, "world motion must be finite and invertible");
  beginGesture(id);
  updateGesture(worldMotion);
  endGesture();
}

}  // namespace ffdkit::widgets
