// SceneView's highlights: colours, line widths, the selected lattices' faces, the point marker, the
// edit mode's selected points, pins, fold tints and the soft radius. They build no widget geometry.

#include "scene_view_impl.h"

#include <array>

#include <vtkAppendPolyData.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>

namespace ffdkit::app {

namespace {

using namespace scene_view_shapes;
using widgets::WidgetId;

}  // namespace

void SceneView::Impl::updatePins() {
  if (pins && highlights.pins == pinsShown) return;
  pinsShown = highlights.pins;
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(pinsShown.size()), 3);
  for (std::size_t i = 0; i < pinsShown.size(); ++i) points.row(static_cast<Eigen::Index>(i)) = pinsShown[i].transpose();
  if (!pins) {
    pins = vtkSmartPointer<vtkActor>::New();
    pins->SetMapper(vtkSmartPointer<vtkPolyDataMapper>::New());
    pins->GetProperty()->SetColor(kPinColour.x(), kPinColour.y(), kPinColour.z());
    pins->GetProperty()->SetPointSize(14.0);
    pins->GetProperty()->SetRenderPointsAsSpheres(true);
    pins->GetProperty()->SetLighting(false);
    renderer->AddActor(pins);
  }
  vtkPolyDataMapper::SafeDownCast(pins->GetMapper())->SetInputData(pointsPolyData(points));
  pins->SetVisibility(!pinsShown.empty());
}

vtkSmartPointer<vtkActor> SceneView::Impl::addPlainActor() {
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(vtkSmartPointer<vtkPolyDataMapper>::New());
  renderer->AddActor(actor);
  return actor;
}

void SceneView::Impl::updateFoldTintAndRadius(const widgets::WidgetModel& model) {
  if (!foldTint) {
    foldTint = addPlainActor();
    foldTint->GetProperty()->SetOpacity(0.45);
    softSphere = addPlainActor();
    softSphere->GetProperty()->SetColor(0.95, 0.95, 0.95);
    softSphere->GetProperty()->SetLighting(false);
    softSphere->GetProperty()->SetLineWidth(1.5);
  }
  if (highlights.foldTints != foldTintShown || (!foldTintShown.empty() && foldTintRevision != model.revision())) {
    foldTintShown = highlights.foldTints;
    foldTintRevision = model.revision();
    vtkNew<vtkAppendPolyData> all;
    for (const FoldTint& tint : foldTintShown) {
      if (!model.contains(tint.lattice) || model.type(tint.lattice) != widgets::WidgetType::Lattice) continue;
      // A tint of another lattice under that id (the scene before an Open) or of its older cells
      // is not drawn: its verdicts would be indexed past the lattice's cells.
      const ffd::Lattice lattice = model.ffdLattice(tint.lattice);
      const std::array<int, 3> cells{lattice.axis(0).cellCount(), lattice.axis(1).cellCount(), lattice.axis(2).cellCount()};
      if (cells == tint.cellCounts) all->AddInputData(foldTintPolyData(lattice, tint.cellCounts, tint.cells));
    }
    if (all->GetNumberOfInputConnections(0) > 0) {
      all->Update();
      vtkPolyDataMapper::SafeDownCast(foldTint->GetMapper())->SetInputData(all->GetOutput());
    }
    foldTint->SetVisibility(all->GetNumberOfInputConnections(0) > 0);
  }
  if (highlights.softRadius != softRadiusShown) {
    softRadiusShown = highlights.softRadius;
    if (softRadiusShown)
      vtkPolyDataMapper::SafeDownCast(softSphere->GetMapper())
          ->SetInputData(sphereCirclesPolyData(softRadiusShown->centre, softRadiusShown->radius));
    softSphere->SetVisibility(softRadiusShown.has_value());
  }
}

Eigen::Vector3d SceneView::Impl::emphasis(WidgetId id, const Eigen::Vector3d& base) const {
  if (contains(highlights.selected, id)) return kSelected;
  if (contains(highlights.visited, id)) return kVisited;
  if (highlights.hovered == id) return 0.45 * base + 0.55 * Eigen::Vector3d::Ones();
  return base;
}

// Colours, line widths, the selected lattices' faces and the point marker from the highlights.
void SceneView::Impl::applyHighlights(const widgets::WidgetModel& model) {
  for (const WidgetActor& w : widgets) {
    const bool selected = contains(highlights.selected, w.id);
    vtkProperty* property = w.actor->GetProperty();
    if (w.role == Role::LatticeFaces) {
      w.actor->SetVisibility(selected);
      continue;
    }
    const Eigen::Vector3d colour = emphasis(w.id, w.base);
    property->SetColor(colour.x(), colour.y(), colour.z());
    if (w.role == Role::Lattice) property->SetLineWidth(selected ? 3.0 : 1.5);
  }
  const bool marked = highlights.point && model.contains(highlights.point->lattice) &&
                      model.type(highlights.point->lattice) == widgets::WidgetType::Lattice &&
                      highlights.point->index < model.controlPoints(highlights.point->lattice).rows();
  pointMarker->SetVisibility(marked);
  // The edit mode's selection: its few points again when it or the model changed.
  if (highlights.selectedPoints != selectedShown || selectedRevision != model.revision()) {
    selectedShown = highlights.selectedPoints;
    selectedRevision = model.revision();
    Eigen::MatrixX3d points(static_cast<Eigen::Index>(selectedShown.size()), 3);
    Eigen::Index row = 0;
    for (const LatticePointRef& p : selectedShown)
      if (model.contains(p.lattice) && model.type(p.lattice) == widgets::WidgetType::Lattice &&
          p.index < model.controlPoints(p.lattice).rows())
        points.row(row++) = (model.latticeFrame(p.lattice) * Eigen::Vector3d(model.controlPoints(p.lattice).row(p.index).transpose())).transpose();
    vtkPolyDataMapper::SafeDownCast(selectedPoints->GetMapper())->SetInputData(pointsPolyData(points.topRows(row)));
  }
  selectedPoints->SetVisibility(!selectedShown.empty());
  if (marked) {
    const Eigen::Vector3d p =
        model.latticeFrame(highlights.point->lattice) *
        Eigen::Vector3d(model.controlPoints(highlights.point->lattice).row(highlights.point->index).transpose());
    pointMarker->SetPosition(p.x(), p.y(), p.z());
  }
}

}  // namespace ffdkit::app
