#include "ffdkit/render/scene_view.h"

#include "scene_view_impl.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include <vtkCamera.h>
#include <vtkFloatArray.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderer.h>

#include "object_arrays.h"

namespace ffdkit::app {

using namespace scene_view_shapes;

SceneView::SceneView(vtkRenderer* renderer) : impl_(std::make_unique<Impl>()) { impl_->renderer = renderer; }

SceneView::~SceneView() {
  impl_->removeOverlay();
  impl_->clearObjects();
  for (auto& actor : impl_->widgetActors) impl_->renderer->RemoveActor(actor);
  if (impl_->pins) impl_->renderer->RemoveActor(impl_->pins);
}

void SceneView::show(const scenes::Scene& scene, const scenes::SceneDeformer& deformed) {
  impl_->buildObjects(scene, deformed);
  impl_->buildTransformer();
  impl_->buildWidgets(scene.widgets);
  impl_->updateWidgets(scene.widgets);
  impl_->renderer->SetBackground(scene.background().x(), scene.background().y(), scene.background().z());
  applyCamera(scene.camera());
}

void SceneView::refresh(const scenes::Scene& scene, const scenes::SceneDeformer& deformed) {
  if (impl_->sameObjects(scene)) {
    if (scene.structureRevision() != impl_->namesSeen) {  // a rename: the labels only
      auto entry = impl_->objects.begin();
      for (const auto& object : scene.objects())
        if (object.display.visible) (entry++)->name = object.name;
    }
    for (auto& entry : impl_->objects) {
      if (impl_->drawProxy(entry, scene, deformed)) continue;  // level of detail: the proxy only
      impl_->updateKeepsOutward(entry, scene.widgets);
      // Only objects whose deformed points moved: their point array, normals and comb, in place.
      const std::uint64_t revision = deformed.revision(entry.id);
      if (revision == entry.pointsRevision) continue;
      entry.pointsRevision = revision;
      auto* normals = vtkFloatArray::SafeDownCast(entry.polyData->GetPointData()->GetNormals());
      // A later step of a one-control-point drag: points and normals follow the motion in one pass.
      const bool followed = normals && entry.gestureNormals.follow(deformed, entry.id, entry.polyData->GetPoints(), normals);
      if (!normals) object_arrays::setFloatPoints(entry.polyData->GetPoints(), deformed.points(entry.id), entry.origin);
      ++impl_->stats.pointUpdates;
      if (normals) {
        ++impl_->stats.normalUpdates;
        // Otherwise the points and normals together (the first step of a drag from the normals
        // drawn last: gesture_normals.h).
        if (followed)
          ++impl_->stats.followedNormals;
        else if (entry.gestureNormals.update(deformed, entry.id, scene.findObject(entry.id)->mesh.triangles,
                                             entry.vertexFaces, deformed.points(entry.id), entry.origin,
                                             entry.faceNormals, entry.polyData->GetPoints(), normals))
          ++impl_->stats.normalsFromBase;
        if (auto* tcoords = vtkFloatArray::SafeDownCast(entry.polyData->GetPointData()->GetTCoords()))
          updateZebraCoordinates(tcoords, normals, entry.display.zebraDirection, entry.display.zebraStripes);
      }
      if (entry.comb)
        vtkPolyDataMapper::SafeDownCast(entry.comb->GetMapper())
            ->SetInputData(combPolyData(entry.chains, deformed.points(entry.id), entry.combFactor));
      entry.polyData->Modified();
    }
  } else {
    impl_->buildObjects(scene, deformed);
    // Drawn in the order a freshly shown scene draws them, the objects before the widgets: where
    // an object's edge and a widget's line meet at one depth, the one drawn first wins the pixel,
    // so an undo that rebuilds the objects gives back the picture as it was.
    for (auto& actor : impl_->widgetActors) {
      impl_->renderer->RemoveActor(actor);
      impl_->renderer->AddActor(actor);
    }
  }
  impl_->namesSeen = scene.structureRevision();
  impl_->updateWidgets(scene.widgets);
  impl_->renderer->SetBackground(scene.background().x(), scene.background().y(), scene.background().z());
  // The clipping range from our own bounds: VTK's would visit every cell of a large mesh
  // (~40 ms per frame at 1M vertices).
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  auto grow = [&](const Eigen::MatrixX3d& points) {
    if (points.rows() == 0) return;
    lo = lo.cwiseMin(points.colwise().minCoeff().transpose());
    hi = hi.cwiseMax(points.colwise().maxCoeff().transpose());
  };
  // Deformed points lie in their lattices' control hull (FFD's convex hull property) or stay
  // near their own points (outside policies): the own box and the lattices bound the scene
  // without visiting a million points per frame.
  for (const auto& entry : impl_->objects) {
    lo = lo.cwiseMin(entry.restLo);
    hi = hi.cwiseMax(entry.restHi);
  }
  for (widgets::WidgetId lattice : scene.widgets.widgets(widgets::WidgetType::Lattice))
    grow(scene.widgets.worldControlPoints(lattice));
  if (lo.x() <= hi.x()) {
    const Eigen::Vector3d margin = Eigen::Vector3d::Constant(0.5 * (hi - lo).norm() + 1e-6);  // glyphs stick out
    lo -= margin;
    hi += margin;
    double bounds[6] = {lo.x(), hi.x(), lo.y(), hi.y(), lo.z(), hi.z()};
    impl_->renderer->ResetCameraClippingRange(bounds);
  } else {
    impl_->renderer->ResetCameraClippingRange();
  }
}

void SceneView::setHighlights(const ViewHighlights& highlights) {
  impl_->highlights = highlights;
  impl_->updateFoldFree();
}

const SceneViewStats& SceneView::stats() const { return impl_->stats; }

void SceneView::applyCamera(const scenes::Camera& camera) {
  vtkCamera* c = impl_->renderer->GetActiveCamera();
  c->SetPosition(camera.position.data());
  c->SetFocalPoint(camera.focalPoint.data());
  c->SetViewUp(camera.viewUp.data());
  c->SetViewAngle(camera.viewAngleDegrees);
  c->OrthogonalizeViewUp();
  impl_->renderer->ResetCameraClippingRange();
}

scenes::Camera SceneView::camera() const {
  vtkCamera* c = impl_->renderer->GetActiveCamera();
  scenes::Camera camera;
  c->GetPosition(camera.position.data());
  c->GetFocalPoint(camera.focalPoint.data());
  c->GetViewUp(camera.viewUp.data());
  camera.viewAngleDegrees = c->GetViewAngle();
  return camera;
}

ViewCamera SceneView::viewCamera() const {
  vtkCamera* c = impl_->renderer->GetActiveCamera();
  return ViewCamera{camera(), c->GetParallelProjection() != 0, c->GetParallelScale()};
}

void SceneView::setViewCamera(const ViewCamera& view) {
  vtkCamera* c = impl_->renderer->GetActiveCamera();
  c->SetParallelProjection(view.parallel);
  c->SetParallelScale(view.parallelScale);
  applyCamera(view.camera);
}

widgets::Ray SceneView::rayAt(double x, double y) const {
  vtkRenderer* r = impl_->renderer;
  auto world = [&](double z) {
    r->SetDisplayPoint(x, y, z);
    r->DisplayToWorld();
    double p[4];
    r->GetWorldPoint(p);
    return Eigen::Vector3d(p[0] / p[3], p[1] / p[3], p[2] / p[3]);
  };
  widgets::Ray ray;
  ray.origin = world(0.0);
  ray.direction = (world(1.0) - ray.origin).normalized();
  return ray;
}

Eigen::Vector2d SceneView::displayPoint(const Eigen::Vector3d& p) const {
  vtkRenderer* r = impl_->renderer;
  r->SetWorldPoint(p.x(), p.y(), p.z(), 1.0);
  r->WorldToDisplay();
  double d[3];
  r->GetDisplayPoint(d);
  return {d[0], d[1]};
}

double SceneView::pixelSize() const {
  vtkCamera* c = impl_->renderer->GetActiveCamera();
  const int* size = impl_->renderer->GetSize();
  const double height = std::max(1, size[1]);
  if (c->GetParallelProjection()) return 2.0 * c->GetParallelScale() / height;
  return 2.0 * c->GetDistance() * std::tan(c->GetViewAngle() * std::numbers::pi / 360.0) / height;
}

}  // namespace ffdkit::app
