// A CGNS zone behind the VolumeMesh interface (volume_mesh.h), so that the CLI and Python take
// .cgns files as they take the other volume meshes.
#include "ffdkit/meshio/cgns.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/meshio/volume_mesh.h"

namespace ffdkit::meshio {

namespace fs = std::filesystem;

namespace {

class CgnsVolume final : public VolumeMesh {
 public:
  explicit CgnsVolume(CgnsMesh mesh) : VolumeMesh(mesh.file, std::move(mesh.points)), mesh_(std::move(mesh)) {}
  VolumeMeshFormat format() const override { return VolumeMeshFormat::Cgns; }
  std::int64_t cellCount() const override { return mesh_.cells.cellCount(); }
  VolumeMeshQuality check(const Eigen::MatrixX3d& points) const override {
    VolumeMeshQuality r;
    if (mesh_.cells.cellCount() == 0) {
      r.summary = "no volume elements to check";
      return r;
    }
    const ElementQuality q = checkElementCells(points, mesh_.cells);
    r.checked = true;
    r.cellCount = q.cellCount;
    r.badCells = q.badCells;
    r.summary = elementQualityText(q);
    if (!q.ok()) r.badText = badElementsText(q);
    return r;
  }
  std::string summary() const override {
    return "CGNS: " + path().string() + ", zone " + mesh_.zoneName + "\n" + std::to_string(pointCount()) + " vertices, " +
           std::to_string(mesh_.cells.cellCount()) + " volume cells, " + std::to_string(mesh_.boundaryElements) +
           " boundary elements, " + std::to_string(mesh_.polyhedralElements) + " polyhedral elements (not checked)";
  }
  void write(const Eigen::MatrixX3d& points, const fs::path& output, const VolumeMeshWriteOptions& options) const override {
    CgnsWriteOptions o;
    o.durable = options.durable;
    writeCgnsMesh(mesh_, points, output, o);
  }
  std::string bytesWith(const Eigen::MatrixX3d&) const override {
    throw MeshIoError(path().string() + ": a CGNS file is written through the CGNS library, to a file, not as bytes");
  }
  const ElementCells* elementCells() const override { return &mesh_.cells; }

 private:
  CgnsMesh mesh_;
};

}  // namespace

std::unique_ptr<VolumeMesh> readCgnsVolumeMesh(const fs::path& path, const VolumeMeshReadOptions& options) {
  CgnsReadOptions o;
  o.limits = options.limits;
  return std::make_unique<CgnsVolume>(readCgnsMesh(path, o));
}

}  // namespace ffdkit::meshio
