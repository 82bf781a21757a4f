#include "volume_mesh.h"

#include <cstdio>
#include <stdexcept>

#include "args.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"

namespace ffdkit::cli {

namespace fs = std::filesystem;

namespace {

meshio::OpenFoamReadOptions readOptionsOf(const ReadSettings& read) {
  meshio::OpenFoamReadOptions options;
  options.limits = read.limits;
  options.confinement = read.confinement;
  return options;
}

std::string pointsFormatText(const meshio::FoamPointsFile& file) {
  std::string text = file.layout.binary ? "binary" : "ascii";
  if (file.layout.binary) text += file.layout.scalarBytes == 8 ? " float64" : " float32";
  if (file.gzip) text += ", gzip";
  return text;
}

// The points of `mesh` deformed by every root lattice of the widget file `tool`.
Eigen::MatrixX3d deformedByTool(const fs::path& tool, const ReadSettings& read, const Eigen::MatrixX3d& points) {
  scenes::Scene scene;
  scene.widgets = readWidgetsFile(tool, read);
  scenes::SceneObject object;
  object.name = "mesh";
  object.mesh.points = points;
  scene.addObject(std::move(object));
  std::vector<scenes::Attachment> attachments;
  for (auto root : scene.widgets.roots()) attachments.push_back({root, {"mesh"}});
  scene.setAttachments(std::move(attachments));
  scenes::validateScene(scene);
  return scenes::deformScene(scene).at("mesh");
}

}  // namespace

bool isVolumeMesh(const fs::path& path) { return meshio::isOpenFoamMeshFolder(path); }

bool VolumeMeshInput::applies(const std::vector<std::string>& inputs) {
  std::size_t volumes = 0;
  for (const auto& input : inputs) volumes += isVolumeMesh(input) ? 1 : 0;
  if (volumes > 0 && inputs.size() > 1)
    throw UsageError("an OpenFOAM case is deformed on its own: give it as the only INPUT");
  return volumes == 1;
}

VolumeMeshInput::VolumeMeshInput(const fs::path& folder, const ReadSettings& read)
    : mesh_(meshio::readOpenFoamMesh(folder, readOptionsOf(read))) {}

Eigen::MatrixX3d VolumeMeshInput::takePoints() { return std::move(mesh_.points); }

meshio::CellQuality VolumeMeshInput::qualityBefore() const { return meshio::checkPolyMeshCells(mesh_.points, mesh_.cells); }

meshio::CellQuality VolumeMeshInput::check(const Eigen::MatrixX3d& deformed) const {
  return meshio::checkPolyMeshCells(deformed, mesh_.cells);
}

void VolumeMeshInput::write(const Eigen::MatrixX3d& deformed, const meshio::CellQuality& quality, const fs::path& output,
                            bool allowInverted, const Console& console) const {
  if (!quality.ok()) {
    if (!allowInverted)
      throw std::runtime_error("the deformed mesh has " + meshio::badCellsText(quality) + "; nothing written (" +
                               output.string() + " is unchanged; --allow-inverted writes it anyway)");
    console.warn("writing a mesh with " + meshio::badCellsText(quality) + " (--allow-inverted)");
  }
  meshio::writeOpenFoamMesh(mesh_, deformed, output);
}

void infoVolumeMesh(const fs::path& folder, const ReadSettings& read, bool quality, const fs::path* tool) {
  const meshio::OpenFoamMesh mesh = meshio::readOpenFoamMesh(folder, readOptionsOf(read));
  std::string patches;
  for (const auto& patch : mesh.patches)
    patches += (patches.empty() ? "" : ", ") + patch.name + " (" + patch.type + ", " + std::to_string(patch.faceCount) + " faces)";
  std::printf("OpenFOAM mesh: %s\n", mesh.polyMesh.string().c_str());
  std::printf("%lld points (%s), %lld faces (%lld internal), %lld cells, %zu patches: %s\n",
              static_cast<long long>(mesh.points.rows()), pointsFormatText(mesh.pointsFile).c_str(),
              static_cast<long long>(mesh.cells.faceCount()), static_cast<long long>(mesh.cells.neighbour.size()),
              static_cast<long long>(mesh.cells.cellCount), mesh.patches.size(), patches.c_str());
  if (!quality && tool == nullptr) return;
  const meshio::CellQuality before = meshio::checkPolyMeshCells(mesh.points, mesh.cells);
  std::printf("quality: %s\n", meshio::cellQualityText(before).c_str());
  if (!before.ok()) std::printf("bad cells: %s\n", meshio::badCellsText(before).c_str());
  if (tool == nullptr) return;
  const meshio::CellQuality after = meshio::checkPolyMeshCells(deformedByTool(*tool, read, mesh.points), mesh.cells);
  std::printf("quality deformed by %s: %s\n", tool->string().c_str(), meshio::cellQualityText(after).c_str());
  if (!after.ok()) std::printf("bad cells deformed: %s\n", meshio::badCellsText(after).c_str());
}

std::string checkVolumeMesh(const fs::path& folder, const ReadSettings& read) {
  const meshio::OpenFoamMesh mesh = meshio::readOpenFoamMesh(folder, readOptionsOf(read));
  const meshio::CellQuality quality = meshio::checkPolyMeshCells(mesh.points, mesh.cells);
  if (!quality.ok()) throw std::runtime_error(folder.string() + ": " + meshio::badCellsText(quality));
  return format("OpenFOAM mesh, %lld points, %lld cells", static_cast<long long>(mesh.points.rows()),
                static_cast<long long>(mesh.cells.cellCount));
}

}  // namespace ffdkit::cli
