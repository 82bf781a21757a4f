#pragma once
// The cells of an element mesh (Gmsh, SU2): tetrahedra, hexahedra, prisms and pyramids, first or
// higher order, stored by their corner nodes, and their check before a deformed mesh is written.
// A cell is inverted or degenerate when the Jacobian of its (linear) map from the reference cell
// is not positive at one of its corners (and, for a hexahedron, at its centre): the corner
// Jacobians of Knupp 2000 ("Achieving finite element mesh quality via optimization of the
// Jacobian matrix norm and associated quantities"). A higher-order cell is checked at its corner nodes;
// its edge and face nodes move with the deformation but are not part of the test. 2D meshes
// (triangles and quadrilaterals in the plane z = 0) are checked by their signed corner areas.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ffdkit::meshio {

/// The shape of a cell, in Gmsh's corner order (Gmsh reference manual, "Node ordering"): the
/// reference cell has a positive Jacobian.
enum class CellShape : std::uint8_t {
  Triangle,     ///< 3 corners, counter-clockwise seen from +z
  Quadrilateral,///< 4 corners, counter-clockwise seen from +z
  Tetrahedron,  ///< 4 corners: (0, 1, 2) counter-clockwise seen from 3
  Hexahedron,   ///< 8 corners: bottom 0-3 counter-clockwise seen from the top 4-7 above them
  Prism,        ///< 6 corners: bottom 0-2 counter-clockwise seen from the top 3-5 above them
  Pyramid,      ///< 5 corners: base 0-3 counter-clockwise seen from the apex 4
};

/// Corners of a shape (3, 4, 4, 8, 6, 5).
int cornerCount(CellShape shape);
/// "tetrahedron", "hexahedron", ...
const char* cellShapeName(CellShape shape);

/// The cells of a mesh to check: cell c has shape shapes[c] and the point indices
/// corners[cornerStarts[c] .. cornerStarts[c] + cornerCount(shapes[c])).
struct ElementCells {
  std::vector<CellShape> shapes;           ///< #C shapes
  std::vector<std::int64_t> cornerStarts;  ///< #C offsets into corners
  std::vector<std::int32_t> corners;       ///< point indices (rows of the points)
  /// The id a message gives cell c (the file's element tag); empty: c itself.
  std::vector<std::int64_t> ids;

  /// The number of cells.
  std::int64_t cellCount() const { return std::int64_t(shapes.size()); }
  /// Appends a cell: its shape and cornerCount(shape) point indices.
  void add(CellShape shape, const std::int32_t* cornerIndices, std::int64_t id);
};

/// Options of the element check.
struct ElementQualityOptions {
  /// How many ids of bad cells the result lists (the first ones, in cell order).
  std::size_t listedIds = 10;
};

/// What the element check found.
struct ElementQuality {
  std::int64_t cellCount = 0;     ///< cells checked
  double minVolume = 0.0;         ///< the smallest cell volume (area in 2D); negative when inverted
  double maxVolume = 0.0;         ///< the largest
  double totalVolume = 0.0;       ///< their sum
  /// The smallest scaled Jacobian over all corners: det(J) / (|e1| |e2| |e3|) of the corner's
  /// edge vectors, 1 for a right angle, <= 0 for an inverted or degenerate corner.
  double minScaledJacobian = 0.0;
  std::int64_t badCells = 0;                ///< cells with a non-positive corner Jacobian or volume
  std::vector<std::int64_t> firstBadCells;  ///< their first ids (ElementCells::ids when given)

  /// Whether no cell is inverted or of zero volume.
  bool ok() const { return badCells == 0; }
  /// min / max cell volume (0 when the largest is not positive).
  double volumeRatio() const { return maxVolume > 0.0 ? minVolume / maxVolume : 0.0; }
};

/// Checks every cell of `cells` over `points` (#P x 3). 2D shapes use x and y only.
/// @throws std::out_of_range when a corner index is not a row of `points`.
ElementQuality checkElementCells(const Eigen::MatrixX3d& points, const ElementCells& cells,
                                 const ElementQualityOptions& options = {});

/// "cells 1200, volume min 1.2e-05 max 4.1e-05 (ratio 0.29), worst scaled Jacobian 0.31".
std::string elementQualityText(const ElementQuality& quality);
/// "3 cells inverted or of zero volume (first: 4, 5, 13)".
std::string badElementsText(const ElementQuality& quality);

}  // namespace ffdkit::meshio
