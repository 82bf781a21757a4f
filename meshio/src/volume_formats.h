#pragma once
// The text volume-mesh formats whose files come back by replacing their coordinates' text (SU2,
// UNV, Elmer, LS-DYNA, Kratos): each reader returns the bytes, where the coordinates are and
// what the cell check needs. Private to meshio: volume_mesh.cpp wraps them as VolumeMeshes.

#include <string>

#include <Eigen/Core>

#include "ffdkit/meshio/element_cells.h"
#include "ffdkit/meshio/read_limits.h"
#include "text_coordinates.h"

namespace ffdkit::meshio::detail {

/// A text volume-mesh file as read.
struct TextVolumeFile {
  std::string bytes;        ///< the whole file
  CoordinateSpans spans;    ///< where each point's coordinates are
  Eigen::MatrixX3d points;  ///< #P x 3 (z = 0 for a 2D file)
  bool hasCells = false;    ///< the cells were read (SU2)
  ElementCells cells;       ///< the cells to check
  std::string summary;      ///< what the file holds, for info
};

/// SU2 native mesh (SU2 documentation, "Mesh File"): NDIME, NELEM, NPOIN and NMARK sections,
/// one zone. Elements' VTK types 5, 9 (2D), 10, 12, 13, 14 (3D).
TextVolumeFile readSu2(std::string bytes, const std::string& source, ReadBudget& budget);
/// I-DEAS universal file: dataset 2411's node coordinates (other datasets kept as they are).
TextVolumeFile readUnv(std::string bytes, const std::string& source, ReadBudget& budget);
/// Elmer's mesh.nodes: "node partition x y z" per line.
TextVolumeFile readElmerNodes(std::string bytes, const std::string& source, ReadBudget& budget);
/// LS-DYNA keyword file: the *NODE cards (fixed columns I8, 3 x E16.0, or comma-separated).
TextVolumeFile readLsDyna(std::string bytes, const std::string& source, ReadBudget& budget);
/// Kratos .mdpa: the "Begin Nodes" ... "End Nodes" blocks ("id x y z" per line).
TextVolumeFile readKratos(std::string bytes, const std::string& source, ReadBudget& budget);

}  // namespace ffdkit::meshio::detail
