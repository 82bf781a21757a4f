#pragma once
// The cell check of a polyhedral (OpenFOAM) mesh, done as OpenFOAM's checkMesh does it, so that
// what ffdkit refuses is what checkMesh reports: face centres and area vectors from the triangles
// about each face's point average, cell centres and volumes from the face pyramids about a first
// centre estimate (the average of the cell's face centres), then each face's two pyramids about
// the cell centres, the non-orthogonality and the skewness of each face. OpenFOAM source,
// primitiveMeshFaceCentresAndAreas.C, primitiveMeshCellCentresAndVols.C, primitiveMeshCheck.C
// (checkCellVolumes, checkFacePyramids, checkFaceOrthogonality, checkFaceSkewness).

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/meshio/openfoam.h"

namespace ffdkit::meshio {

/// Options of the cell-quality check.
struct CellQualityOptions {
  /// How many ids of bad cells the result lists (the first ones, in cell order).
  std::size_t listedIds = 10;
};

/// What the check found. The counts are the two checkMesh reports for folded cells.
struct CellQuality {
  std::int64_t cellCount = 0;  ///< cells of the mesh
  std::int64_t faceCount = 0;  ///< faces of the mesh
  double minVolume = 0.0;    ///< the smallest cell volume (negative for an inverted cell)
  double maxVolume = 0.0;  ///< the largest cell volume
  double totalVolume = 0.0;  ///< sum of the cell volumes
  double minPyramidVolume = 0.0;     ///< the worst face pyramid, owner or neighbour side
  double maxNonOrthogonality = 0.0;  ///< degrees, over internal faces
  double meanNonOrthogonality = 0.0; ///< degrees: the angle of the mean cosine, as checkMesh's average
  double maxSkewness = 0.0;          ///< checkMesh's normalised skewness (its limit is 4)
  /// Cells of volume < 1e-300 (checkMesh: "Number of negative volume cells").
  std::int64_t negativeVolumeCells = 0;
  /// Face pyramids of volume < -1e-15 (checkMesh: "N faces are incorrectly oriented").
  std::int64_t incorrectlyOrientedFaces = 0;
  /// Cells that fail either test: a negative or zero volume, or an inverted face pyramid.
  std::int64_t badCells = 0;
  std::vector<std::int64_t> firstBadCells;  ///< their first ids (CellQualityOptions::listedIds)

  /// True when no cell is bad.
  bool ok() const { return badCells == 0; }
  /// min / max cell volume (0 when the largest is not positive).
  double volumeRatio() const { return maxVolume > 0.0 ? minVolume / maxVolume : 0.0; }
};

/// Checks every cell of `cells` over `points` (#P x 3, read in place). Runs on every core
/// (OpenMP); the result does not depend on the number of threads. The cells are visited in order,
/// in sweeps of consecutive cells, and each face's centre and area vector are computed once where
/// they can be (kept in a window of the last 2^18 faces computed, 13 MB per thread, until the
/// face's second cell is reached: in OpenFOAM's upper-triangular face order, every face but those
/// between two sweeps). Memory, for a mesh whose internal faces come in their owners' order and
/// whose bandwidth (the largest |neighbour - owner|) is small beside its cell count, as OpenFOAM
/// numbers them: a byte per cell; per thread, the cell-to-face lists of one sweep (8 bytes per
/// cell and 4 per cell-face pair of the sweep), the centres of its last cells (3 doubles per cell of
/// a window larger than the bandwidth) and the face window; the centres of the cells within the
/// bandwidth of each sweep's ends. Any other mesh: 4 bytes per cell and per cell-face pair, 3
/// doubles and a byte per cell of the mesh, and the face windows.
CellQuality checkPolyMeshCells(const Eigen::MatrixX3d& points, const PolyMeshCells& cells,
                               const CellQualityOptions& options = {});

/// One line each: "cells 27, volume min 0.037 max 0.037 (ratio 1), worst face pyramid 0.012,
/// non-orthogonality max 0 mean 0 deg, skewness max 1.3e-15".
std::string cellQualityText(const CellQuality& quality);
/// "3 cells inverted or of zero volume (first: 4, 5, 13); checkMesh counts 3 negative-volume
/// cells and 12 incorrectly oriented faces".
std::string badCellsText(const CellQuality& quality);

}  // namespace ffdkit::meshio
