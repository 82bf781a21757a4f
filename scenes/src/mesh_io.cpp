#include "ffdkit/scenes/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <vtkAppendPolyData.h>
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkCompositeDataIterator.h>
#include <vtkCompositeDataSet.h>
#include <vtkGLTFReader.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkOBJWriter.h>
#include <vtkPLYReader.h>
#include <vtkPLYWriter.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkPolyDataReader.h>
#include <vtkSTLReader.h>
#include <vtkSTLWriter.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include "ffdkit/scenes/atomic_write.h"

namespace ffdkit::scenes {
namespace {

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// Collects the error messages a VTK algorithm raises, instead of letting them go to stderr.
class VtkErrorCollector {
 public:
  explicit VtkErrorCollector(vtkObject* object) {
    callback_->SetClientData(&messages_);
    callback_->SetCallback([](vtkObject*, unsigned long, void* messages, void* callData) {
      if (callData != nullptr) static_cast<std::string*>(messages)->append(static_cast<const char*>(callData));
    });
    object->AddObserver(vtkCommand::ErrorEvent, callback_);
    object->AddObserver(vtkCommand::WarningEvent, callback_);
  }
  const std::string& messages() const { return messages_; }

 private:
  vtkNew<vtkCallbackCommand> callback_;
  std::string messages_;
};

std::string firstLine(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  if (auto colon = line.rfind(": "); colon != std::string::npos && colon + 2 < line.size()) line = line.substr(colon + 2);
  return line;
}

MeshData fromPolyData(vtkPolyData* input, const std::filesystem::path& path) {
  vtkNew<vtkTriangleFilter> triangulate;  // polygons and strips -> triangles, poly-lines -> segments
  triangulate->SetInputData(input);
  triangulate->PassVertsOff();
  triangulate->PassLinesOn();
  triangulate->Update();
  vtkPolyData* poly = triangulate->GetOutput();

  MeshData mesh;
  mesh.hasNormals = input->GetPointData() != nullptr && input->GetPointData()->GetNormals() != nullptr;
  // Keep every input point (a point cloud has no cells to triangulate).
  vtkPoints* points = input->GetPoints();
  const vtkIdType n = points != nullptr ? points->GetNumberOfPoints() : 0;
  if (n == 0) throw MeshIoError(path.string() + ": the file has no points");
  mesh.points.resize(n, 3);
  for (vtkIdType i = 0; i < n; ++i) {
    double p[3];
    points->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw MeshIoError(path.string() + ": point " + std::to_string(i) + " has a non-finite coordinate");
    mesh.points.row(i) << p[0], p[1], p[2];
  }
  // The triangle filter keeps point ids when it passes the input's points through.
  if (poly->GetNumberOfPoints() != n) throw MeshIoError(path.string() + ": triangulation changed the points");

  std::vector<Eigen::RowVector3i> triangles;
  vtkCellArray* polys = poly->GetPolys();
  vtkNew<vtkIdList> ids;
  for (polys->InitTraversal(); polys->GetNextCell(ids);) {
    if (ids->GetNumberOfIds() == 3)
      triangles.emplace_back(int(ids->GetId(0)), int(ids->GetId(1)), int(ids->GetId(2)));
  }
  std::vector<Eigen::RowVector2i> segments;
  vtkCellArray* lines = poly->GetLines();
  for (lines->InitTraversal(); lines->GetNextCell(ids);) {
    for (vtkIdType k = 0; k + 1 < ids->GetNumberOfIds(); ++k)
      segments.emplace_back(int(ids->GetId(k)), int(ids->GetId(k + 1)));
  }
  mesh.triangles.resize(Eigen::Index(triangles.size()), 3);
  for (std::size_t t = 0; t < triangles.size(); ++t) mesh.triangles.row(Eigen::Index(t)) = triangles[t];
  mesh.segments.resize(Eigen::Index(segments.size()), 2);
  for (std::size_t s = 0; s < segments.size(); ++s) mesh.segments.row(Eigen::Index(s)) = segments[s];
  return mesh;
}

// VTK's pipeline prints its own error report to stderr when a reader fails; we report the
// failure ourselves, with the file name, so silence VTK while reading.
class QuietVtk {
 public:
  QuietVtk() : previous_(vtkObject::GetGlobalWarningDisplay()) { vtkObject::GlobalWarningDisplayOff(); }
  ~QuietVtk() { vtkObject::SetGlobalWarningDisplay(previous_); }
  QuietVtk(const QuietVtk&) = delete;
  QuietVtk& operator=(const QuietVtk&) = delete;

