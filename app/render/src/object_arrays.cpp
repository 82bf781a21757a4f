#include "object_arrays.h"

#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkType.h>
#include <vtkTypeInt32Array.h>

namespace ffdkit::app::object_arrays {
namespace {

// Cells of `width` points each from the rows of `cells` (#cells x width), 32-bit.
template <class Rows>
vtkSmartPointer<vtkCellArray> cellArray(const Rows& cells, int width) {
  const vtkIdType count = static_cast<vtkIdType>(cells.rows());
  vtkNew<vtkTypeInt32Array> offsets, connectivity;
  offsets->SetNumberOfValues(count + 1);
  connectivity->SetNumberOfValues(count * width);
  std::int32_t* o = offsets->GetPointer(0);
  std::int32_t* c = connectivity->GetPointer(0);
#pragma omp parallel for schedule(static) if (count >= 65536)
  for (vtkIdType t = 0; t < count; ++t) {
    o[t] = static_cast<std::int32_t>(t * width);
    for (int k = 0; k < width; ++k) c[t * width + k] = static_cast<std::int32_t>(cells(t, k));
  }
  o[count] = static_cast<std::int32_t>(count * width);
  auto array = vtkSmartPointer<vtkCellArray>::New();
  array->SetData(offsets, connectivity);
  return array;
}

}  // namespace

void setFloatPoints(vtkPoints* drawn, const Eigen::MatrixX3d& points, const Eigen::Vector3d& origin) {
  if (drawn->GetDataType() != VTK_FLOAT) drawn->SetDataTypeToFloat();
  drawn->SetNumberOfPoints(points.rows());
  float* out = static_cast<float*>(drawn->GetVoidPointer(0));
  const double* x = points.data();  // column-major: the x, y and z columns
  const double* y = x + points.rows();
  const double* z = y + points.rows();
  const double ox = origin.x(), oy = origin.y(), oz = origin.z();
  // Memory bound: both cores' bandwidth.
#pragma omp parallel for schedule(static) if (points.rows() >= 65536)
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    out[3 * i] = static_cast<float>(x[i] - ox);
    out[3 * i + 1] = static_cast<float>(y[i] - oy);
    out[3 * i + 2] = static_cast<float>(z[i] - oz);
  }
  drawn->Modified();
}

vtkSmartPointer<vtkPolyData> objectPolyData(const meshio::MeshData& mesh, const Eigen::MatrixX3d& points,
                                            const Eigen::Vector3d& origin) {
  vtkNew<vtkPoints> drawn;
  setFloatPoints(drawn, points, origin);
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(drawn);
  if (mesh.triangles.rows() > 0) polyData->SetPolys(cellArray(mesh.triangles, 3));
  if (mesh.segments.rows() > 0) polyData->SetLines(cellArray(mesh.segments, 2));
  if (mesh.triangles.rows() == 0 && mesh.segments.rows() == 0) {  // a point cloud
    const Eigen::VectorXi ids = Eigen::VectorXi::LinSpaced(points.rows(), 0, int(points.rows()) - 1);
    polyData->SetVerts(cellArray(ids, 1));
  }
  return polyData;
}

Eigen::MatrixX3d worldPoints(vtkPoints* drawn, const Eigen::Vector3d& origin) {
  Eigen::MatrixX3d out(drawn->GetNumberOfPoints(), 3);
  for (Eigen::Index i = 0; i < out.rows(); ++i) {
    double p[3];
    drawn->GetPoint(i, p);
    out.row(i) = Eigen::RowVector3d(p[0], p[1], p[2]) + origin.transpose();
  }
  return out;
}

}  // namespace ffdkit::app::object_arrays
