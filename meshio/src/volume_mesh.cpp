#include "ffdkit/meshio/volume_mesh.h"

#include <algorithm>
#include <cctype>

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/cell_quality.h"
#include "ffdkit/meshio/cgns.h"
#include "ffdkit/meshio/element_cells.h"
#include "ffdkit/meshio/gmsh.h"
#include "ffdkit/meshio/openfoam.h"
#include "ffdkit/meshio/read_failures.h"
#include "formats.h"
#include "volume_formats.h"

namespace ffdkit::meshio {

namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

VolumeMeshQuality fromElements(const ElementQuality& q) {
  VolumeMeshQuality r;
  r.checked = true;
  r.cellCount = q.cellCount;
  r.badCells = q.badCells;
  r.summary = elementQualityText(q);
  if (!q.ok()) r.badText = badElementsText(q);
  return r;
}

void writeBytes(const fs::path& output, const std::string& bytes, const VolumeMeshWriteOptions& options) {
  try {
    writeFileAtomically(output, bytes, options.durable);
  } catch (const MeshIoError&) {
    throw;
  } catch (const std::exception& e) {
    throw MeshIoError(e.what());
  }
}

std::string countsText(const std::map<int, std::int64_t>& byType) {
  std::string text;
  for (const auto& [type, count] : byType) {
    int nodes = 0, dim = 0;
    CellShape shape{};
    gmshElementType(type, nodes, dim, shape);
    text += (text.empty() ? "" : ", ") + std::to_string(count) + " of type " + std::to_string(type) + " (" +
            std::to_string(nodes) + " nodes" + (dim == 3 ? std::string(", ") + cellShapeName(shape) : std::string()) + ")";
  }
  return text;
}

class OpenFoamVolume final : public VolumeMesh {
 public:
  // The points are held once, by VolumeMesh (moved out of the OpenFOAM mesh first).
  explicit OpenFoamVolume(OpenFoamMesh mesh) : VolumeMesh(mesh.root, std::move(mesh.points)), mesh_(std::move(mesh)) {}
  VolumeMeshFormat format() const override { return VolumeMeshFormat::OpenFoam; }
  std::int64_t cellCount() const override { return mesh_.cells.cellCount; }
  VolumeMeshQuality check(const Eigen::MatrixX3d& points) const override {
    const CellQuality q = checkPolyMeshCells(points, mesh_.cells);
    VolumeMeshQuality r;
    r.checked = true;
    r.cellCount = q.cellCount;
    r.badCells = q.badCells;
    r.summary = cellQualityText(q);
    if (!q.ok()) r.badText = badCellsText(q);
    return r;
  }
  std::string summary() const override {
    std::string patches;
    for (const auto& patch : mesh_.patches)
      patches += (patches.empty() ? "" : ", ") + patch.name + " (" + patch.type + ", " + std::to_string(patch.faceCount) + " faces)";
    const FoamPointsFile& file = mesh_.pointsFile;
    std::string format = file.layout.binary ? "binary" : "ascii";
    if (file.layout.binary) format += file.layout.scalarBytes == 8 ? " float64" : " float32";
    if (file.gzip) format += ", gzip";
    return "OpenFOAM mesh: " + mesh_.polyMesh.string() + "\n" + std::to_string(pointCount()) + " points (" + format + "), " +
           std::to_string(mesh_.cells.faceCount()) + " faces (" + std::to_string(mesh_.cells.neighbour.size()) + " internal), " +
           std::to_string(mesh_.cells.cellCount) + " cells, " + std::to_string(mesh_.patches.size()) + " patches: " + patches;
  }
  void write(const Eigen::MatrixX3d& points, const fs::path& output, const VolumeMeshWriteOptions& options) const override {
    OpenFoamWriteOptions o;
    o.durable = options.durable;
    writeOpenFoamMesh(mesh_, points, output, o);
  }
  std::string bytesWith(const Eigen::MatrixX3d&) const override {
    throw MeshIoError(path().string() + ": an OpenFOAM mesh is a folder, not one file's bytes");
  }
  const OpenFoamMesh* openFoam() const override { return &mesh_; }