 private:
  int previous_;
};

template <class Reader>
MeshData readWith(const std::filesystem::path& path) {
  QuietVtk quiet;
  vtkNew<Reader> reader;
  VtkErrorCollector errors(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  if (!errors.messages().empty() && reader->GetOutput()->GetNumberOfPoints() == 0)
    throw MeshIoError(path.string() + ": cannot read (" + firstLine(errors.messages()) + ")");
  return fromPolyData(reader->GetOutput(), path);
}

MeshData readGltf(const std::filesystem::path& path) {
  QuietVtk quiet;
  vtkNew<vtkGLTFReader> reader;
  VtkErrorCollector errors(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  auto* blocks = vtkCompositeDataSet::SafeDownCast(reader->GetOutputDataObject(0));
  if (blocks == nullptr)
    throw MeshIoError(path.string() + ": cannot read glTF (" + firstLine(errors.messages()) + ")");
  vtkNew<vtkAppendPolyData> append;
  vtkSmartPointer<vtkCompositeDataIterator> it = vtkSmartPointer<vtkCompositeDataIterator>::Take(blocks->NewIterator());
  int pieces = 0;
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem()) {
    if (auto* piece = vtkPolyData::SafeDownCast(it->GetCurrentDataObject())) {
      append->AddInputData(piece);
      ++pieces;
    }
  }
  if (pieces == 0) throw MeshIoError(path.string() + ": the glTF file has no meshes");
  append->Update();
  return fromPolyData(append->GetOutput(), path);
}

vtkSmartPointer<vtkPolyData> toPolyData(const MeshData& mesh) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh.points.rows());
  for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) points->SetPoint(i, mesh.points(i, 0), mesh.points(i, 1), mesh.points(i, 2));
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  if (mesh.triangles.rows() > 0) {
    vtkNew<vtkCellArray> cells;
    for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
      const vtkIdType ids[3] = {mesh.triangles(t, 0), mesh.triangles(t, 1), mesh.triangles(t, 2)};
      cells->InsertNextCell(3, ids);
    }
    poly->SetPolys(cells);
  }
  if (mesh.segments.rows() > 0) {
    vtkNew<vtkCellArray> cells;
    for (Eigen::Index s = 0; s < mesh.segments.rows(); ++s) {
      const vtkIdType ids[2] = {mesh.segments(s, 0), mesh.segments(s, 1)};
      cells->InsertNextCell(2, ids);
    }
    poly->SetLines(cells);
  }
  if (mesh.triangles.rows() == 0 && mesh.segments.rows() == 0) {
    vtkNew<vtkCellArray> verts;  // a point cloud: one vertex cell per point, so writers keep them
    for (vtkIdType i = 0; i < mesh.points.rows(); ++i) verts->InsertNextCell(1, &i);
    poly->SetVerts(verts);
  }
  if (mesh.hasNormals && mesh.triangles.rows() > 0) {
    vtkNew<vtkPolyDataNormals> normals;  // the deformed surface's normals, not the stale ones
    normals->SetInputData(poly);
    normals->SetSplitting(false);
    normals->ConsistencyOff();
    normals->AutoOrientNormalsOff();
    normals->ComputePointNormalsOn();
    normals->ComputeCellNormalsOff();
    normals->Update();
    poly = normals->GetOutput();
  }
  return poly;
}

template <class Writer>
void writeWith(Writer* writer, vtkPolyData* poly, const std::filesystem::path& temporary) {
  VtkErrorCollector errors(writer);
  writer->SetInputData(poly);
  writer->SetFileName(temporary.c_str());
  if (writer->Write() != 1 || !errors.messages().empty())
    throw MeshIoError(firstLine(errors.messages().empty() ? std::string("the writer failed") : errors.messages()));
}

}  // namespace

void validateMesh(const MeshData& mesh, const std::string& what) {
  const Eigen::Index n = mesh.points.rows();
  if (n == 0) throw MeshIoError(what + ": the mesh has no points");
  for (Eigen::Index i = 0; i < n; ++i)
    if (!mesh.points.row(i).allFinite())
      throw MeshIoError(what + ": point " + std::to_string(i) + " has a non-finite coordinate");
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t)
    if (mesh.triangles.row(t).minCoeff() < 0 || mesh.triangles.row(t).maxCoeff() >= n)
      throw MeshIoError(what + ": triangle " + std::to_string(t) + " uses a point index outside 0.." + std::to_string(n - 1));
  for (Eigen::Index s = 0; s < mesh.segments.rows(); ++s)
    if (mesh.segments.row(s).minCoeff() < 0 || mesh.segments.row(s).maxCoeff() >= n)
      throw MeshIoError(what + ": segment " + std::to_string(s) + " uses a point index outside 0.." + std::to_string(n - 1));
}

