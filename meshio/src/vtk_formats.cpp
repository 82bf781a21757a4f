// VTK XML poly data (.vtp), read and written through VTK, and legacy poly data (.vtk), written
// through VTK (legacy_vtk_format.cpp reads it): the one place VTK is used in meshio. VTK's XML
// reader allocates what a file announces and trusts the data, so the announced counts and
// compression headers are checked against the file's size first, and the output is checked completely before anything
// uses it: every cell's offsets and point ids in range, every point finite; cells are then
// triangulated here (fans, strips), not by a VTK filter.
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkIdTypeArray.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataWriter.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include "formats.h"
#include "parse_support.h"
#include "vtk_xml_block_headers.h"

namespace ffdkit::meshio::detail {
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

// Silences VTK's output window while a file is read: parser objects inside the readers report
// there, and our message names the file instead.
class QuietOutputWindow {
 public:
  QuietOutputWindow()
      : window_(vtkOutputWindow::GetInstance()), previous_(window_->GetDisplayMode()),
        previousLog_(vtkLogger::GetCurrentVerbosityCutoff()) {
    window_->SetDisplayModeToNever();
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);  // VTK 9.1 also logs errors through loguru
  }
  ~QuietOutputWindow() {
    window_->SetDisplayMode(previous_);
    vtkLogger::SetStderrVerbosity(previousLog_);
  }
  QuietOutputWindow(const QuietOutputWindow&) = delete;
  QuietOutputWindow& operator=(const QuietOutputWindow&) = delete;

 private:
  vtkOutputWindow* window_;
  int previous_;
  vtkLogger::Verbosity previousLog_;
};

// Calls `cell(first, size)` for every cell of `cells` over its connectivity, after checking the
// offsets run from 0 up to the connectivity's size and every id is a point.
template <class Cell>
void forEachCheckedCell(vtkCellArray* cells, const char* kind, vtkIdType points, const std::string& source, std::vector<vtkIdType>& ids,
                        Cell&& cell) {
  if (cells == nullptr || cells->GetNumberOfCells() == 0) return;
  vtkDataArray* offsets = cells->GetOffsetsArray();
  vtkDataArray* connectivity = cells->GetConnectivityArray();
  if (offsets == nullptr || connectivity == nullptr) throw MeshIoError(source + ": " + kind + " cells without arrays");
  const vtkIdType size = connectivity->GetNumberOfTuples();
  const vtkIdType n = offsets->GetNumberOfTuples() - 1;
  if (n < 0 || offsets->GetComponent(0, 0) != 0.0 || offsets->GetComponent(n, 0) != double(size))
    throw MeshIoError(source + ": " + kind + " cells: the offsets do not cover the connectivity");
  vtkIdType previous = 0;
  for (vtkIdType c = 0; c < n; ++c) {
    const auto next = vtkIdType(offsets->GetComponent(c + 1, 0));
    if (next < previous || next > size)
      throw MeshIoError(source + ": " + Where{kind, c}.text() + ": offset " + std::to_string(next) + " out of order");
    ids.clear();
    for (vtkIdType k = previous; k < next; ++k) {
      const double id = connectivity->GetComponent(k, 0);
      if (!(id >= 0.0 && id < double(points)))
        throw MeshIoError(source + ": " + Where{kind, c}.text() + ": point id " + std::to_string((long long)id) + " is outside 0.." +
                          std::to_string(points - 1));
      ids.push_back(vtkIdType(id));
    }
    cell(c, ids);
    previous = next;
  }
}

