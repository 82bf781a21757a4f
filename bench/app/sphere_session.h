// The setup the application benchmarks share (bench/app): a check that aborts the run when a
// benchmark's work did not do what it should, and the scene they measure on.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

#include "ffdkit/interaction/interaction_controller.h"

namespace ffdkit::bench {

/// Aborts the benchmark run with `what` (prefixed by `program`) unless `ok`.
inline void require(bool ok, const char* program, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "%s: %s\n", program, what);
    std::abort();
  }
}

/// The widgets addSphereInCubicLattice made.
struct SphereWidget {
  widgets::WidgetId lattice;
  widgets::WidgetId widget;
};

/// Through `controller`'s edits: a sphere of about resolution^2 / 2 vertices in a 4x4x4 cubic
/// B-spline lattice, a translate widget on an inner point of the top layer; nothing selected.
inline SphereWidget addSphereInCubicLattice(app::InteractionController& controller, int resolution) {
  scenes::PrimitiveOptions sphere;
  sphere.resolution = resolution;
  const std::string name = controller.addPrimitive(sphere);
  app::NewLatticeOptions cubic;
  cubic.counts = Eigen::Vector3i::Constant(4);
  cubic.basis = {ffd::AxisBasis::bspline(3), ffd::AxisBasis::bspline(3), ffd::AxisBasis::bspline(3)};
  SphereWidget out;
  out.lattice = controller.newLattice(cubic);
  controller.attachLattice(out.lattice, name);
  out.widget = controller.addAffineAtPoint({out.lattice, 1 + 4 * (1 + 4 * 3)}, widgets::AffineKind::Translate);
  controller.clearSelection();
  return out;
}

/// A ray down `widget`'s frame z through its arrow at `along` glyph sizes, `shift` glyph sizes
/// sideways (the frame's y): what a press, a drag step or a hover over the arrow casts.
inline widgets::Ray rayAlongArrow(const widgets::WidgetModel& model, widgets::WidgetId widget, double along,
                                  double shift = 0.0) {
  const widgets::WidgetFrame f = model.affineFrame(widget);
  widgets::Ray r;
  r.origin = f.frame.translation() + f.size * (along * f.frame.linear().col(0) + shift * f.frame.linear().col(1)) +
             5.0 * f.frame.linear().col(2);
  r.direction = -f.frame.linear().col(2);
  return r;
}

/// The pick tolerance the benchmarks press and hover with: 5 % of `widget`'s glyph size.
inline double pickTolerance(const widgets::WidgetModel& model, widgets::WidgetId widget) {
  return 0.05 * model.affineFrame(widget).size;
}

}  // namespace ffdkit::bench
