// ffdkit::widgets from an installed package: a translate widget on the top face of a 2x2x2
// lattice moves its four points by the variation and leaves the bottom four where they were.
#include <cmath>

#include "../consumer_check.h"
#include "ffdkit/widgets/widget_model.h"

using namespace ffdkit;

int main() {
  widgets::WidgetModel model;
  const widgets::WidgetId box = model.addLattice("box", Eigen::Vector3i(2, 2, 2));
  const widgets::WidgetId top = model.addCell(box, widgets::CellSpec::face(0, 0, 1, 2), "top");
  const widgets::WidgetId push = model.addAffine(top, widgets::AffineKind::Translate, "push");
  model.applyVariation(push, 0.25);
  const Eigen::VectorXd moved = (model.controlPoints(box) - model.restPoints(box)).rowwise().norm();
  int movedBy025 = 0, still = 0;
  for (Eigen::Index p = 0; p < moved.size(); ++p) {
    if (std::abs(moved(p) - 0.25) < 1e-12) ++movedBy025;
    if (moved(p) < 1e-15) ++still;
  }
  consumer::check(moved.size() == 8 && movedBy025 == 4 && still == 4, "the top face moves by 0.25, the rest stays");
  return consumer::exitCode();
}
