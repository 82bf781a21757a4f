// VTK XML poly data (.vtp) and legacy poly data (.vtk), written through VTK: the one place VTK
// is used in meshio. ffdkit reads both itself (vtp_format.cpp, legacy_vtk_format.cpp): VTK's
// readers trust what a file announces. This file defines vtkPolyDataBytes and nothing else the
// rest of meshio calls, so a program that defines it itself leaves this file, and VTK, out of its
// link (ffdkit/meshio/vtk_writer.h).
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataWriter.h>
#include <vtkXMLPolyDataWriter.h>

#include "ffdkit/meshio/vtk_writer.h"
#include "formats.h"
#include "parse_support.h"

namespace ffdkit::meshio {
namespace {

// Collects the errors a VTK algorithm raises instead of letting them go to stderr.
class VtkMessages {
 public:
  explicit VtkMessages(vtkObject* object) {
    callback_->SetClientData(&text_);
    callback_->SetCallback([](vtkObject*, unsigned long, void* text, void* callData) {
      if (callData != nullptr) static_cast<std::string*>(text)->append(static_cast<const char*>(callData));
    });
    object->AddObserver(vtkCommand::ErrorEvent, callback_);
  }
  std::string firstLine() const {
    std::string line = text_.substr(0, text_.find('\n'));
    if (auto colon = line.rfind(": "); colon != std::string::npos && colon + 2 < line.size()) line = line.substr(colon + 2);
    return line;
  }
  bool empty() const { return text_.empty(); }

 private:
  vtkNew<vtkCallbackCommand> callback_;
  std::string text_;
};

vtkSmartPointer<vtkCellArray> cellArray(const auto& indices) {
  const vtkIdType rows = indices.rows(), cols = indices.cols();
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(rows + 1);
  connectivity->SetNumberOfValues(rows * cols);
  for (vtkIdType r = 0; r <= rows; ++r) offsets->SetValue(r, r * cols);
  for (vtkIdType r = 0; r < rows; ++r)
    for (vtkIdType c = 0; c < cols; ++c) connectivity->SetValue(r * cols + c, indices(r, c));
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, connectivity);
  return cells;
}

}  // namespace

std::string vtkPolyDataBytes(const MeshData& mesh, bool xml) {
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(mesh.points.rows());
  for (Eigen::Index i = 0; i < mesh.points.rows(); ++i)
    for (int c = 0; c < 3; ++c) coordinates->SetTypedComponent(i, c, mesh.points(i, c));
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  if (mesh.triangles.rows() > 0) poly->SetPolys(cellArray(mesh.triangles));
  if (mesh.segments.rows() > 0) poly->SetLines(cellArray(mesh.segments));
  if (mesh.triangles.rows() == 0 && mesh.segments.rows() == 0) {
    // A point cloud: one vertex cell per point, so that VTK tools show the points.
    Eigen::VectorXi all = Eigen::VectorXi::LinSpaced(mesh.points.rows(), 0, int(mesh.points.rows() - 1));
    poly->SetVerts(cellArray(all));
  }
  if (mesh.hasNormals && mesh.triangles.rows() > 0) {
    const Eigen::MatrixX3d n = vertexNormals(mesh.points, mesh.triangles);  // of the deformed surface
    vtkNew<vtkDoubleArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(n.rows());
    for (Eigen::Index i = 0; i < n.rows(); ++i)
      for (int c = 0; c < 3; ++c) normals->SetTypedComponent(i, c, n(i, c));
    poly->GetPointData()->SetNormals(normals);
  }
  if (xml) {
    vtkNew<vtkXMLPolyDataWriter> writer;
    VtkMessages messages(writer);
    writer->SetInputData(poly);
    writer->SetDataModeToBinary();
    writer->SetCompressorTypeToLZ4();  // zlib took ~10x longer than the PLY writer on 1M vertices
    writer->WriteToOutputStringOn();
    if (writer->Write() != 1 || !messages.empty())
      throw MeshIoError("VTK's writer failed (" + messages.firstLine() + ")");
    return writer->GetOutputString();
  }
  vtkNew<vtkPolyDataWriter> writer;
  VtkMessages messages(writer);
  writer->SetInputData(poly);
  writer->SetFileTypeToBinary();
  writer->WriteToOutputStringOn();
  if (writer->Write() != 1 || !messages.empty()) throw MeshIoError("VTK's writer failed (" + messages.firstLine() + ")");
  return writer->GetOutputStdString();
}

}  // namespace ffdkit::meshio