 private:
  OpenFoamMesh mesh_;
};

class GmshVolume final : public VolumeMesh {
 public:
  GmshVolume(fs::path path, GmshMesh mesh) : VolumeMesh(std::move(path), std::move(mesh.points)), mesh_(std::move(mesh)) {}
  VolumeMeshFormat format() const override { return VolumeMeshFormat::Gmsh; }
  std::int64_t cellCount() const override { return mesh_.cells.cellCount(); }
  VolumeMeshQuality check(const Eigen::MatrixX3d& points) const override {
    if (mesh_.cells.cellCount() == 0) {
      VolumeMeshQuality r;
      r.summary = "no 3D elements to check";
      return r;
    }
    return fromElements(checkElementCells(points, mesh_.cells));
  }
  std::string summary() const override {
    return std::string("Gmsh MSH 4.1 ") + (mesh_.file.binary ? "binary" : "ASCII") + ": " + path().string() + "\n" +
           std::to_string(pointCount()) + " nodes, " + std::to_string(mesh_.elementCount) + " elements (" +
           countsText(mesh_.elementsByType) + "), " + std::to_string(mesh_.cells.cellCount()) + " volume cells, " +
           std::to_string(mesh_.entityCount) + " entities, " + std::to_string(mesh_.physicalNameCount) + " physical names";
  }
  std::string bytesWith(const Eigen::MatrixX3d& points) const override { return gmshBytes(mesh_.file, points, path().string()); }
  void write(const Eigen::MatrixX3d& points, const fs::path& output, const VolumeMeshWriteOptions& options) const override {
    writeGmsh(mesh_, points, output, options.durable);
  }
  const ElementCells* elementCells() const override { return &mesh_.cells; }

 private:
  GmshMesh mesh_;
};

class TextVolume final : public VolumeMesh {
 public:
  TextVolume(fs::path path, VolumeMeshFormat format, detail::TextVolumeFile file)
      : VolumeMesh(std::move(path), std::move(file.points)), format_(format), file_(std::move(file)) {}
  VolumeMeshFormat format() const override { return format_; }
  std::int64_t cellCount() const override { return file_.hasCells ? file_.cells.cellCount() : 0; }
  VolumeMeshQuality check(const Eigen::MatrixX3d& points) const override {
    if (!file_.hasCells) {
      VolumeMeshQuality r;
      r.summary = std::string("cells not checked (") + volumeMeshFormatName(format_) + ": " +
                  (format_ == VolumeMeshFormat::Unv ? "no solid elements" : "points only") + ")";
      return r;
    }
    return fromElements(checkElementCells(points, file_.cells));
  }
  std::string summary() const override {
    return std::string(volumeMeshFormatName(format_)) + ": " + path().string() + "\n" + file_.summary;
  }
  std::string bytesWith(const Eigen::MatrixX3d& points) const override {
    return detail::replaceCoordinates(file_.bytes, file_.spans, points, path().string());
  }
  void write(const Eigen::MatrixX3d& points, const fs::path& output, const VolumeMeshWriteOptions& options) const override {
    writeBytes(output, detail::replaceCoordinates(file_.bytes, file_.spans, points, output.string()), options);
  }
  const ElementCells* elementCells() const override { return file_.hasCells ? &file_.cells : nullptr; }

 private:
  VolumeMeshFormat format_;
  detail::TextVolumeFile file_;
};

}  // namespace

const char* volumeMeshFormatName(VolumeMeshFormat format) {
  switch (format) {
    case VolumeMeshFormat::OpenFoam: return "OpenFOAM";
    case VolumeMeshFormat::Gmsh: return "Gmsh";
    case VolumeMeshFormat::Su2: return "SU2";
    case VolumeMeshFormat::Unv: return "UNV";
    case VolumeMeshFormat::Elmer: return "Elmer";
    case VolumeMeshFormat::LsDyna: return "LS-DYNA";
    case VolumeMeshFormat::Kratos: return "Kratos";
    case VolumeMeshFormat::Cgns: return "CGNS";
  }
  return "volume mesh";
}

