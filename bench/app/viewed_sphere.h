// The scene the drag benchmarks of bench/app measure, with a view of it (no window): the sphere
// of addSphereInCubicLattice, its deformer, undo stack and controller, and a SceneView.
#pragma once

#include <map>
#include <memory>

#include <vtkNew.h>
#include <vtkRenderer.h>

#include "ffdkit/render/scene_view.h"
#include "sphere_session.h"

namespace ffdkit::bench {

/// A sphere of about resolution^2 / 2 vertices in a 4x4x4 cubic lattice with a translate widget
/// (addSphereInCubicLattice), shown by a view with the given level of detail.
struct ViewedSphere {
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  app::InteractionController controller{scene, deformer, commands};
  vtkNew<vtkRenderer> renderer;
  std::unique_ptr<app::SceneView> view;
  widgets::WidgetId lattice, widget;
  scenes::ObjectId sphere;

  ViewedSphere(int resolution, app::LevelOfDetail levelOfDetail) {
    const SphereWidget made = addSphereInCubicLattice(controller, resolution);
    lattice = made.lattice;
    widget = made.widget;
    sphere = scene.objects().front().id;
    view = std::make_unique<app::SceneView>(renderer);
    view->setLevelOfDetail(levelOfDetail);
    view->setHighlights(controller.highlights());
    view->show(scene, deformer);
  }
  ViewedSphere(const ViewedSphere&) = delete;
  ViewedSphere& operator=(const ViewedSphere&) = delete;

  /// As the window does: every change the controller reports refreshes the view's highlights
  /// and arrays.
  void refreshViewOnEveryChange() {
    controller.onChanged = [this] {
      view->setHighlights(controller.highlights());
      view->refresh(scene, deformer);
    };
  }
  /// rayAlongArrow of the widget.
  widgets::Ray ray(double along, double shift = 0.0) const {
    return rayAlongArrow(scene.widgets, widget, along, shift);
  }
  /// pickTolerance of the widget.
  double tolerance() const { return pickTolerance(scene.widgets, widget); }
};

/// The one `Session` per resolution of a benchmark run, made at its first use and kept (its
/// setup is not what a benchmark times).
template <class Session>
Session& sessionAt(int resolution) {
  static std::map<int, std::unique_ptr<Session>> sessions;
  auto& s = sessions[resolution];
  if (!s) s = std::make_unique<Session>(resolution);
  return *s;
}

}  // namespace ffdkit::bench
