#pragma once
// Volume meshes in the CLI: an OpenFOAM case or polyMesh folder, or a Gmsh, SU2, UNV, Elmer,
// LS-DYNA or Kratos file (meshio/volume_mesh.h), given to deform, info or validate
// (docs/volume-meshes.md). Its points are deformed like any INPUT's; before anything is written
// its cells are checked (the formats that have cells) and a mesh with inverted or zero-volume
// cells is refused unless --allow-inverted.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "console.h"
#include "ffdkit/ffd/deformer.h"
#include "ffdkit/meshio/volume_mesh.h"
#include "ffdkit/scenes/scene.h"
#include "read_options.h"

namespace ffdkit::cli {

/// Whether `path` is a volume mesh the CLI reads (meshio::volumeMeshFormatOf knows it).
bool isVolumeMesh(const std::filesystem::path& path);

/// A volume mesh given as deform's INPUT: read once, its points handed to the deformation, its
/// deformed points checked and written back by pass-through.
class VolumeMeshInput {
 public:
  /// Whether `inputs` is one volume mesh. @throws UsageError when a volume mesh comes with
  /// other INPUTs (a volume mesh is deformed on its own).
  static bool applies(const std::vector<std::string>& inputs);

  /// Reads the mesh. @throws meshio::MeshIoError.
  VolumeMeshInput(const std::filesystem::path& path, const ReadSettings& read);

  /// The points read (#P x 3), until takePoints.
  const Eigen::MatrixX3d& points() const { return mesh_->points(); }
  /// The points read, moved out: call once.
  Eigen::MatrixX3d takePoints() { return mesh_->takePoints(); }
  /// Cells the check visits (0 for a points-only format).
  std::int64_t cellCount() const { return mesh_->cellCount(); }

  /// The cell check of `deformed` (#P x 3) over the mesh's cells.
  meshio::VolumeMeshQuality check(const Eigen::MatrixX3d& deformed) const { return mesh_->check(deformed); }
  /// Writes the mesh with `deformed` as its points to `output` when `quality` (check() of the
  /// same points) passes, or when `allowInverted` (and says so on stderr).
  /// @throws std::runtime_error naming the bad cells when they fail and !allowInverted (nothing
  /// written), meshio::MeshIoError when the write fails (nothing written).
  void write(const Eigen::MatrixX3d& deformed, const meshio::VolumeMeshQuality& quality, const std::filesystem::path& output,
             bool allowInverted, const Console& console) const;

  /// check() of `deformed`, then write() to `output`, with the steps' times booked on `console`
  /// (`sayQuality`: the check's summary said first). An OpenFOAM case is written beside the
  /// check: to a hidden folder next to `output`, on a thread of its own while the check takes the
  /// cores, and renamed onto `output` only once the check has passed (or allowInverted); a refusal
  /// or a failure removes it, so nothing is written. --timings then books "check + write
  /// (overlapped)" and "write (after the check)" (the part of the write the check did not hide).
  /// @throws as write().
  meshio::VolumeMeshQuality checkAndWrite(const Eigen::MatrixX3d& deformed, const std::filesystem::path& output,
                                          bool allowInverted, bool sayQuality, Console& console) const;

  const meshio::VolumeMesh& mesh() const { return *mesh_; }

 private:
  std::unique_ptr<meshio::VolumeMesh> mesh_;
};

/// What deformVolumeInPlace did: the points its lattice left outside, or failed to embed.
struct InPlaceDeformCounts {
  Eigen::Index outsidePoints = 0;  ///< outside the lattice (its outside policy applied)
  Eigen::Index failedPoints = 0;   ///< not embedded, left unchanged
};

/// Whether `object` of `scene` is deformed by one lattice alone (a root lattice without child
/// lattices): then deformVolumeInPlace gives, bit for bit, the points scenes::SceneDeformer gives.
bool deformsByOneLattice(const scenes::Scene& scene, const std::string& object);

/// Deforms `points` (the object's, #P x 3) in place by its one lattice (deformsByOneLattice) with
/// ffd::deformInPlace: no embedding or second copy of a mesh of millions of points. Books the
/// console's "embed" and "deform" steps (wall and CPU time).
InPlaceDeformCounts deformVolumeInPlace(const scenes::Scene& scene, const std::string& object, Eigen::MatrixX3d& points,
                                        ffd::Precision precision, Console& console);

/// `info` of a volume mesh: what it holds, and with `quality` the cell check; with a `tool` (a
/// widget file) also the check after the tool deforms the mesh.
void infoVolumeMesh(const std::filesystem::path& path, const ReadSettings& read, bool quality,
                    const std::filesystem::path* tool);

/// `validate` of a volume mesh: reads it and checks its cells. Returns the summary line.
/// @throws std::runtime_error naming the bad cells.
std::string checkVolumeMesh(const std::filesystem::path& path, const ReadSettings& read);

}  // namespace ffdkit::cli
