#pragma once
// A volume mesh as a scene object: a mesh object whose file is a solver's volume mesh (an
// OpenFOAM case or polyMesh folder, Gmsh .msh, SU2, UNV, Elmer, LS-DYNA, Kratos or CGNS;
// meshio/volume_mesh.h). Its MeshData holds every point of the mesh and, as triangles, the
// mesh's boundary surface (meshio/volume_boundary.h): the view draws the surface, the lattices
// deform every point. Written back, the whole mesh is the file read with the deformed points
// (pass-through), after its cells are checked (docs/volume-meshes.md).

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/meshio/path_confinement.h"
#include "ffdkit/meshio/read_limits.h"
#include "ffdkit/meshio/volume_mesh.h"
#include "ffdkit/scenes/scene.h"

namespace ffdkit::scenes {

/// The volume-mesh format of a mesh object's file (relative paths resolve against
/// `baseDirectory`), or nullopt when the object is not a volume mesh (a surface mesh file, a
/// primitive, a generator).
std::optional<meshio::VolumeMeshFormat> volumeMeshFormatOf(const ObjectSource& source,
                                                           const std::filesystem::path& baseDirectory);

/// The points and boundary surface of the volume mesh at `path` (resolved and confined by the
/// caller), turned from the file's `up` axis to Z-up: every point of the mesh, in the file's order,
/// and the boundary triangles (meshio::volumeMeshSurface). The read has `budget`'s limits, and
/// what it keeps is charged to `budget`. @throws meshio::MeshIoError, meshio::ReadLimitError.
MeshData volumeObjectMesh(const std::filesystem::path& path, UpAxis up, meshio::ReadBudget& budget,
                          const meshio::PathConfinement& confinement);

/// A deformed volume mesh that is not written because cells are inverted or of zero volume.
class InvertedCellsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// How a scene's volume mesh is written.
struct VolumeObjectWriteOptions {
  bool allowInverted = false;           ///< write even when cells are inverted (the result says how many)
  meshio::PathConfinement confinement;  ///< the rule for the object's path (as the scene was read)
  meshio::ReadLimits limits;            ///< the budget of reading the file again
  bool durable = true;                  ///< flush to disk before the file (or folder) is renamed into place
};

/// What writing a scene's volume mesh did.
struct VolumeObjectWriteResult {
  meshio::VolumeMeshFormat format = meshio::VolumeMeshFormat::Gmsh;  ///< the format written
  std::int64_t pointCount = 0;        ///< points written
  meshio::VolumeMeshQuality quality;  ///< the cell check of the deformed points
};

/// Writes the volume mesh of `object` with `deformed` (#P x 3, world Z-up coordinates, one row
/// per point of the mesh: SceneDeformer::points of the object) to `output`: the file is read
/// again from its source, the points are turned back to the file's up axis, the cells are
/// checked, and the file is written by pass-through (every byte but the coordinates as read),
/// all or nothing. `baseDirectory` is the folder the scene's relative paths resolve against.
/// @throws InvertedCellsError naming the bad cells (nothing written) unless
///   options.allowInverted; std::invalid_argument when the object is not a volume mesh, when
///   `output` names another format (a file's extension must be its format's: .msh for Gmsh, ...;
///   an OpenFOAM case is a folder), or when `deformed` has another point count than the file (it
///   changed since the scene was read);
///   meshio::MeshIoError when the file cannot be read or written (nothing written).
VolumeObjectWriteResult writeVolumeObject(const SceneObject& object, const Eigen::MatrixX3d& deformed,
                                          const std::filesystem::path& baseDirectory,
                                          const std::filesystem::path& output,
                                          const VolumeObjectWriteOptions& options = {});

/// One volume object of a scene to write with its deformed points.
struct VolumeObjectOutput {
  const SceneObject* object = nullptr;         ///< a volume-mesh object of the scene
  const Eigen::MatrixX3d* deformed = nullptr;  ///< its deformed points (#P x 3, world Z-up), as for writeVolumeObject
  std::filesystem::path path;                  ///< where its mesh goes (named for its format)
};

/// Writes several volume objects all or nothing: first every object's file is read again and its
/// cells checked as writeVolumeObject does (a refusal of any leaves every output as it was); then
/// each mesh is written beside its output (a hidden temporary file or folder) and, once all are
/// written, each is renamed into place. A failed write removes what this run wrote: no output
/// changes. Returns the results in the order of `outputs`.
/// @throws what writeVolumeObject throws, for the first object that fails; meshio::MeshIoError when
///   a rename into place fails after others succeeded (it names the outputs already in place).
std::vector<VolumeObjectWriteResult> writeVolumeObjects(const std::vector<VolumeObjectOutput>& outputs,
                                                        const std::filesystem::path& baseDirectory,
                                                        const VolumeObjectWriteOptions& options = {});

}  // namespace ffdkit::scenes
