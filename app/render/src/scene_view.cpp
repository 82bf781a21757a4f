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

vtkSmartPointer<vtkPolyData> toPolyData(const geometry::TriangleMesh& mesh) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh.vertices.rows());
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i)
    points->SetPoint(i, mesh.vertices(i, 0), mesh.vertices(i, 1), mesh.vertices(i, 2));
  vtkNew<vtkCellArray> triangles;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const vtkIdType ids[3] = {mesh.triangles(t, 0), mesh.triangles(t, 1), mesh.triangles(t, 2)};
    triangles->InsertNextCell(3, ids);
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(points);
  polyData->SetPolys(triangles);
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

void SceneView::show(const scenes::Scene& scene) {
  for (auto& actor : impl_->actors) impl_->renderer->RemoveActor(actor);
  impl_->actors.clear();

  for (const auto& object : scene.objects) {
    if (!object.display.visible) continue;
    vtkNew<vtkPolyDataNormals> normals;  // smooth shading
    normals->SetInputData(toPolyData(object.mesh));
    normals->SetSplitting(false);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(normals->GetOutputPort());
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(object.display.color.x(), object.display.color.y(), object.display.color.z());
    actor->GetProperty()->SetOpacity(object.display.opacity);
    actor->GetProperty()->SetSpecular(0.2);
    actor->GetProperty()->SetSpecularPower(30);
    impl_->actors.push_back(actor);
  }
  for (const auto& lattice : scene.lattices) {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(latticePolyData(scenes::latticeRestPoints(scene, lattice), lattice.counts));
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
