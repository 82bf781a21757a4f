// What the app tests cast at an affine widget: a ray down its frame z through its arrow, and the
// pick tolerance they press with.
#pragma once

#include "ffdkit/widgets/ray.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::app::test {

/// A ray down `widget`'s frame z through its arrow at `along` glyph sizes (from five glyph sizes
/// above the frame's origin): what a press, a drag step or a hover over the arrow casts.
inline widgets::Ray arrowRay(const widgets::WidgetModel& model, widgets::WidgetId widget, double along) {
  const widgets::WidgetFrame f = model.affineFrame(widget);
  widgets::Ray r;
  r.origin = f.frame.translation() + f.size * along * f.frame.linear().col(0) + 5.0 * f.frame.linear().col(2);
  r.direction = -f.frame.linear().col(2);
  return r;
}

/// The pick tolerance the tests press and hover with: 5 % of `widget`'s glyph size.
inline double arrowTolerance(const widgets::WidgetModel& model, widgets::WidgetId widget) {
  return 0.05 * model.affineFrame(widget).size;
}

}  // namespace ffdkit::app::test
