#include "volume_mesh.h"

#include <cstdio>
#include <future>
#include <stdexcept>
#include <type_traits>

#include "args.h"
#include "ffdkit/ffd/in_place_deform.h"
#include "ffdkit/meshio/openfoam.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"

namespace ffdkit::cli {

namespace fs = std::filesystem;

namespace {

meshio::VolumeMeshReadOptions readOptionsOf(const ReadSettings& read) {
  meshio::VolumeMeshReadOptions options;
  options.limits = read.limits;
  options.confinement = read.confinement;
  return options;
}

// The points deformed by every root lattice of the widget file `tool`.
Eigen::MatrixX3d deformedByTool(const fs::path& tool, const ReadSettings& read, const Eigen::MatrixX3d& points) {
  scenes::Scene scene;
  scene.widgets = readWidgetsFile(tool, read);
  scenes::SceneObject object;
  object.name = "mesh";
  object.mesh.points = points;
  scene.addObject(std::move(object));
  // The one object under every root lattice. Attachment::objects names objects by name or, in
  // the scene API with object ids, by id: the generic lambda compiles for either.
  const auto attachAll = [&scene](auto attachment) {
    for (const auto& o : scene.objects()) {
      if constexpr (std::is_same_v<typename decltype(attachment.objects)::value_type, std::string>)
        attachment.objects.push_back(o.name);
      else
        attachment.objects.push_back(o.id);
    }
    return attachment;
  };
  std::vector<scenes::Attachment> attachments;
  for (auto root : scene.widgets.roots()) attachments.push_back(attachAll(scenes::Attachment{root, {}}));
  scene.setAttachments(std::move(attachments));
  scenes::validateScene(scene);
  return scenes::deformScene(scene).at("mesh");
}

}  // namespace

bool isVolumeMesh(const fs::path& path) { return meshio::volumeMeshFormatOf(path).has_value(); }

bool VolumeMeshInput::applies(const std::vector<std::string>& inputs) {
  std::size_t volumes = 0;
  for (const auto& input : inputs) volumes += isVolumeMesh(input) ? 1 : 0;
  if (volumes > 0 && inputs.size() > 1)
    throw UsageError("a volume mesh (an OpenFOAM case, a .msh, .su2, .unv, .nodes, .k or .mdpa file) is deformed on its "
                     "own: give it as the only INPUT");
  return volumes == 1;
}

VolumeMeshInput::VolumeMeshInput(const fs::path& path, const ReadSettings& read)
    : mesh_(meshio::readVolumeMesh(path, readOptionsOf(read))) {}

namespace {

// Refuses a mesh whose check found bad cells, unless allowInverted (then says so).
void refuseBadCells(const meshio::VolumeMeshQuality& quality, const fs::path& output, bool allowInverted,
                    const Console& console) {
  if (quality.ok()) return;
  if (!allowInverted)
    throw std::runtime_error("the deformed mesh has " + quality.badText + "; nothing written (" + output.string() +
                             " is unchanged; --allow-inverted writes it anyway)");
  console.warn("writing a mesh with " + quality.badText + " (--allow-inverted)");
}

}  // namespace

void VolumeMeshInput::write(const Eigen::MatrixX3d& deformed, const meshio::VolumeMeshQuality& quality,
                            const fs::path& output, bool allowInverted, const Console& console) const {
  refuseBadCells(quality, output, allowInverted, console);
  mesh_->write(deformed, output);
}

meshio::VolumeMeshQuality VolumeMeshInput::checkAndWrite(const Eigen::MatrixX3d& deformed, const fs::path& output,
                                                         bool allowInverted, bool sayQuality, Console& console) const {
  const std::string cells = std::to_string(cellCount()) + " cells";
  const meshio::OpenFoamMesh* foam = mesh_->openFoam();
  if (foam == nullptr) {
    console.begin("check", "checking " + cells);
    const meshio::VolumeMeshQuality quality = check(deformed);
    if (sayQuality) console.say("cell check after: " + quality.summary);
    console.begin("write", "writing " + output.string());
    write(deformed, quality, output, allowInverted, console);
    return quality;
  }
  // The write needs the cores little (the kernel copies the case's other files, the disk flushes
  // them): it runs on its own thread, one file after another, while the check takes the cores.
  console.begin("check + write (overlapped)", "checking " + cells + " and writing " + output.string() + " beside them");
  meshio::OpenFoamWriteOptions options;
  options.everyCore = false;
  // If the check throws, the future's destructor waits for the staging, and the staged folder it
  // returns is removed.
  std::future<meshio::StagedOpenFoamMesh> staging =
      std::async(std::launch::async, [&] { return meshio::stageOpenFoamMesh(*foam, deformed, output, options); });
  const meshio::VolumeMeshQuality quality = check(deformed);
  if (sayQuality) console.say("cell check after: " + quality.summary);
  if (!quality.ok() && !allowInverted) {
    // Refused: the staged folder (or the staging's own failure) is dropped, nothing is written.
    try {
      staging.get();
    } catch (const std::exception&) {
    }
    refuseBadCells(quality, output, allowInverted, console);
  }
  console.begin("write (after the check)", "writing " + output.string());
  meshio::StagedOpenFoamMesh staged = staging.get();
  refuseBadCells(quality, output, allowInverted, console);
  staged.commit();
  return quality;
}

bool deformsByOneLattice(const scenes::Scene& scene, const std::string& object) {
  const std::vector<widgets::WidgetId> stages = scene.stagesDeforming(object);
  return stages.size() == 1 && !scene.widgets.parentLattice(stages.front()) && scene.widgets.children(stages.front()).empty();
}

InPlaceDeformCounts deformVolumeInPlace(const scenes::Scene& scene, const std::string& object, Eigen::MatrixX3d& points,
                                        ffd::Precision precision, Console& console) {
  console.begin("deform", "embedding and deforming " + std::to_string(points.rows()) + " points in place");
  // The lattice as scenes::SceneDeformer's pipeline builds it for its one stage.
  const ffd::Lattice lattice = scene.widgets.ffdLattice(scene.stagesDeforming(object).front());
  ffd::InPlaceDeformOptions options;
  options.precision = precision;
  const ffd::InPlaceDeformResult result = ffd::deformInPlace(lattice, points, options);
  console.carve("embed", 1e3 * result.embedSeconds, 1e3 * result.embedCpuSeconds);
  console.end();
  return {result.outsidePoints, result.failedPoints};
}

void infoVolumeMesh(const fs::path& path, const ReadSettings& read, bool quality, const fs::path* tool) {
  const auto mesh = meshio::readVolumeMesh(path, readOptionsOf(read));
  std::printf("%s\n", mesh->summary().c_str());
  if (!quality && tool == nullptr) return;
  const meshio::VolumeMeshQuality before = mesh->check(mesh->points());
  std::printf("quality: %s\n", before.summary.c_str());
  if (!before.ok()) std::printf("bad cells: %s\n", before.badText.c_str());
  if (tool == nullptr) return;
  const meshio::VolumeMeshQuality after = mesh->check(deformedByTool(*tool, read, mesh->points()));
  std::printf("quality deformed by %s: %s\n", tool->string().c_str(), after.summary.c_str());
  if (!after.ok()) std::printf("bad cells deformed: %s\n", after.badText.c_str());
}

std::string checkVolumeMesh(const fs::path& path, const ReadSettings& read) {
  const auto mesh = meshio::readVolumeMesh(path, readOptionsOf(read));
  const meshio::VolumeMeshQuality quality = mesh->check(mesh->points());
  if (!quality.ok()) throw std::runtime_error(path.string() + ": " + quality.badText);
  std::string text = format("%s mesh, %lld points", meshio::volumeMeshFormatName(mesh->format()),
                            static_cast<long long>(mesh->pointCount()));
  if (quality.checked) text += format(", %lld cells", static_cast<long long>(quality.cellCount));
  return text;
}

}  // namespace ffdkit::cli
