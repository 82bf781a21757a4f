// SceneView's widget actors: built for a new model instance, and for the widgets a change concerns.

#include "scene_view_impl.h"

#include <algorithm>

#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkTransform.h>

#include "ffdkit/parts/parts.h"
#include "ffdkit/widgets/widget_redraw.h"

namespace ffdkit::app {

namespace {

using namespace scene_view_shapes;
using widgets::AffineKind;
using widgets::WidgetId;

}  // namespace

vtkSmartPointer<vtkActor> SceneView::Impl::addWidgetActor(vtkPolyData* polyData, const Eigen::Vector3d& colour) {
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(polyData);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(colour.x(), colour.y(), colour.z());
  renderer->AddActor(actor);
  widgetActors.push_back(actor);
  return actor;
}
vtkSmartPointer<vtkActor> SceneView::Impl::addWidgetActor(vtkPolyData* polyData, WidgetId id, Role role,
                                                          const Eigen::Vector3d& base) {
  auto actor = addWidgetActor(polyData, base);
  widgets.push_back({actor, id, role, base});
  return actor;
}

vtkPolyData* SceneView::Impl::cachedGlyph(const widgets::Glyph& glyph, AffineKind kind) {
  std::string key = glyph.shape + "|" + std::string(widgets::affineKindName(kind));
  if (partMesh(glyph.shape)) {
    const Eigen::Matrix4d& m = glyph.partPlacement.matrix();
    key.append(reinterpret_cast<const char*>(m.data()), sizeof(double) * 16);
  }
  auto& shape = glyphShapes[key];
  if (!shape) shape = glyphShape(glyph, kind);
  return shape;
}

// The actors of one widget: a lattice's points and edges and its faces, a cell's points, an
// affine widget's glyph at its frame.
void SceneView::Impl::addWidgetActors(const widgets::WidgetModel& model, WidgetId id) {
  ++stats.widgetActorBuilds;
  switch (model.type(id)) {
    case widgets::WidgetType::Lattice: {
      const Eigen::MatrixX3d points = model.worldControlPoints(id);
      const Eigen::Vector3d base{0.55, 0.8, 1.0};
      auto actor = addWidgetActor(latticePolyData(points, model.counts(id)), id, Role::Lattice, base);
      actor->GetProperty()->SetPointSize(9.0);
      actor->GetProperty()->SetRenderPointsAsSpheres(true);
      actor->GetProperty()->SetLighting(false);
      auto faces = addWidgetActor(latticeFacesPolyData(points, model.counts(id)), id, Role::LatticeFaces, base);
      faces->GetProperty()->SetOpacity(0.18);
      faces->GetProperty()->SetLighting(false);
      return;
    }
    case widgets::WidgetType::Cell: {
      auto actor = addWidgetActor(pointsPolyData(model.cellWorldPoints(id)), id, Role::Cell, {1.0, 0.65, 0.2});
      actor->GetProperty()->SetPointSize(14.0);
      actor->GetProperty()->SetRenderPointsAsSpheres(true);
      actor->GetProperty()->SetLighting(false);
      return;
    }
    case widgets::WidgetType::Affine: {
      const widgets::WidgetFrame frame = model.affineFrame(id);
      vtkNew<vtkTransform> transform;
      const AffineKind kind = model.affineKind(id);
      Eigen::Matrix4d m = frame.frame.matrix();
      m.topLeftCorner<3, 3>() *= frame.size;
      // A free rotate widget (a handle) turns its glyph by its variation about its axis, so a
      // crank follows the pointer; an attached one already turns with its cell.
      if (kind == AffineKind::Rotate && !model.attachedCell(id))
        m.topLeftCorner<3, 3>() *= Eigen::AngleAxisd(model.variation(id), Eigen::Vector3d::UnitZ()).toRotationMatrix();
      Eigen::Matrix<double, 4, 4, Eigen::RowMajor> rowMajor = m;
      transform->SetMatrix(rowMajor.data());
      auto actor = addWidgetActor(cachedGlyph(model.glyph(id), kind), id, Role::Glyph, kindColour(kind));
      actor->SetUserTransform(transform);
      actor->GetProperty()->SetSpecular(0.4);
      actor->GetProperty()->SetSpecularPower(40);
      return;
    }
  }
}

void SceneView::Impl::buildWidgets(const widgets::WidgetModel& model) {
  for (auto& actor : widgetActors) renderer->RemoveActor(actor);
  widgetActors.clear();
  widgets.clear();
  widgetInstance = model.instance();
  widgetRevision = model.revision();
  ++stats.widgetBuilds;
  for (widgets::WidgetType type : {widgets::WidgetType::Lattice, widgets::WidgetType::Cell, widgets::WidgetType::Affine})
    for (WidgetId id : model.widgets(type)) addWidgetActors(model, id);
  // The picked-point marker: one point at the origin, placed by the actor's position.
  pointMarker = addWidgetActor(pointsPolyData(Eigen::RowVector3d::Zero()), kSelected);
  pointMarker->GetProperty()->SetPointSize(18.0);
  pointMarker->GetProperty()->SetRenderPointsAsSpheres(true);
  pointMarker->GetProperty()->SetLighting(false);
  selectedPoints = addWidgetActor(pointsPolyData(Eigen::MatrixX3d(0, 3)), kSelected);
  selectedPoints->GetProperty()->SetPointSize(17.0);  // over a cell's points (14)
  selectedPoints->GetProperty()->SetRenderPointsAsSpheres(true);
  selectedPoints->GetProperty()->SetLighting(false);
  selectedShown.clear();
  selectedRevision = 0;
}

// The actors of the widgets a change concerns (widgets::widgetsToRedraw) anew, and those of the
// widgets the model no longer has gone; every other actor stays as it is.
void SceneView::Impl::redrawWidgets(const widgets::WidgetModel& model, const std::vector<WidgetId>& redraw) {
  widgetRevision = model.revision();
  ++stats.widgetBuilds;
  auto stale = [&](WidgetId id) { return !model.contains(id) || std::binary_search(redraw.begin(), redraw.end(), id); };
  std::erase_if(widgets, [&](const WidgetActor& w) {
    if (!stale(w.id)) return false;
    renderer->RemoveActor(w.actor);
    std::erase(widgetActors, w.actor);
    return true;
  });
  for (WidgetId id : redraw) addWidgetActors(model, id);
}

// Widget actors from the model when it changed; highlights always (no geometry).
void SceneView::Impl::updateWidgets(const widgets::WidgetModel& model) {
  updateTransformer();
  if (!pointMarker || widgetInstance != model.instance()) {
    buildWidgets(model);
  } else if (widgetRevision != model.revision()) {
    redrawWidgets(model, widgets::widgetsToRedraw(model, model.changesSince(widgetRevision)));
  }
  applyHighlights(model);
  updatePins();
  updateFoldTintAndRadius(model);
}

}  // namespace ffdkit::app
