#include "ffdkit/meshio/volume_boundary.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace ffdkit::meshio {

namespace {

// The faces of each 3D shape by corner positions, ordered so that the right-hand normal points
// out of the cell: the reverse of "counter-clockwise seen from inside" (element_cells.h gives the
// corner orders; -1 ends a triangle).
using FaceCorners = std::array<int, 4>;
constexpr FaceCorners kTetFaces[] = {{0, 2, 1, -1}, {0, 1, 3, -1}, {1, 2, 3, -1}, {0, 3, 2, -1}};
constexpr FaceCorners kHexFaces[] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
constexpr FaceCorners kPrismFaces[] = {{0, 2, 1, -1}, {3, 4, 5, -1}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
constexpr FaceCorners kPyramidFaces[] = {{0, 3, 2, 1}, {0, 1, 4, -1}, {1, 2, 4, -1}, {2, 3, 4, -1}, {3, 0, 4, -1}};
constexpr FaceCorners kTriangleFace[] = {{0, 1, 2, -1}};
constexpr FaceCorners kQuadFace[] = {{0, 1, 2, 3}};

struct ShapeFaces {
  const FaceCorners* faces;
  int count;
};

ShapeFaces facesOf(CellShape shape) {
  switch (shape) {
    case CellShape::Tetrahedron: return {kTetFaces, 4};
    case CellShape::Hexahedron: return {kHexFaces, 6};
    case CellShape::Prism: return {kPrismFaces, 5};
    case CellShape::Pyramid: return {kPyramidFaces, 5};
    case CellShape::Triangle: return {kTriangleFace, 1};
    case CellShape::Quadrilateral: return {kQuadFace, 1};
  }
  return {nullptr, 0};
}

// A face of a cell: its point indices in outward order (-1 ends a triangle) and, to match it with
// the same face of the neighbouring cell, the same indices sorted.
struct Face {
  std::array<std::int32_t, 4> points;
  std::array<std::int32_t, 4> key;
};

void appendFan(std::vector<std::array<int, 3>>& triangles, const std::int32_t* points, std::int64_t count) {
  for (std::int64_t k = 1; k + 1 < count; ++k) triangles.push_back({points[0], points[k], points[k + 1]});
}

Eigen::MatrixX3i toMatrix(const std::vector<std::array<int, 3>>& triangles) {
  Eigen::MatrixX3i result(Eigen::Index(triangles.size()), 3);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) result(Eigen::Index(t), c) = triangles[t][std::size_t(c)];
  return result;
}

}  // namespace

Eigen::MatrixX3i boundaryTriangles(const ElementCells& cells) {
  std::vector<Face> faces;
  std::vector<std::array<int, 3>> triangles;
  for (std::int64_t c = 0; c < cells.cellCount(); ++c) {
    const CellShape shape = cells.shapes[std::size_t(c)];
    const std::int32_t* corners = cells.corners.data() + cells.cornerStarts[std::size_t(c)];
    const ShapeFaces shapeFaces = facesOf(shape);
    if (shape == CellShape::Triangle || shape == CellShape::Quadrilateral) {  // a 2D mesh: the cell is the surface
      appendFan(triangles, corners, cornerCount(shape));
      continue;
    }
    for (int f = 0; f < shapeFaces.count; ++f) {
      Face face{};
      for (int k = 0; k < 4; ++k) {
        const int corner = shapeFaces.faces[f][std::size_t(k)];
        face.points[std::size_t(k)] = corner < 0 ? -1 : corners[corner];
      }
      face.key = face.points;
      std::sort(face.key.begin(), face.key.end());  // a triangle's -1 sorts first: it never matches a quad
      faces.push_back(face);
    }
  }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.key < b.key; });
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j == i + 1) {
      const Face& face = faces[i];
      appendFan(triangles, face.points.data(), face.points[3] < 0 ? 3 : 4);
    }
    i = j;
  }
  return toMatrix(triangles);
}

Eigen::MatrixX3i boundaryTriangles(const PolyMeshCells& cells) {
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::int32_t> face;  // the face's points (a list read in place has no aligned pointer)
  for (std::int64_t f = std::int64_t(cells.neighbour.size()); f < cells.faceCount(); ++f) {
    const auto first = cells.faceVertices.begin() + cells.faceStarts[std::size_t(f)];
    face.assign(first, cells.faceVertices.begin() + cells.faceStarts[std::size_t(f) + 1]);
    appendFan(triangles, face.data(), std::int64_t(face.size()));
  }
  return toMatrix(triangles);
}

MeshData volumeMeshSurface(const VolumeMesh& mesh) {
  MeshData surface;
  surface.points = mesh.points();
  if (const OpenFoamMesh* foam = mesh.openFoam()) {
    surface.triangles = boundaryTriangles(foam->cells);
  } else if (const ElementCells* cells = mesh.elementCells()) {
    surface.triangles = boundaryTriangles(*cells);
  }
  return surface;
}

}  // namespace ffdkit::meshio
