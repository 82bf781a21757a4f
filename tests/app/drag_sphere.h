#pragma once
// The scene the drag tests and BM_DragStep share, built through the controller as a user would:
// a sphere in a 4x4x4 cubic B-spline lattice (one cell: every point moves with every control
// point) with a translate widget on an inner point of its top layer.

#include <string>

#include "ffdkit/interaction/interaction_controller.h"

namespace ffdkit::app::testing {

struct DragSphere {
  std::string sphere;
  widgets::WidgetId lattice, widget;
};

/// Adds the sphere (`resolution`: scenes::PrimitiveOptions::resolution), its lattice and the
/// widget; clears the selection.
inline DragSphere addDragSphere(InteractionController& controller, int resolution) {
  DragSphere made;
  scenes::PrimitiveOptions options;
  options.resolution = resolution;
  made.sphere = controller.addPrimitive(options);
  NewLatticeOptions cubic;
  cubic.counts = Eigen::Vector3i::Constant(4);
  cubic.basis = {ffd::AxisBasis::bspline(3), ffd::AxisBasis::bspline(3), ffd::AxisBasis::bspline(3)};
  made.lattice = controller.newLattice(cubic);
  controller.attachLattice(made.lattice, made.sphere);
  made.widget = controller.addAffineAtPoint({made.lattice, 1 + 4 * (1 + 4 * 3)}, widgets::AffineKind::Translate);
  controller.clearSelection();
  return made;
}

}  // namespace ffdkit::app::testing