MeshData checkedMesh(vtkPolyData* poly, const std::string& source) {
  vtkPoints* points = poly->GetPoints();
  const vtkIdType n = points != nullptr ? points->GetNumberOfPoints() : 0;
  if (n == 0) throw MeshIoError(source + ": the file has no points");
  if (n > INT_MAX) throw MeshIoError(source + ": more points than ffdkit indexes");
  MeshData mesh;
  mesh.hasNormals = poly->GetPointData() != nullptr && poly->GetPointData()->GetNormals() != nullptr;
  mesh.points.resize(n, 3);
  for (vtkIdType i = 0; i < n; ++i) {
    double p[3];
    points->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw MeshIoError(source + ": " + Where{"point", i}.text() + ": non-finite coordinate");
    mesh.points.row(i) << p[0], p[1], p[2];
  }
  TriangleSink triangles;
  SegmentSink segments;
  std::vector<vtkIdType> ids;
  forEachCheckedCell(poly->GetVerts(), "vertex cell", n, source, ids, [](vtkIdType, const std::vector<vtkIdType>&) {});
  forEachCheckedCell(poly->GetLines(), "line", n, source, ids, [&](vtkIdType, const std::vector<vtkIdType>& line) {
    for (std::size_t k = 0; k + 1 < line.size(); ++k) segments.add(int(line[k]), int(line[k + 1]));
  });
  forEachCheckedCell(poly->GetPolys(), "polygon", n, source, ids, [&](vtkIdType, const std::vector<vtkIdType>& polygon) {
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) triangles.add(int(polygon[0]), int(polygon[k]), int(polygon[k + 1]));
  });
  forEachCheckedCell(poly->GetStrips(), "strip", n, source, ids, [&](vtkIdType, const std::vector<vtkIdType>& strip) {
    for (std::size_t k = 0; k + 2 < strip.size(); ++k) {
      if (k % 2 == 0) triangles.add(int(strip[k]), int(strip[k + 1]), int(strip[k + 2]));
      else triangles.add(int(strip[k + 1]), int(strip[k]), int(strip[k + 2]));
    }
  });
  mesh.triangles = triangles.take();
  mesh.segments = segments.take();
  return mesh;
}

template <class Reader>
MeshData readWith(std::string_view bytes, const std::string& source) {
  // VTK's error macros report only while global warnings are on; the observers keep the
  // reports off stderr (the executive's too), and ours names the file instead.
  QuietOutputWindow quiet;
  vtkNew<Reader> reader;
  VtkMessages messages(reader);
  VtkMessages executive(reader->GetExecutive());
  reader->ReadFromInputStringOn();
  reader->SetInputString(std::string(bytes));
  try {
    reader->Update();
  } catch (const std::bad_alloc&) {
    // VTK allocates the sizes a binary block's header announces before it reads the block.
    throw MeshIoError(source + ": cannot read (a data block announces more data than fits in memory)");
  }
  vtkPolyData* poly = reader->GetOutput();
  // Any error means part of the file was not read (VTK keeps what it had, e.g. zeros).
  if (!messages.empty()) throw MeshIoError(source + ": cannot read (" + messages.firstLine() + ")");
  if (poly == nullptr) throw MeshIoError(source + ": cannot read");
  return checkedMesh(poly, source);
}

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

MeshData readVtp(std::string_view bytes, const std::string& source) {
  // Every NumberOf... attribute (of each Piece) against what the file's bytes can hold: a
  // point or cell takes at least 4 bytes, and compression (zlib, LZ4) expands data at most
  // ~1000 times, so no count above 256 x the file's size can be real.
  const std::size_t limit = 256 * std::max<std::size_t>(bytes.size(), 1);
  for (std::size_t at = bytes.find("NumberOf"); at != std::string_view::npos; at = bytes.find("NumberOf", at + 8)) {
    const std::size_t quote = bytes.find('"', at);
    if (quote == std::string_view::npos || quote > at + 40) continue;
    unsigned long long value = 0;
    const auto r = std::from_chars(bytes.data() + quote + 1, bytes.data() + bytes.size(), value);
    if (r.ec == std::errc::result_out_of_range || (r.ec == std::errc() && value > limit))
      throw MeshIoError(source + ": " + std::string(bytes.substr(at, quote - at - 1)) + " announces more than a file of " +
                        std::to_string(bytes.size()) + " bytes can hold");
  }
  checkVtkXmlBlockHeaders(bytes, source);
  return readWith<vtkXMLPolyDataReader>(bytes, source);
}

std::string writeVtk(const MeshData& mesh, bool xml) {
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

}  // namespace ffdkit::meshio::detail
