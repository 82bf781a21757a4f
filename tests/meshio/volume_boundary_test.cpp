// The boundary surface of a volume mesh (volume_boundary.h): faces used by one cell, facing out.
// Checked by invariants that do not depend on the extraction: a closed surface, its area, and the
// volume it encloses (the divergence theorem) equal to the sum of the cells' volumes.
#include "ffdkit/meshio/volume_boundary.h"

#include <map>
#include <set>
#include <utility>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "ffdkit/meshio/element_cells.h"

namespace ffdkit::meshio {
namespace {

// The volume a closed, outward-facing triangle surface encloses: sum of signed tetrahedra with the origin.
double enclosedVolume(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles) {
  double volume = 0.0;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const Eigen::Vector3d a = points.row(triangles(t, 0)), b = points.row(triangles(t, 1)), c = points.row(triangles(t, 2));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

double area(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles) {
  double sum = 0.0;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const Eigen::Vector3d a = points.row(triangles(t, 0)), b = points.row(triangles(t, 1)), c = points.row(triangles(t, 2));
    sum += 0.5 * (b - a).cross(c - a).norm();
  }
  return sum;
}

// Every edge of a closed surface is used twice, once in each direction.
bool closedAndConsistent(const Eigen::MatrixX3i& triangles) {
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) ++directed[{triangles(t, k), triangles(t, (k + 1) % 3)}];
  for (const auto& [edge, count] : directed)
    if (count != 1 || directed.count({edge.second, edge.first}) == 0) return false;
  return true;
}

// An n x n x n block of unit cubes, each cut into cells of `shape` (hexahedra; six tetrahedra;
// two prisms), in Gmsh's corner orders.
struct Block {
  Eigen::MatrixX3d points;
  ElementCells cells;
};

Block block(int n, CellShape shape) {
  Block b;
  const int m = n + 1;
  b.points.resize(m * m * m, 3);
  const auto id = [m](int i, int j, int k) { return std::int32_t(i + m * (j + m * k)); };
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) b.points.row(id(i, j, k)) = Eigen::RowVector3d(i, j, k);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::int32_t c[8] = {id(i, j, k),         id(i + 1, j, k),         id(i + 1, j + 1, k),     id(i, j + 1, k),
                                   id(i, j, k + 1),     id(i + 1, j, k + 1),     id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        if (shape == CellShape::Hexahedron) {
          b.cells.add(shape, c, 0);
        } else if (shape == CellShape::Prism) {  // the bottom square's two triangles, extruded
          const std::int32_t p0[6] = {c[0], c[1], c[2], c[4], c[5], c[6]};
          const std::int32_t p1[6] = {c[0], c[2], c[3], c[4], c[6], c[7]};
          b.cells.add(shape, p0, 0);
          b.cells.add(shape, p1, 0);
        } else {  // six tetrahedra round the diagonal 0-6 (Kuhn's subdivision), each positive
          const int paths[6][2] = {{1, 2}, {2, 3}, {3, 7}, {7, 4}, {4, 5}, {5, 1}};
          for (const auto& path : paths) {
            const std::int32_t t[4] = {c[0], c[path[0]], c[path[1]], c[6]};
            const ElementCells one = [&] {
              ElementCells e;
              e.add(shape, t, 0);
              return e;
            }();
            if (checkElementCells(b.points, one).minVolume > 0) {
              b.cells.add(shape, t, 0);
            } else {
              const std::int32_t flipped[4] = {t[0], t[2], t[1], t[3]};
              b.cells.add(shape, flipped, 0);
            }
          }
        }
      }
  return b;
}

TEST(VolumeBoundary, BlocksOfEveryShapeGiveTheirClosedOutwardSurface) {
  for (const CellShape shape : {CellShape::Hexahedron, CellShape::Tetrahedron, CellShape::Prism}) {
    SCOPED_TRACE(cellShapeName(shape));
    const Block b = block(3, shape);
    ASSERT_TRUE(checkElementCells(b.points, b.cells).ok());
    const Eigen::MatrixX3i surface = boundaryTriangles(b.cells);
    EXPECT_TRUE(closedAndConsistent(surface));
    EXPECT_NEAR(area(b.points, surface), 6 * 9.0, 1e-12);           // six faces of 3 x 3
    EXPECT_NEAR(enclosedVolume(b.points, surface), 27.0, 1e-12);    // positive: the triangles face out
    // No interior point is on the surface: only the points of the block's faces (4^3 - 2^3 = 56).
    std::set<int> used(surface.data(), surface.data() + surface.size());
    EXPECT_EQ(used.size(), 56u);
  }
}

