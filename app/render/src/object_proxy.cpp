#include "object_proxy.h"

#include <Eigen/Geometry>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkRenderer.h>

#include "surface_mapper.h"

namespace ffdkit::app {

ObjectProxy::ObjectProxy(vtkRenderer* renderer, vtkActor* full, const meshio::MeshData& mesh, Eigen::Index targetVertices)
    : renderer_(renderer), full_(full), target_(targetVertices) {
  mesh_ = clusterVertices(mesh.points, mesh.triangles, targetVertices);
  polyData_ = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(vertexCount());
  polyData_->SetPoints(points);
  vtkNew<vtkCellArray> cells;
  cells->AllocateExact(mesh_.triangles.rows(), 3 * mesh_.triangles.rows());
  for (Eigen::Index t = 0; t < mesh_.triangles.rows(); ++t) {
    const vtkIdType ids[3] = {mesh_.triangles(t, 0), mesh_.triangles(t, 1), mesh_.triangles(t, 2)};
    cells->InsertNextCell(3, ids);
  }
  polyData_->SetPolys(cells);
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(vertexCount());
  polyData_->GetPointData()->SetNormals(normals);
  vtkNew<SurfaceMapper> mapper;
  mapper->SetInputData(polyData_);
  actor_ = vtkSmartPointer<vtkActor>::New();
  actor_->SetMapper(mapper);
  actor_->SetProperty(full->GetProperty());
  actor_->SetVisibility(false);
  renderer_->AddActor(actor_);
}

ObjectProxy::~ObjectProxy() { renderer_->RemoveActor(actor_); }

void ObjectProxy::show(bool proxy) {
  shown_ = proxy;
  actor_->SetVisibility(proxy);
  full_->SetVisibility(!proxy);
}

void ObjectProxy::gather(const Eigen::MatrixX3d& points, Eigen::MatrixX3d& out) const {
  const Eigen::Index n = vertexCount();
  out.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) out.row(i) = points.row(mesh_.vertices[static_cast<std::size_t>(i)]);
}

bool ObjectProxy::update(const scenes::SceneDeformer& deformer, scenes::ObjectId object) {
  const std::uint64_t revision = deformer.revision(object);
  if (drawn_ && revision == drawnRevision_) return false;
  if (deformer.coverage(object) == scenes::PointCoverage::Subset) {
    if (deformer.subsetIndices(object) != mesh_.vertices) return false;  // evaluated for another view's proxy
    draw(deformer.subsetPoints(object));
  } else {
    gather(deformer.points(object), scratch_);
    draw(scratch_);
  }
  drawnRevision_ = revision;
  drawn_ = true;
  return true;
}

void ObjectProxy::draw(const Eigen::MatrixX3d& points) {
  const Eigen::Index n = points.rows();
  auto* vtkPts = vtkFloatArray::SafeDownCast(polyData_->GetPoints()->GetData());
  float* p = vtkPts->GetPointer(0);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) p[3 * i + c] = static_cast<float>(points(i, c));
  // Area-weighted vertex normals of the proxy's triangles.
  std::vector<Eigen::Vector3d> sums(static_cast<std::size_t>(n), Eigen::Vector3d::Zero());
  for (Eigen::Index t = 0; t < mesh_.triangles.rows(); ++t) {
    const int a = mesh_.triangles(t, 0), b = mesh_.triangles(t, 1), c = mesh_.triangles(t, 2);
    const Eigen::Vector3d pa = points.row(a).transpose();
    const Eigen::Vector3d area = (points.row(b).transpose() - pa).cross(points.row(c).transpose() - pa);
    sums[static_cast<std::size_t>(a)] += area;
    sums[static_cast<std::size_t>(b)] += area;
    sums[static_cast<std::size_t>(c)] += area;
  }
  auto* normals = vtkFloatArray::SafeDownCast(polyData_->GetPointData()->GetNormals());
  float* out = normals->GetPointer(0);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d& s = sums[static_cast<std::size_t>(i)];
    const double length = s.norm();
    const Eigen::Vector3d unit = length > 0.0 ? Eigen::Vector3d(s / length) : Eigen::Vector3d::UnitZ();
    for (int c = 0; c < 3; ++c) out[3 * i + c] = static_cast<float>(unit[c]);
  }
  polyData_->GetPoints()->Modified();
  normals->Modified();
  polyData_->Modified();
}

std::size_t ObjectProxy::memoryBytes() const {
  return std::size_t(polyData_->GetActualMemorySize()) * 1024 + sizeof(Eigen::Index) * mesh_.vertices.capacity() +
         sizeof(double) * std::size_t(scratch_.size());
}

bool hasProxy(const LevelOfDetail& lod, const scenes::SceneObject* object, Eigen::Index pointCount,
              const scenes::DisplaySettings& display) {
  return lod.enabled && object != nullptr && pointCount >= lod.minVertices && object->mesh.triangles.rows() > 0 &&
         display.surfaceStyle != scenes::SurfaceStyle::Zebra && object->mesh.points.rows() == pointCount;
}

bool prepareObjectProxy(std::unique_ptr<ObjectProxy>& proxy, const LevelOfDetail& lod, vtkRenderer* renderer,
                        vtkActor* full, const scenes::SceneObject* object, Eigen::Index pointCount,
                        const scenes::DisplaySettings& display) {
  if (!hasProxy(lod, object, pointCount, display)) {
    if (proxy) proxy->show(false);
    proxy.reset();
    return false;
  }
  if (proxy && proxy->targetVertices() == lod.proxyVertices) return false;
  proxy.reset();
  proxy = std::make_unique<ObjectProxy>(renderer, full, object->mesh, lod.proxyVertices);
  return true;
}

}  // namespace ffdkit::app
