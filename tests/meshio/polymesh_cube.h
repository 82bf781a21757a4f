#pragma once
// The polyMesh of a unit cube of n^3 hexahedra in the order blockMesh writes it (points x fastest;
// internal faces in upper-triangular order: by owner, then +x, +y, +z; the boundary faces after
// them, pointing out of the cube), built in memory. The cell-check tests check it as it is; the
// OpenFOAM benchmark writes it as a binary case (bench/python/openfoam_cube.py writes the same
// case from Python, for runs without a build).

#include <cstdint>

#include <Eigen/Core>

#include "ffdkit/meshio/openfoam.h"

namespace ffdkit::meshio::test {

/// A cube's points (#P x 3, (n + 1)^3 of them) and cells (n^3).
struct PolyMeshCube {
  Eigen::MatrixX3d points;  ///< one per row, x fastest, then y, then z
  PolyMeshCells cells;      ///< faces, owner, neighbour
};

/// The unit cube [0, 1]^3 cut into n^3 hexahedra (n >= 1).
inline PolyMeshCube polyMeshCube(int n) {
  PolyMeshCube c;
  const int m = n + 1;
  c.points.resize(Eigen::Index(m) * m * m, 3);
  for (int k = 0, p = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i, ++p) c.points.row(p) << double(i) / n, double(j) / n, double(k) / n;
  auto point = [m](int i, int j, int k) { return std::int32_t(i + m * (j + m * k)); };
  auto cell = [n](int i, int j, int k) { return std::int32_t(i + n * (j + n * k)); };
  PolyMeshCells& cells = c.cells;
  const std::size_t faces = 3 * std::size_t(n) * n * (n + 1);
  cells.faceStarts.reserve(faces + 1);
  cells.faceVertices.reserve(4 * faces);
  cells.owner.reserve(faces);
  cells.neighbour.reserve(3 * std::size_t(n) * n * (n - 1));
  cells.faceStarts = {0};
  // Normals point from owner to neighbour (right-hand rule).
  auto face = [&](std::int32_t a, std::int32_t b, std::int32_t d, std::int32_t e, std::int32_t own) {
    cells.faceVertices.held().insert(cells.faceVertices.held().end(), {a, b, d, e});
    cells.faceStarts.push_back(std::int32_t(cells.faceVertices.size()));
    cells.owner.push_back(own);
  };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (i + 1 < n) {
          face(point(i + 1, j, k), point(i + 1, j + 1, k), point(i + 1, j + 1, k + 1), point(i + 1, j, k + 1), cell(i, j, k));
          cells.neighbour.push_back(cell(i + 1, j, k));
        }
        if (j + 1 < n) {
          face(point(i, j + 1, k), point(i, j + 1, k + 1), point(i + 1, j + 1, k + 1), point(i + 1, j + 1, k), cell(i, j, k));
          cells.neighbour.push_back(cell(i, j + 1, k));
        }
        if (k + 1 < n) {
          face(point(i, j, k + 1), point(i + 1, j, k + 1), point(i + 1, j + 1, k + 1), point(i, j + 1, k + 1), cell(i, j, k));
          cells.neighbour.push_back(cell(i, j, k + 1));
        }
      }
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      face(point(0, a, b), point(0, a, b + 1), point(0, a + 1, b + 1), point(0, a + 1, b), cell(0, a, b));
      face(point(n, a, b), point(n, a + 1, b), point(n, a + 1, b + 1), point(n, a, b + 1), cell(n - 1, a, b));
      face(point(a, 0, b), point(a + 1, 0, b), point(a + 1, 0, b + 1), point(a, 0, b + 1), cell(a, 0, b));
      face(point(a, n, b), point(a, n, b + 1), point(a + 1, n, b + 1), point(a + 1, n, b), cell(a, n - 1, b));
      face(point(a, b, 0), point(a, b + 1, 0), point(a + 1, b + 1, 0), point(a + 1, b, 0), cell(a, b, 0));
      face(point(a, b, n), point(a + 1, b, n), point(a + 1, b + 1, n), point(a, b + 1, n), cell(a, b, n - 1));
    }
  cells.cellCount = std::int64_t(n) * n * n;
  return c;
}

}  // namespace ffdkit::meshio::test
