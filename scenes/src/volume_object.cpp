#include "ffdkit/scenes/volume_object.h"

#include <fcntl.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/mesh_data.h"
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

namespace {

// A volume object read again and checked, ready to be written.
struct PreparedVolume {
  std::unique_ptr<meshio::VolumeMesh> volume;
  Eigen::MatrixX3d points;  // in the file's axes
  VolumeObjectWriteResult result;
};

// Reads `object`'s file again, checks that `output` is named for its format and that the file has
// as many points as `deformed`, turns the points back to the file's axes and checks the cells.
// @throws as writeVolumeObject (InvertedCellsError unless options.allowInverted).
PreparedVolume prepareVolumeObject(const SceneObject& object, const Eigen::MatrixX3d& deformed, const fs::path& baseDirectory,
                                   const fs::path& output, const VolumeObjectWriteOptions& options) {
  const auto* file = std::get_if<MeshFileSource>(&object.source);
  if (file == nullptr || !volumeMeshFormatOf(object.source, baseDirectory))
    throw std::invalid_argument("object '" + object.name + "' is not a volume mesh");
  const fs::path path = meshio::confinedPath(baseDirectory, file->path, "mesh file", options.confinement);
  meshio::VolumeMeshReadOptions readOptions;
  readOptions.limits = options.limits;
  readOptions.confinement = options.confinement;
  PreparedVolume prepared;
  prepared.volume = meshio::readVolumeMesh(path, readOptions);
  const meshio::VolumeMesh& volume = *prepared.volume;
  // Pass-through writes the format read: the output's name must not promise another.
  const std::optional<meshio::VolumeMeshFormat> named = meshio::volumeMeshFormatOf(output);
  if (volume.format() == meshio::VolumeMeshFormat::OpenFoam ? named && *named != volume.format()
                                                            : named != volume.format())
    throw std::invalid_argument("object '" + object.name + "' is a " + meshio::volumeMeshFormatName(volume.format()) +
                                " mesh, written in its own format: " +
                                (volume.format() == meshio::VolumeMeshFormat::OpenFoam
                                     ? std::string("name a folder for the case, not ") + output.string()
                                     : output.string() + " should end in " + path.extension().string()));
  if (volume.pointCount() != deformed.rows())
    throw std::invalid_argument("object '" + object.name + "': " + path.string() + " holds " +
                                std::to_string(volume.pointCount()) + " points, the deformed object " +
                                std::to_string(deformed.rows()) + " (the file changed since the scene was read)");
  // Back to the file's axes: the scene turned them Z-up as it read them.
  prepared.points = file->up == UpAxis::Z ? deformed : Eigen::MatrixX3d(deformed * upAxisRotation(file->up));
  prepared.result.format = volume.format();
  prepared.result.pointCount = prepared.points.rows();
  prepared.result.quality = volume.check(prepared.points);
  if (!prepared.result.quality.ok() && !options.allowInverted)
    throw InvertedCellsError("object '" + object.name + "': the deformed mesh has " + prepared.result.quality.badText +
                             "; nothing written (" + output.string() + " is unchanged)");
  return prepared;
}

// Renames the written `staged` file or folder onto `output`; an existing folder is exchanged
// with it (renameat2(RENAME_EXCHANGE)) and then removed.
void moveIntoPlace(const fs::path& staged, const fs::path& output) {
  std::error_code ec;
  if (fs::is_directory(staged) && fs::is_directory(output, ec)) {
    if (::renameat2(AT_FDCWD, staged.c_str(), AT_FDCWD, output.c_str(), RENAME_EXCHANGE) != 0)
      throw meshio::MeshIoError(output.string() + ": cannot put the written case in place (" + std::strerror(errno) + ")");
    fs::remove_all(staged, ec);  // the old case
    return;
  }
  fs::rename(staged, output);
}

}  // namespace

VolumeObjectWriteResult writeVolumeObject(const SceneObject& object, const Eigen::MatrixX3d& deformed,
                                          const fs::path& baseDirectory, const fs::path& output,
                                          const VolumeObjectWriteOptions& options) {
  const PreparedVolume prepared = prepareVolumeObject(object, deformed, baseDirectory, output, options);
  meshio::VolumeMeshWriteOptions writeOptions;
  writeOptions.durable = options.durable;
  prepared.volume->write(prepared.points, output, writeOptions);
  return prepared.result;
}

std::vector<VolumeObjectWriteResult> writeVolumeObjects(const std::vector<VolumeObjectOutput>& outputs,
                                                        const fs::path& baseDirectory,
                                                        const VolumeObjectWriteOptions& options) {
  // First every object is read again and checked: a refusal leaves every output as it was.
  std::vector<PreparedVolume> prepared;
  prepared.reserve(outputs.size());
  for (const VolumeObjectOutput& out : outputs)
    prepared.push_back(prepareVolumeObject(*out.object, *out.deformed, baseDirectory, out.path, options));
  // Then each is written beside its output; a failure removes what this run wrote.
  std::vector<fs::path> staged;
  const auto removeStaged = [&] {
    std::error_code ignored;
    for (const fs::path& path : staged) fs::remove_all(path, ignored);
  };
  meshio::VolumeMeshWriteOptions writeOptions;
  writeOptions.durable = options.durable;
  try {
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      staged.push_back(meshio::temporaryPathBeside(outputs[i].path));
      prepared[i].volume->write(prepared[i].points, staged.back(), writeOptions);
    }
  } catch (...) {
    removeStaged();
    throw;
  }
  // All written: each is renamed into place (a rename within its folder).
  std::vector<VolumeObjectWriteResult> results;
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    try {
      moveIntoPlace(staged[i], outputs[i].path);
    } catch (const std::exception& e) {
      std::string placed;
      for (std::size_t k = 0; k < i; ++k) placed += (k ? ", " : "") + outputs[k].path.string();
      staged.erase(staged.begin(), staged.begin() + std::ptrdiff_t(i));
      removeStaged();
      throw meshio::MeshIoError(outputs[i].path.string() + ": cannot put the written mesh in place (" + e.what() + ")" +
                                (placed.empty() ? std::string() : "; already in place: " + placed));
    }
    results.push_back(prepared[i].result);
  }
  return results;
}

}  // namespace ffdkit::scenes