MeshData readXyz(std::istream& in, const std::string& sourceName) {
  std::vector<Eigen::RowVector3d> points;
  std::string line;
  for (int lineNumber = 1; std::getline(in, line); ++lineNumber) {
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream fields(line);
    std::vector<std::string> tokens;
    for (std::string token; fields >> token;) tokens.push_back(token);
    if (tokens.empty()) continue;  // blank or comment line
    const std::string where = sourceName + ":" + std::to_string(lineNumber) + ": ";
    if (tokens.size() != 3) throw MeshIoError(where + "expected three numbers \"x y z\", got " + std::to_string(tokens.size()) + " fields");
    Eigen::RowVector3d p;
    for (int c = 0; c < 3; ++c) {
      // strtod, not >>: it parses "nan" and "1e999" (to NaN / inf) so that they are reported, not skipped.
      const std::string& token = tokens[std::size_t(c)];
      char* end = nullptr;
      p[c] = std::strtod(token.c_str(), &end);
      if (end != token.c_str() + token.size()) throw MeshIoError(where + "'" + token + "' is not a number");
      if (!std::isfinite(p[c])) throw MeshIoError(where + "non-finite coordinate '" + token + "'");
    }
    points.push_back(p);
  }
  if (points.empty()) throw MeshIoError(sourceName + ": the file has no points");
  MeshData mesh;
  mesh.points.resize(Eigen::Index(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) mesh.points.row(Eigen::Index(i)) = points[i];
  return mesh;
}

void writeXyz(std::ostream& out, const Eigen::MatrixX3d& points) {
  out.precision(17);  // round-trips every double
  for (Eigen::Index i = 0; i < points.rows(); ++i) out << points(i, 0) << ' ' << points(i, 1) << ' ' << points(i, 2) << '\n';
}

MeshData readMesh(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw MeshIoError(path.string() + ": no such file");
  const std::string ext = lowerExtension(path);
  if (ext == ".xyz") {
    std::ifstream in(path);
    if (!in) throw MeshIoError(path.string() + ": cannot open");
    return readXyz(in, path.string());
  }
  if (ext == ".obj") return readWith<vtkOBJReader>(path);
  if (ext == ".ply") return readWith<vtkPLYReader>(path);
  if (ext == ".stl") return readWith<vtkSTLReader>(path);
  if (ext == ".vtp") return readWith<vtkXMLPolyDataReader>(path);
  if (ext == ".vtk") return readWith<vtkPolyDataReader>(path);
  if (ext == ".gltf" || ext == ".glb") return readGltf(path);
  throw MeshIoError(path.string() + ": unknown mesh format '" + ext +
                    "' (reads .obj .ply .stl .vtp .vtk .gltf .glb .xyz)");
}

void writeMesh(const std::filesystem::path& path, const MeshData& mesh) {
  const std::string ext = lowerExtension(path);
  if (ext != ".obj" && ext != ".ply" && ext != ".stl" && ext != ".vtp" && ext != ".xyz")
    throw MeshIoError(path.string() + ": cannot write format '" + ext + "' (writes .obj .ply .stl .vtp .xyz)");
  validateMesh(mesh, path.string());
  if (ext == ".stl" && mesh.triangles.rows() == 0) throw MeshIoError(path.string() + ": STL needs triangles");

  if (ext == ".xyz") {
    std::ostringstream text;
    writeXyz(text, mesh.points);
    try {
      writeFileAtomically(path, text.str());
    } catch (const std::exception& e) {
      throw MeshIoError(e.what());
    }
    return;
  }

  // VTK writers take a file name: write a temporary file beside the target (same extension,
  // which some writers look at), then rename it over the target.
  const std::filesystem::path temporary = temporaryPathBeside(path);
  try {
    vtkSmartPointer<vtkPolyData> poly = toPolyData(mesh);
    if (ext == ".obj") {
      vtkNew<vtkOBJWriter> w;
      writeWith(w.Get(), poly, temporary);
    } else if (ext == ".ply") {
      vtkNew<vtkPLYWriter> w;
      w->SetFileTypeToBinary();
      writeWith(w.Get(), poly, temporary);
    } else if (ext == ".stl") {
      vtkNew<vtkSTLWriter> w;
      w->SetFileTypeToBinary();
      writeWith(w.Get(), poly, temporary);
    } else {
      vtkNew<vtkXMLPolyDataWriter> w;
      w->SetDataModeToBinary();
      w->SetCompressorTypeToLZ4();  // zlib took ~10x longer than the PLY writer on 1M vertices
      writeWith(w.Get(), poly, temporary);
    }
    std::filesystem::rename(temporary, path);
  } catch (const std::exception& e) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw MeshIoError(path.string() + ": cannot write (" + e.what() + ")");
  }
}

}  // namespace ffdkit::scenes
