#include "ffdkit/widgets/widget_redraw.h"

#include <set>

namespace ffdkit::widgets {

std::vector<WidgetId> widgetsToRedraw(const WidgetModel& model, const WidgetChanges& changes) {
  std::set<WidgetId> ids;
  auto add = [&](WidgetId id) {
    if (model.contains(id)) ids.insert(id);
  };
  for (WidgetId id : changes.widgets) add(id);
  for (const std::vector<WidgetId>* lattices : {&changes.controlPoints, &changes.frames})
    for (WidgetId lattice : *lattices) {
      if (!model.contains(lattice)) continue;
      ids.insert(lattice);
      for (WidgetId cell : model.cellsOf(lattice)) {
        ids.insert(cell);
        for (WidgetId affine : model.affinesOf(cell)) ids.insert(affine);
      }
    }
  for (BindingId id : changes.bindings) {
    const Binding& binding = model.binding(id);
    add(binding.from);
    add(binding.to);
  }
  return {ids.begin(), ids.end()};
}

}  // namespace ffdkit::widgets
