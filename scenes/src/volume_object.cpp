#include "ffdkit/scenes/volume_object.h"

#include "ffdkit/meshio/volume_boundary.h"
#include "ffdkit/scenes/up_axis.h"

namespace ffdkit::scenes {

namespace fs = std::filesystem;

std::optional<meshio::VolumeMeshFormat> volumeMeshFormatOf(const ObjectSource& source, const fs::path& baseDirectory) {
  const auto* file = std::get_if<MeshFileSource>(&source);
  if (file == nullptr) return std::nullopt;
  const fs::path named(file->path);
  return meshio::volumeMeshFormatOf(named.is_absolute() ? named : baseDirectory / named);
}

MeshData volumeObjectMesh(const fs::path& path, UpAxis up, meshio::ReadBudget& budget,
                          const meshio::PathConfinement& confinement) {
  meshio::VolumeMeshReadOptions options;
  options.limits = budget.limits();
  options.confinement = confinement;
  const std::unique_ptr<meshio::VolumeMesh> volume = meshio::readVolumeMesh(path, options);
  MeshData mesh = meshio::volumeMeshSurface(*volume);
  // What the scene keeps of it: the points and the surface's triangles.
  budget.chargeBytes(std::uint64_t(mesh.points.rows()), sizeof(double) * 3, "the points of the volume mesh " + path.string());
  budget.chargeBytes(std::uint64_t(mesh.triangles.rows()), sizeof(int) * 3,
                     "the boundary triangles of the volume mesh " + path.string());
  convertToZUp(mesh, up);
  return mesh;
}

VolumeObjectWriteResult writeVolumeObject(const SceneObject& object, const Eigen::MatrixX3d& deformed,
                                          const fs::path& baseDirectory, const fs::path& output,
                                          const VolumeObjectWriteOptions& options) {
  const auto* file = std::get_if<MeshFileSource>(&object.source);
  if (file == nullptr || !volumeMeshFormatOf(object.source, baseDirectory))
    throw std::invalid_argument("object '" + object.name + "' is not a volume mesh");
  const fs::path path = meshio::confinedPath(baseDirectory, file->path, "mesh file", options.confinement);
  meshio::VolumeMeshReadOptions readOptions;
  readOptions.limits = options.limits;
  readOptions.confinement = options.confinement;
  const std::unique_ptr<meshio::VolumeMesh> volume = meshio::readVolumeMesh(path, readOptions);
  // Pass-through writes the format read: the output's name must not promise another.
  const std::optional<meshio::VolumeMeshFormat> named = meshio::volumeMeshFormatOf(output);
  if (volume->format() == meshio::VolumeMeshFormat::OpenFoam ? named && *named != volume->format()
                                                             : named != volume->format())
    throw std::invalid_argument("object '" + object.name + "' is a " + meshio::volumeMeshFormatName(volume->format()) +
                                " mesh, written in its own format: " +
                                (volume->format() == meshio::VolumeMeshFormat::OpenFoam
                                     ? std::string("name a folder for the case, not ") + output.string()
                                     : output.string() + " should end in " + path.extension().string()));
  if (volume->pointCount() != deformed.rows())
    throw std::invalid_argument("object '" + object.name + "': " + path.string() + " holds " +
                                std::to_string(volume->pointCount()) + " points, the deformed object " +
                                std::to_string(deformed.rows()) + " (the file changed since the scene was read)");
  // Back to the file's axes: the scene turned them Z-up as it read them.
  const Eigen::MatrixX3d points =
      file->up == UpAxis::Z ? deformed : Eigen::MatrixX3d(deformed * upAxisRotation(file->up));
  VolumeObjectWriteResult result;
  result.format = volume->format();
  result.pointCount = points.rows();
  result.quality = volume->check(points);
  if (!result.quality.ok() && !options.allowInverted)
    throw InvertedCellsError("object '" + object.name + "': the deformed mesh has " + result.quality.badText +
                             "; nothing written (" + output.string() + " is unchanged)");
  meshio::VolumeMeshWriteOptions writeOptions;
  writeOptions.durable = options.durable;
  volume->write(points, output, writeOptions);
  return result;
}

}  // namespace ffdkit::scenes
