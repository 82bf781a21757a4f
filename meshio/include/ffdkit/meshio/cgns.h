#pragma once
// CGNS unstructured meshes (CFD General Notation System, SIDS; read and written through the CGNS
// library, Debian's libcgns-dev, HDF5 or ADF files): the grid coordinates of one unstructured
// zone, read to deform them, and its element sections, read for the cell check; written by copying
// the file and overwriting the coordinate arrays in place, in their own data type, so that every
// other node of the file (sections, boundary conditions, families, solutions, descriptors) is the
// one read. Available when ffdkit is built with CGNS (CMake option FFDKIT_WITH_CGNS, on when the
// library is found); cgnsSupported() says whether it was.

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <Eigen/Core>

#include "ffdkit/meshio/element_cells.h"
#include "ffdkit/meshio/read_limits.h"
#include "ffdkit/meshio/volume_mesh.h"

namespace ffdkit::meshio {

/// Whether this build reads and writes CGNS (FFDKIT_WITH_CGNS).
bool cgnsSupported();

/// Whether `path` names a CGNS file by its extension (.cgns, any case).
bool isCgnsPath(const std::filesystem::path& path);

/// How a CGNS file is read.
struct CgnsReadOptions {
  ReadLimits limits{};  ///< the read's budget: points and connectivity are charged before they are read
  int base = 1;         ///< the CGNS base (1-based, as the library counts)
  int zone = 1;         ///< the unstructured zone of that base (1-based)
  /// true: the CGNS library reads the file in a child process (fork), so that a file that makes
  /// the library crash (its ADF reader overflows a buffer on some malformed files) or run away
  /// is a MeshIoError, not the end of this process; the zone comes back through a pipe.
  bool isolate = true;
  /// With isolate: the child's CPU time limit in seconds (0: none).
  double maxSeconds = 120.0;
};

/// A CGNS zone as read.
struct CgnsMesh {
  std::filesystem::path file;  ///< the file read
  int base = 1;                ///< its base (1-based)
  int zone = 1;                ///< its zone (1-based)
  std::string zoneName;        ///< the zone's name
  int cellDimension = 3;       ///< the base's cell dimension (2 or 3)
  int physicalDimension = 3;   ///< the base's physical dimension (the coordinates written: 2 or 3)
  Eigen::MatrixX3d points;     ///< #P x 3 (z = 0 when the physical dimension is 2)
  std::int64_t pointCount = 0; ///< #P, the zone's vertices (also once `points` is moved out)
  std::array<std::string, 3> coordinateNames;  ///< CoordinateX, CoordinateY, CoordinateZ (or as the file names them)
  std::array<bool, 3> singlePrecision{};       ///< a coordinate array stored as RealSingle
  /// The cells of the zone's sections of the base's cell dimension (tetrahedra, pyramids, prisms,
  /// hexahedra; triangles and quadrilaterals in 2D), by their corner nodes (a higher-order cell's
  /// corners come first in CGNS, its other nodes are not part of the check); ids are the CGNS
  /// element numbers. Faces, edges and nodes (boundary sections) are not cells.
  ElementCells cells;
  std::int64_t boundaryElements = 0;   ///< elements of a lower dimension (not checked)
  std::int64_t polyhedralElements = 0;  ///< NGON_n / NFACE_n elements (not checked)
};

/// Reads the coordinates and element sections of one unstructured zone. Every size the file
/// states is charged before it is read; element nodes are checked to lie in 1..#P.
/// @throws MeshIoError naming the file, the zone and the section: a structured zone, a missing
/// coordinate, a node out of range, an unknown element type, a non-finite coordinate, or a build
/// without CGNS.
CgnsMesh readCgnsMesh(const std::filesystem::path& path, const CgnsReadOptions& options = {});

/// Options of the CGNS writer.
struct CgnsWriteOptions {
  bool durable = true;  ///< flush the file to disk before it is renamed into place
  /// true: the CGNS library opens and rewrites the copy in a child process, as
  /// CgnsReadOptions::isolate reads; a crash there is a MeshIoError and nothing is written.
  bool isolate = true;
};

/// Writes `mesh`'s file with `points` (#P x 3) as the coordinates of its zone: a copy of the file
/// read, beside `output`, whose coordinate arrays are overwritten in place in their own type
/// (a RealSingle array refuses a value float32 cannot hold), then renamed onto `output`; all or
/// nothing. @throws MeshIoError naming the file and the step.
void writeCgnsMesh(const CgnsMesh& mesh, const Eigen::MatrixX3d& points, const std::filesystem::path& output,
                   const CgnsWriteOptions& options = {});

/// The CGNS file `path` (its first base's first zone) as a VolumeMesh: what readVolumeMesh
/// returns for a .cgns file. @throws MeshIoError as readCgnsMesh.
std::unique_ptr<VolumeMesh> readCgnsVolumeMesh(const std::filesystem::path& path, const VolumeMeshReadOptions& options);

}  // namespace ffdkit::meshio
