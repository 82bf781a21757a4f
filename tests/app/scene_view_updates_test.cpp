// The view is change-driven (scene_view.h): hover and selection build no geometry and touch no
// point or normal array; a drag step rewrites the points and normals of the objects that moved,
// and only theirs. No GL draw: the renderer has no window.
#include <gtest/gtest.h>

#include <vtkNew.h>
#include <vtkRenderer.h>

#include "ffdkit/app/interaction_controller.h"
#include "ffdkit/app/scene_view.h"

namespace ffdkit::app {
namespace {

struct Session {
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  InteractionController controller{scene, deformer, commands};
  vtkNew<vtkRenderer> renderer;
  SceneView view{renderer};
  widgets::WidgetId lattice, widget;
  std::string moved, still;

  Session() {
    scenes::PrimitiveOptions sphere;
    sphere.resolution = 12;
    moved = controller.addPrimitive(sphere);
    sphere.placement = Eigen::Translation3d(3, 0, 0);
    still = controller.addPrimitive(sphere);
    lattice = controller.newLattice({});
    controller.attachLattice(lattice, moved);
    widget = controller.addAffineAtPoint({lattice, 1 + 3 * (1 + 3 * 2)}, widgets::AffineKind::Translate);
    controller.clearSelection();
    view.setHighlights(controller.highlights());
    view.show(scene, deformer);
    controller.onChanged = [this] {
      view.setHighlights(controller.highlights());
      view.refresh(scene, deformer);
    };
  }
  widgets::Ray ray(double along, double aside = 0.0) const {
    const widgets::WidgetFrame f = scene.widgets.affineFrame(widget);
    widgets::Ray r;
    r.origin = f.frame.translation() + f.size * (along * f.frame.linear().col(0) + aside * f.frame.linear().col(1)) +
               5.0 * f.frame.linear().col(2);
    r.direction = -f.frame.linear().col(2);
    return r;
  }
  double tolerance() const { return 0.05 * scene.widgets.affineFrame(widget).size; }
};

void expectNoGeometryWork(const SceneViewStats& before, const SceneViewStats& after) {
  EXPECT_EQ(after.objectBuilds, before.objectBuilds);
  EXPECT_EQ(after.pointUpdates, before.pointUpdates);
  EXPECT_EQ(after.normalUpdates, before.normalUpdates);
  EXPECT_EQ(after.widgetBuilds, before.widgetBuilds);
}

TEST(SceneViewUpdates, HoverAndSelectionBuildNoGeometry) {
  Session s;
  const SceneViewStats start = s.view.stats();
  EXPECT_EQ(start.objectBuilds, 2);
  EXPECT_EQ(start.widgetBuilds, 1);
  for (int i = 0; i < 5; ++i) {
    EXPECT_TRUE(s.controller.hover(s.ray(0.5), s.tolerance()));
    EXPECT_EQ(s.controller.hovered(), s.widget);
    EXPECT_TRUE(s.controller.hover(s.ray(0.5, 4.0), s.tolerance()));
  }
  s.controller.setSelection({s.lattice});
  s.controller.setPickedPoint(LatticePointRef{s.lattice, 4});
  s.controller.clearSelection();
  expectNoGeometryWork(start, s.view.stats());
}

TEST(SceneViewUpdates, ADragStepUpdatesThePointsOfTheObjectsThatMovedOnly) {
  Session s;
  ASSERT_EQ(s.controller.press(s.ray(0.5), s.tolerance()), InteractionController::PressResult::Widget);
  const SceneViewStats pressed = s.view.stats();
  s.controller.drag(s.ray(0.8));
  const SceneViewStats dragged = s.view.stats();
  EXPECT_EQ(dragged.pointUpdates, pressed.pointUpdates + 1);  // the attached sphere, not the other
  EXPECT_EQ(dragged.normalUpdates, pressed.normalUpdates + 1);
  EXPECT_EQ(dragged.objectBuilds, pressed.objectBuilds);
  EXPECT_EQ(dragged.widgetBuilds, pressed.widgetBuilds + 1);  // the lattice and glyphs moved
  // A hover during nothing-changed refreshes does no geometry work either.
  s.controller.release();
  const SceneViewStats released = s.view.stats();
  s.controller.hover(s.ray(0.5, 4.0), s.tolerance());
  expectNoGeometryWork(released, s.view.stats());
}

}  // namespace
}  // namespace ffdkit::app