TEST(VolumeBoundary, APyramidOnACubeHidesTheFaceTheyShare) {
  Eigen::MatrixX3d points(9, 3);
  points << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1, 0.5, 0.5, 2;
  ElementCells cells;
  const std::int32_t hex[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const std::int32_t pyramid[5] = {4, 5, 6, 7, 8};
  cells.add(CellShape::Hexahedron, hex, 1);
  cells.add(CellShape::Pyramid, pyramid, 2);
  const Eigen::MatrixX3i surface = boundaryTriangles(cells);
  EXPECT_EQ(surface.rows(), 5 * 2 + 4);  // five square faces of the cube, four pyramid sides
  EXPECT_TRUE(closedAndConsistent(surface));
  EXPECT_NEAR(enclosedVolume(points, surface), 1.0 + 1.0 / 3.0, 1e-12);
}

TEST(VolumeBoundary, ATwoDimensionalMeshIsItsOwnSurface) {
  Eigen::MatrixX3d points(4, 3);
  points << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  ElementCells cells;
  const std::int32_t quad[4] = {0, 1, 2, 3};
  cells.add(CellShape::Quadrilateral, quad, 1);
  const Eigen::MatrixX3i surface = boundaryTriangles(cells);
  ASSERT_EQ(surface.rows(), 2);
  EXPECT_NEAR(area(points, surface), 1.0, 1e-15);
}

TEST(VolumeBoundary, OpenFoamBoundaryFacesAreItsPatches) {
  // Two unit cubes side by side along x: 10 boundary quads, 1 internal face (listed first).
  PolyMeshCells cells;
  Eigen::MatrixX3d points(12, 3);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) points.row(i + 3 * (j + 2 * k)) = Eigen::RowVector3d(i, j, k);
  const auto p = [](int i, int j, int k) { return std::int32_t(i + 3 * (j + 2 * k)); };
  std::vector<std::vector<std::int32_t>> faces;
  std::vector<std::int32_t> owner;
  faces.push_back({p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1)});  // internal, +x out of cell 0
  owner.push_back(0);
  cells.neighbour = {1};
  for (int c = 0; c < 2; ++c) {
    const int i = c;
    faces.push_back({p(i, 0, 0), p(i, 1, 0), p(i + 1, 1, 0), p(i + 1, 0, 0)});  // bottom, -z
    faces.push_back({p(i, 0, 1), p(i + 1, 0, 1), p(i + 1, 1, 1), p(i, 1, 1)});  // top, +z
    faces.push_back({p(i, 0, 0), p(i + 1, 0, 0), p(i + 1, 0, 1), p(i, 0, 1)});  // front, -y
    faces.push_back({p(i, 1, 0), p(i, 1, 1), p(i + 1, 1, 1), p(i + 1, 1, 0)});  // back, +y
    owner.insert(owner.end(), 4, c);
  }
  faces.push_back({p(0, 0, 0), p(0, 0, 1), p(0, 1, 1), p(0, 1, 0)});  // -x
  faces.push_back({p(2, 0, 0), p(2, 1, 0), p(2, 1, 1), p(2, 0, 1)});  // +x
  owner.push_back(0);
  owner.push_back(1);
  cells.faceStarts = {0};
  for (const auto& face : faces) {
    cells.faceVertices.insert(cells.faceVertices.end(), face.begin(), face.end());
    cells.faceStarts.push_back(std::int64_t(cells.faceVertices.size()));
  }
  cells.owner = owner;
  cells.cellCount = 2;
  const Eigen::MatrixX3i surface = boundaryTriangles(cells);
  EXPECT_EQ(surface.rows(), 2 * 10);
  EXPECT_TRUE(closedAndConsistent(surface));
  EXPECT_NEAR(enclosedVolume(points, surface), 2.0, 1e-12);
}

}  // namespace
}  // namespace ffdkit::meshio
