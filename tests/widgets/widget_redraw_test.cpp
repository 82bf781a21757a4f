// widgetsToRedraw (widget_redraw.h): what a view redraws for a change set.
#include "ffdkit/widgets/widget_redraw.h"

#include <gtest/gtest.h>

namespace ffdkit::widgets {
namespace {

// Two root lattices; the first carries a point cell with a translate widget and, on its top
// slab, a child lattice; a free scale widget.
struct Model {
  WidgetModel m;
  WidgetId root, other, corner, push, top, child, free;
  Model() {
    root = m.addLattice("root", Eigen::Vector3i(3, 3, 3));
    other = m.addLattice("other", Eigen::Vector3i(2, 2, 2));
    corner = m.addCell(root, CellSpec::point(0, 0, 0), "corner");
    push = m.addAffine(corner, AffineKind::Translate, "push");
    top = m.addCell(root, CellSpec::slab(2, 2), "top");
    child = m.addLattice("child", Eigen::Vector3i(2, 2, 2));
    m.bind(top, child);
    AffineOptions options;
    options.name = "free";
    free = m.addFreeAffine(AffineKind::Scale, options);
  }
};

TEST(WidgetRedraw, MovedPointsRedrawTheLatticeItsCellsTheirWidgetsAndItsChildren) {
  Model s;
  const std::uint64_t before = s.m.revision();
  Eigen::MatrixX3d points = s.m.controlPoints(s.root);
  points(0, 2) -= 0.25;
  s.m.setControlPoints(s.root, points);
  EXPECT_EQ(widgetsToRedraw(s.m, s.m.changesSince(before)),
            (std::vector<WidgetId>{s.root, s.corner, s.push, s.top, s.child}));
}

TEST(WidgetRedraw, OwnDataRedrawsThatWidgetOnlyAndRemovedWidgetsAreNotListed) {
  Model s;
  std::uint64_t before = s.m.revision();
  s.m.rename(s.free, "handle");
  EXPECT_EQ(widgetsToRedraw(s.m, s.m.changesSince(before)), std::vector<WidgetId>{s.free});
  before = s.m.revision();
  s.m.remove(s.corner);  // its widget becomes free where it is
  EXPECT_EQ(widgetsToRedraw(s.m, s.m.changesSince(before)), std::vector<WidgetId>{s.push});
  before = s.m.revision();
  EXPECT_TRUE(widgetsToRedraw(s.m, s.m.changesSince(before)).empty());
}

}  // namespace
}  // namespace ffdkit::widgets
