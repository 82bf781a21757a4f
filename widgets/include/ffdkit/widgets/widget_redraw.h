#pragma once

#include <vector>

#include "ffdkit/widgets/widget_changes.h"
#include "ffdkit/widgets/widget_id.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::widgets {

/// The widgets of `model` whose drawing a change set (WidgetModel::changesSince) concerns, in id
/// order: those whose own data changed (added ones included); the lattices whose control points
/// or rest lattice in the world changed, with their cells and the affine widgets attached to
/// those cells (they ride on the points); both ends of the bindings whose mask, rule or direction
/// changed. Widgets removed are not listed (a view drops what the model no longer contains).
/// What a view redraws instead of every widget (STYLE 9: update just what the change touched).
std::vector<WidgetId> widgetsToRedraw(const WidgetModel& model, const WidgetChanges& changes);

}  // namespace ffdkit::widgets