std::optional<VolumeMeshFormat> volumeMeshFormatOf(const fs::path& path) {
  std::error_code error;
  if (fs::is_directory(path, error)) {
    if (isOpenFoamMeshFolder(path)) return VolumeMeshFormat::OpenFoam;
    return std::nullopt;
  }
  const std::string ext = lowerExtension(path);
  if (ext == ".msh") return VolumeMeshFormat::Gmsh;
  if (ext == ".su2") return VolumeMeshFormat::Su2;
  if (ext == ".unv") return VolumeMeshFormat::Unv;
  if (ext == ".nodes") return VolumeMeshFormat::Elmer;
  if (ext == ".k" || ext == ".key") return VolumeMeshFormat::LsDyna;
  if (ext == ".mdpa") return VolumeMeshFormat::Kratos;
  if (ext == ".cgns") return VolumeMeshFormat::Cgns;
  return std::nullopt;
}

std::unique_ptr<VolumeMesh> readVolumeMeshBytes(std::string bytes, VolumeMeshFormat format, const std::string& source,
                                                ReadBudget& budget) {
  switch (format) {
    case VolumeMeshFormat::OpenFoam:
      throw MeshIoError(source + ": an OpenFOAM mesh is read from its folder");
    case VolumeMeshFormat::Gmsh:
      return std::make_unique<GmshVolume>(source, readGmsh(std::move(bytes), source, budget));
    case VolumeMeshFormat::Su2:
      return std::make_unique<TextVolume>(source, format, detail::readSu2(std::move(bytes), source, budget));
    case VolumeMeshFormat::Unv:
      return std::make_unique<TextVolume>(source, format, detail::readUnv(std::move(bytes), source, budget));
    case VolumeMeshFormat::Elmer:
      return std::make_unique<TextVolume>(source, format, detail::readElmerNodes(std::move(bytes), source, budget));
    case VolumeMeshFormat::LsDyna:
      return std::make_unique<TextVolume>(source, format, detail::readLsDyna(std::move(bytes), source, budget));
    case VolumeMeshFormat::Kratos:
      return std::make_unique<TextVolume>(source, format, detail::readKratos(std::move(bytes), source, budget));
    case VolumeMeshFormat::Cgns:
      throw MeshIoError(source + ": a CGNS file is read from its path, through the CGNS library");
  }
  throw MeshIoError(source + ": unknown volume-mesh format");
}

std::unique_ptr<VolumeMesh> readVolumeMesh(const fs::path& path, const VolumeMeshReadOptions& options) {
  const auto format = volumeMeshFormatOf(path);
  if (!format)
    throw MeshIoError(path.string() +
                      ": not a volume mesh (an OpenFOAM case or polyMesh folder, or a .msh, .su2, .unv, .nodes, .k, .key "
                      "or .mdpa or .cgns file)");
  if (*format == VolumeMeshFormat::OpenFoam) {
    OpenFoamReadOptions o;
    o.limits = options.limits;
    o.confinement = options.confinement;
    return std::make_unique<OpenFoamVolume>(readOpenFoamMesh(path, o));
  }
  if (*format == VolumeMeshFormat::Cgns) return readCgnsVolumeMesh(path, options);
  ReadBudget budget(options.limits);
  const std::string source = path.string();
  return convertReadFailures<MeshIoError>(source, "the mesh", budget, [&] {
    std::string bytes;
    detail::readRegularFile(path, [&](std::size_t size) {
      budget.chargeBytes(size, 1, "the file's bytes");
      bytes.resize(size);
      return bytes.data();
    });
    return readVolumeMeshBytes(std::move(bytes), *format, source, budget);
  });
}

}  // namespace ffdkit::meshio
