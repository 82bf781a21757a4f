// ffdkit.io's C++ half (ffdkit._ffdkit.io): volume meshes (meshio/volume_mesh.h) read to numpy
// points and written back by pass-through. python/ffdkit/io.py adds read_mesh / write_mesh and
// PyGeM's handler classes on top.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "ffdkit/meshio/volume_mesh.h"
#include "numpy_eigen.h"

namespace ffdkit::python {

namespace {

meshio::VolumeMeshReadOptions readOptions(std::optional<std::uint64_t> maxMemory, std::optional<std::uint64_t> maxPoints,
                                          bool allowOutside) {
  meshio::VolumeMeshReadOptions options;
  if (maxMemory) options.limits.maxMemoryBytes = *maxMemory;
  if (maxPoints) options.limits.maxPoints = *maxPoints;
  options.confinement.allowOutside = allowOutside;
  return options;
}

}  // namespace

void bindIo(py::module_& module) {
  py::enum_<meshio::VolumeMeshFormat>(module, "VolumeMeshFormat",
                                      R"doc(The volume-mesh formats ffdkit reads and writes back.

OpenFoam (a case or polyMesh folder), Gmsh (.msh 4.1), Su2 (.su2), Unv (.unv), Elmer
(mesh.nodes), LsDyna (.k, .key), Kratos (.mdpa).)doc")
      .value("OpenFoam", meshio::VolumeMeshFormat::OpenFoam)
      .value("Gmsh", meshio::VolumeMeshFormat::Gmsh)
      .value("Su2", meshio::VolumeMeshFormat::Su2)
      .value("Unv", meshio::VolumeMeshFormat::Unv)
      .value("Elmer", meshio::VolumeMeshFormat::Elmer)
      .value("LsDyna", meshio::VolumeMeshFormat::LsDyna)
      .value("Kratos", meshio::VolumeMeshFormat::Kratos);

  py::class_<meshio::VolumeMesh>(module, "VolumeMesh", R"doc(A volume mesh as read: its points and its file, for the writer.

Made by read_volume_mesh. write() gives the file back with new points: every byte but the
coordinates as it was read (for OpenFOAM, every file of the folder but points).)doc")
      .def_property_readonly("format", &meshio::VolumeMesh::format, "The file's format (VolumeMeshFormat).")
      .def_property_readonly("path", [](const meshio::VolumeMesh& mesh) { return mesh.path(); },
                             "The file or folder read.")
      .def_property_readonly(
          "points", [](py::object self) {
            const auto& mesh = self.cast<const meshio::VolumeMesh&>();
            return viewOf(mesh.points(), self, false);
          },
          "The points read: a read-only float64 array of shape (N, 3), a view kept alive by the mesh.")
      .def_property_readonly("cell_count", &meshio::VolumeMesh::cellCount,
                             "Cells the quality check visits (0 for the points-only formats).")
      .def("summary", &meshio::VolumeMesh::summary, R"doc(What the file holds, in a line or a few.

Counts of points, cells or elements by type, markers, patches or physical groups.)doc")
      .def(
          "check",
          [](const meshio::VolumeMesh& mesh, const py::object& points) {
            const PointsArg arg(points, "points");
            const meshio::VolumeMeshQuality q = mesh.check(Eigen::MatrixX3d(arg.ref()));
            py::dict result;
            result["checked"] = q.checked;
            result["cells"] = q.cellCount;
            result["bad_cells"] = q.badCells;
            result["ok"] = q.ok();
            result["summary"] = q.summary;
            result["bad_text"] = q.badText;
            return result;
          },
          py::arg("points"), R"doc(Checks the mesh's cells with `points` (N, 3) in place of the file's.

Returns a dict: checked (False for a points-only format), cells, bad_cells (inverted or of zero
volume), ok, summary (volumes and the worst Jacobian) and bad_text (the first bad cells).)doc")
      .def(
          "write",
          [](const meshio::VolumeMesh& mesh, const py::object& points, const std::filesystem::path& path, bool durable) {
            const PointsArg arg(points, "points");
            const Eigen::MatrixX3d copy(arg.ref());
            meshio::VolumeMeshWriteOptions options;
            options.durable = durable;
            py::gil_scoped_release release;
            mesh.write(copy, path, options);
          },
          py::arg("points"), py::arg("path"), py::arg("durable") = true,
          R"doc(Writes the mesh with `points` (N, 3, as many as read) as its coordinates to `path`.

All or nothing (a temporary file or folder renamed into place). Raises MeshIoError naming the
file for a point count that differs or a value a fixed-width field cannot hold.)doc")
      .def(
          "bytes_with",
          [](const meshio::VolumeMesh& mesh, const py::object& points) {
            const PointsArg arg(points, "points");
            return py::bytes(mesh.bytesWith(Eigen::MatrixX3d(arg.ref())));
          },
          py::arg("points"), R"doc(The bytes write() would put in the file, with `points` (N, 3).

Not for OpenFOAM (a folder): raises MeshIoError.)doc");

  module.def(
      "read_volume_mesh",
      [](const std::filesystem::path& path, std::optional<std::uint64_t> maxMemory, std::optional<std::uint64_t> maxPoints,
         bool allowOutside) {
        const auto options = readOptions(maxMemory, maxPoints, allowOutside);
        py::gil_scoped_release release;
        return meshio::readVolumeMesh(path, options);
      },
      py::arg("path"), py::arg("max_memory") = py::none(), py::arg("max_points") = py::none(),
      py::arg("allow_outside") = false, R"doc(Reads the volume mesh at `path` (its format from the extension or the folder).

An OpenFOAM case or polyMesh folder, or a .msh (Gmsh 4.1), .su2, .unv, .nodes (Elmer), .k/.key
(LS-DYNA) or .mdpa (Kratos) file. max_memory (bytes) and max_points bound what the file can make
the reader allocate. Raises MeshIoError naming the file and the line or byte offset.)doc");

  module.def(
      "volume_mesh_format",
      [](const std::filesystem::path& path) { return meshio::volumeMeshFormatOf(path); }, py::arg("path"),
      R"doc(The VolumeMeshFormat of `path` by its extension or folder layout.

None when it is not a volume mesh ffdkit reads.)doc");
}

}  // namespace ffdkit::python
