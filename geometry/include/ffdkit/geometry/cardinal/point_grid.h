#pragma once

#include <filesystem>
#include <iosfwd>
#include <vector>

#include <Eigen/Core>

namespace ffdkit::geometry::cardinal {

/// A rectangular grid of 3D points: the data of a tensor-product surface.
/// Index (i, j): i runs along u (rows), j along v (columns). Row-major storage.
struct PointGrid {
  int rows = 0;  ///< number of points along u
  int cols = 0;  ///< number of points along v
  std::vector<Eigen::Vector3d> data;  ///< rows * cols points, data[i * cols + j]

  PointGrid() = default;
  /// A grid of rowCount x colCount points at the origin.
  PointGrid(int rowCount, int colCount)
      : rows(rowCount), cols(colCount),
        data(static_cast<std::size_t>(rowCount) * colCount, Eigen::Vector3d::Zero()) {}

  /// Point (i, j).
  Eigen::Vector3d& operator()(int i, int j) { return data[static_cast<std::size_t>(i) * cols + j]; }
  /// Point (i, j), read-only.
  const Eigen::Vector3d& operator()(int i, int j) const {
    return data[static_cast<std::size_t>(i) * cols + j];
  }
  /// Row i (fixed u index) as a cols x 3 matrix.
  Eigen::MatrixX3d row(int i) const;
  /// Column j (fixed v index) as a rows x 3 matrix.
  Eigen::MatrixX3d col(int j) const;
  /// Diagonal of the axis-aligned bounding box (0 for an empty grid).
  double boundingBoxDiagonal() const;
};

/// Reads a point grid in the plain text format
///   rows cols
///   x y z        (rows * cols lines, row-major: i outer, j inner)
/// Blank lines and lines starting with '#' are ignored.
/// @throws CardinalSplineError naming the line on malformed input.
PointGrid readPointGrid(std::istream& in, const std::string& sourceName = "<stream>");
/// @throws CardinalSplineError also when the file cannot be opened.
PointGrid readPointGrid(const std::filesystem::path& path);
/// Writes the format read by readPointGrid (full double precision).
void writePointGrid(std::ostream& out, const PointGrid& grid);
void writePointGrid(const std::filesystem::path& path, const PointGrid& grid);

}  // namespace ffdkit::geometry::cardinal
