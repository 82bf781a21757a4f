// Uses ffdkit::ffd, ::widgets, ::geometry and ::scenes from an installed package, and checks
// results against values it computes itself. Usage: consumer <widget file>. Exit 0 on success.
#include <cmath>
#include <cstdio>
#include <numbers>

#include "ffdkit/ffd/deformer.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"
#include "ffdkit/geometry/gauss_legendre.h"
#include "ffdkit/scenes/widget_file.h"
#include "ffdkit/widgets/widget_model.h"

using namespace ffdkit;

static int failures = 0;
static void check(bool ok, const char* what) {
  std::printf("%s: %s\n", ok ? "ok" : "FAILED", what);
  failures += ok ? 0 : 1;
}

int main(int argc, char** argv) {
  // ffd: a trilinear box; raising its top face by 0.5 scales z by 1.5.
  ffd::BoxLatticeOptions options;
  options.counts = Eigen::Vector3i(2, 2, 2);
  options.bases = {ffd::AxisBasis::bernstein(), ffd::AxisBasis::bernstein(), ffd::AxisBasis::bernstein()};
  ffd::Lattice lattice = ffd::makeBoxLattice(options);
  Eigen::MatrixX3d control = lattice.controlPoints();
  for (Eigen::Index p = 4; p < 8; ++p) control(p, 2) += 0.5;
  lattice.setControlPoints(control);
  Eigen::MatrixX3d points(2, 3);
  points << 0.2, 0.3, 0.4, 0.9, 0.1, 1.0;
  ffd::Deformer deformer(ffd::embed(lattice, points));
  const Eigen::MatrixX3d& out = deformer.deform(lattice, points);
  check(std::abs(out(0, 2) - 0.6) < 1e-14 && std::abs(out(1, 2) - 1.5) < 1e-14, "ffd deforms");

  // widgets: a translate widget on the top face moves its four points.
  widgets::WidgetModel model;
  const widgets::WidgetId box = model.addLattice("box", Eigen::Vector3i(2, 2, 2));
  const widgets::WidgetId top = model.addCell(box, widgets::CellSpec::face(0, 0, 1, 2), "top");
  const widgets::WidgetId push = model.addAffine(top, widgets::AffineKind::Translate, "push");
  model.applyVariation(push, 0.25);
  const double moved = (model.controlPoints(box) - model.restPoints(box)).rowwise().norm().sum();
  check(std::abs(moved - 4 * 0.25) < 1e-12, "widgets drive a gesture");

  // geometry: a 3-point Gauss-Legendre rule integrates x^4 on [0, 1] exactly.
  const auto rule = geometry::gaussLegendreRule(3);
  const double integral = geometry::integrateGaussLegendre(rule, 0.0, 1.0, [](double x) { return std::pow(x, 4); });
  check(std::abs(integral - 0.2) < 1e-14, "geometry integrates");

  // scenes: read a widget file (JSON and VTK linked from the package's dependencies).
  if (argc > 1) {
    const widgets::WidgetModel loaded = scenes::readWidgetFile(argv[1]);
    check(!loaded.widgets().empty() && scenes::widgetFileText(loaded).size() > 100, "scenes reads a widget file");
  }
  return failures == 0 ? 0 : 1;
}
