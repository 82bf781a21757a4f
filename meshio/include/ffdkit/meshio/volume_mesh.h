#pragma once
// Volume meshes of CFD and FEM solvers, one interface for every format: read a file (or an
// OpenFOAM case folder) to its points and what its cells need for the quality check, check the
// cells of moved points, and write the file back by pass-through: every byte but the point
// coordinates as it was read (docs/volume-meshes.md lists what each format keeps).
//
//   format        path                         cells checked
//   OpenFOAM      case or polyMesh folder      polyhedra (cell_quality.h)
//   Gmsh MSH 4.1  *.msh (ASCII, binary)        3D elements at their corners (element_cells.h)
//   SU2           *.su2 (2D, 3D)               its elements at their corners
//   UNV           *.unv (datasets 2411, 2412)  its solids at their corners (beams, shells kept)
//   Elmer         *.nodes (mesh.nodes)         none: points only
//   LS-DYNA       *.k, *.key (*NODE)           none: points only
//   Kratos        *.mdpa (Begin Nodes)         none: points only
//   CGNS          *.cgns (unstructured zone)   its elements at their corners (cgns.h)

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "ffdkit/meshio/path_confinement.h"
#include "ffdkit/meshio/read_limits.h"

namespace ffdkit::meshio {

struct OpenFoamMesh;
struct ElementCells;

/// The volume-mesh formats.
enum class VolumeMeshFormat { OpenFoam, Gmsh, Su2, Unv, Elmer, LsDyna, Kratos, Cgns };

/// "OpenFOAM", "Gmsh", "SU2", "UNV", "Elmer", "LS-DYNA", "Kratos", "CGNS".
const char* volumeMeshFormatName(VolumeMeshFormat format);

/// The format of `path`: a folder holding an OpenFOAM mesh, or a file by its extension (.msh,
/// .su2, .unv, .nodes, .k or .key, .mdpa, .cgns, any case); nullopt for anything else.
std::optional<VolumeMeshFormat> volumeMeshFormatOf(const std::filesystem::path& path);

/// What the cell check of a volume mesh found, in words every format shares.
struct VolumeMeshQuality {
  bool checked = false;        ///< false: the format's cells are not read (a points-only format)
  std::int64_t cellCount = 0;  ///< cells checked
  std::int64_t badCells = 0;   ///< inverted or zero-volume cells
  std::string summary;         ///< one line: volumes, worst Jacobian or pyramid, ... (or why not checked)
  std::string badText;         ///< "3 cells inverted or of zero volume (first: 4, 5, 13)..." when badCells > 0

  /// Whether no cell is inverted or of zero volume.
  bool ok() const { return badCells == 0; }
};

/// How a volume mesh is read.
struct VolumeMeshReadOptions {
  ReadLimits limits{};  ///< the read's budget
  /// An OpenFOAM case's files that are symbolic links leading outside its folder are refused
  /// unless allowOutside.
  PathConfinement confinement{};
};

/// How a volume mesh is written.
struct VolumeMeshWriteOptions {
  bool durable = true;  ///< flush to disk before the file (or folder) is renamed into place
};

/// A volume mesh as read: its points and what its writer needs to give the file back.
class VolumeMesh {
 public:
  virtual ~VolumeMesh() = default;

  /// The file's format.
  virtual VolumeMeshFormat format() const = 0;
  /// The file or folder read.
  const std::filesystem::path& path() const { return path_; }
  /// The points (#P x 3, one per row; a 2D mesh's z is 0), until takePoints.
  const Eigen::MatrixX3d& points() const { return points_; }
  /// The points, moved out: call once.
  Eigen::MatrixX3d takePoints() { return std::move(points_); }
  /// The number of points the file holds (also after takePoints).
  std::int64_t pointCount() const { return pointCount_; }
  /// Cells the check visits (0 for a points-only format).
  virtual std::int64_t cellCount() const = 0;
  /// Checks the cells with `points` (#P x 3) in place of the file's.
  virtual VolumeMeshQuality check(const Eigen::MatrixX3d& points) const = 0;
  /// What the file holds, one line or a few: "Gmsh MSH 4.1 binary: 1234 nodes, ...".
  virtual std::string summary() const = 0;
  /// Writes the file (or folder) read with `points` (#P x 3) as its coordinates to `output`,
  /// all or nothing. @throws MeshIoError naming the file and the step.
  virtual void write(const Eigen::MatrixX3d& points, const std::filesystem::path& output,
                     const VolumeMeshWriteOptions& options = {}) const = 0;
  /// The bytes write() puts in the file with `points` (#P x 3). @throws MeshIoError for a
  /// folder (OpenFOAM), a point count that differs, or a value the file cannot hold.
  virtual std::string bytesWith(const Eigen::MatrixX3d& points) const = 0;
  /// The OpenFOAM mesh behind this one, or null for the other formats.
  virtual const OpenFoamMesh* openFoam() const { return nullptr; }
  /// The cells of an element mesh (Gmsh, SU2, UNV with elements, CGNS) by their corners, or null
  /// (OpenFOAM: openFoam(); a points-only format).
  virtual const ElementCells* elementCells() const { return nullptr; }

 protected:
  /// A mesh read from `path` with its points (#P x 3).
  VolumeMesh(std::filesystem::path path, Eigen::MatrixX3d points)
      : path_(std::move(path)), points_(std::move(points)), pointCount_(points_.rows()) {}

 private:
  std::filesystem::path path_;
  Eigen::MatrixX3d points_;
  std::int64_t pointCount_ = 0;
};

/// Reads the volume mesh at `path` in the format volumeMeshFormatOf gives.
/// @throws MeshIoError naming the file (and line or byte offset) for a file that is not one,
///   that is malformed, or that is over the limits.
std::unique_ptr<VolumeMesh> readVolumeMesh(const std::filesystem::path& path, const VolumeMeshReadOptions& options = {});

/// Reads a volume-mesh file of `format` (not OpenFOAM, a folder) from its bytes; `source` names
/// it in messages and `path()`. @throws MeshIoError; a ReadLimitError from `budget` is let through.
std::unique_ptr<VolumeMesh> readVolumeMeshBytes(std::string bytes, VolumeMeshFormat format, const std::string& source,
                                                ReadBudget& budget);

}  // namespace ffdkit::meshio
