#include "widget_model_impl.h"

namespace ffdkit::widgets {

// Bindings: paths, loops, preparing, inserting and erasing (Kuriyama 1996, sec. 6.2.2).

std::vector<BindingId> WidgetModel::Impl::path(WidgetId a, WidgetId b) const {
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

bool WidgetModel::Impl::isDescendantOrSelf(WidgetId lattice, WidgetId candidate) const {
  if (lattice == candidate) return true;
  for (WidgetId c : nodes[lattice.value].children)
    if (isDescendantOrSelf(c, candidate)) return true;
  return false;
}

Binding WidgetModel::Impl::prepareBinding(WidgetId a, WidgetId b, const BindingOptions& options) const {
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
      fail(WidgetErrorCode::InvalidBinding,
           std::string("'") + label(a) + " and '" + label(b) + " are already bound by " + toString(e.id));
  }
  checkLoop(out);
  return out;
}

bool WidgetModel::Impl::drives(const Binding& e, WidgetId u) {
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

void WidgetModel::Impl::checkLoop(const Binding& nb) const {
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

void WidgetModel::Impl::checkRoutes(const Binding& nb) const {
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

BindingId WidgetModel::Impl::insertBinding(Binding b, BindingId explicitId) {
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

void WidgetModel::Impl::eraseBinding(BindingId id) {
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

}  // namespace ffdkit::widgets
