#include "ffdkit/app/scene_view.h"

#include <vector>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

namespace ffdkit::app {
namespace {

vtkSmartPointer<vtkPolyData> toPolyData(const scenes::MeshData& mesh, const Eigen::MatrixX3d& points) {
  vtkNew<vtkPoints> vtkPts;
  vtkPts->SetDataTypeToDouble();
  vtkPts->SetNumberOfPoints(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) vtkPts->SetPoint(i, points(i, 0), points(i, 1), points(i, 2));
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(vtkPts);
  vtkNew<vtkCellArray> triangles;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const vtkIdType ids[3] = {mesh.triangles(t, 0), mesh.triangles(t, 1), mesh.triangles(t, 2)};
    triangles->InsertNextCell(3, ids);
  }
  polyData->SetPolys(triangles);
  vtkNew<vtkCellArray> lines;
  for (Eigen::Index s = 0; s < mesh.segments.rows(); ++s) {
    const vtkIdType ids[2] = {mesh.segments(s, 0), mesh.segments(s, 1)};
    lines->InsertNextCell(2, ids);
  }
  polyData->SetLines(lines);
  if (mesh.triangles.rows() == 0 && mesh.segments.rows() == 0) {
    vtkNew<vtkCellArray> vertices;  // a point cloud
    for (vtkIdType i = 0; i < points.rows(); ++i) vertices->InsertNextCell(1, &i);
    polyData->SetVerts(vertices);
  }
  return polyData;
}

// Lattice points as vertices and the grid lines between neighbours as lines.
vtkSmartPointer<vtkPolyData> latticePolyData(const Eigen::MatrixX3d& points, const Eigen::Vector3i& n) {
  vtkNew<vtkPoints> vtkPts;
  vtkPts->SetDataTypeToDouble();
  for (Eigen::Index i = 0; i < points.rows(); ++i) vtkPts->InsertNextPoint(points(i, 0), points(i, 1), points(i, 2));
  vtkNew<vtkCellArray> vertices;
  for (vtkIdType i = 0; i < points.rows(); ++i) vertices->InsertNextCell(1, &i);
  vtkNew<vtkCellArray> lines;
  auto id = [&](int i, int j, int k) -> vtkIdType { return i + n.x() * (j + n.y() * k); };
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const Eigen::Vector3i here(i, j, k);
        for (int axis = 0; axis < 3; ++axis) {
          Eigen::Vector3i next = here;
          next[axis] += 1;
          if (next[axis] >= n[axis]) continue;
          const vtkIdType ends[2] = {id(i, j, k), id(next.x(), next.y(), next.z())};
          lines->InsertNextCell(2, ends);
        }
      }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(vtkPts);
  polyData->SetVerts(vertices);
  polyData->SetLines(lines);
  return polyData;
}

}  // namespace

struct SceneView::Impl {
  vtkRenderer* renderer = nullptr;
  std::vector<vtkSmartPointer<vtkActor>> actors;
};

SceneView::SceneView(vtkRenderer* renderer) : impl_(std::make_unique<Impl>()) { impl_->renderer = renderer; }

SceneView::~SceneView() {
  for (auto& actor : impl_->actors) impl_->renderer->RemoveActor(actor);
}

void SceneView::show(const scenes::Scene& scene, const scenes::SceneDeformer& deformed) {
  for (auto& actor : impl_->actors) impl_->renderer->RemoveActor(actor);
  impl_->actors.clear();

  for (const auto& object : scene.objects) {
    if (!object.display.visible) continue;
    auto polyData = toPolyData(object.mesh, deformed.points(object.name));
    vtkNew<vtkPolyDataMapper> mapper;
    if (object.mesh.triangles.rows() > 0) {
      vtkNew<vtkPolyDataNormals> normals;  // smooth shading of the deformed surface
      normals->SetInputData(polyData);
      normals->SetSplitting(false);
      mapper->SetInputConnection(normals->GetOutputPort());
    } else {
      mapper->SetInputData(polyData);
    }
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->GetProperty()->SetLineWidth(3.0);
    actor->GetProperty()->SetPointSize(4.0);
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(object.display.color.x(), object.display.color.y(), object.display.color.z());
    actor->GetProperty()->SetOpacity(object.display.opacity);
    actor->GetProperty()->SetSpecular(0.2);
    actor->GetProperty()->SetSpecularPower(30);
    impl_->actors.push_back(actor);
  }
  for (widgets::WidgetId lattice : scene.widgets.widgets(widgets::WidgetType::Lattice)) {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(latticePolyData(scene.widgets.worldControlPoints(lattice), scene.widgets.counts(lattice)));
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.55, 0.8, 1.0);
    actor->GetProperty()->SetLineWidth(2.0);
    actor->GetProperty()->SetPointSize(10.0);
    actor->GetProperty()->SetRenderPointsAsSpheres(true);
    actor->GetProperty()->SetLighting(false);
    impl_->actors.push_back(actor);
  }
  for (auto& actor : impl_->actors) impl_->renderer->AddActor(actor);
  impl_->renderer->SetBackground(scene.background.x(), scene.background.y(), scene.background.z());
  applyCamera(scene.camera);
}

void SceneView::applyCamera(const scenes::Camera& camera) {
  vtkCamera* c = impl_->renderer->GetActiveCamera();
  c->SetPosition(camera.position.data());
  c->SetFocalPoint(camera.focalPoint.data());
  c->SetViewUp(camera.viewUp.data());
  c->SetViewAngle(camera.viewAngleDegrees);
  c->OrthogonalizeViewUp();
  impl_->renderer->ResetCameraClippingRange();
}

}  // namespace ffdkit::app
