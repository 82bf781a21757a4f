#include "ffdkit/meshio/element_cells.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

namespace ffdkit::meshio {

namespace {

using Vec = Eigen::Vector3d;

// Each corner with its three edges in right-handed order (the reference cell's Jacobian at the
// corner is positive): corner, then the three neighbours the edges lead to.
constexpr int kTetCorners[1][4] = {{0, 1, 2, 3}};
constexpr int kHexCorners[8][4] = {{0, 1, 3, 4}, {1, 2, 0, 5}, {2, 3, 1, 6}, {3, 0, 2, 7},
                                   {4, 7, 5, 0}, {5, 4, 6, 1}, {6, 5, 7, 2}, {7, 6, 4, 3}};
constexpr int kPrismCorners[6][4] = {{0, 1, 2, 3}, {1, 2, 0, 4}, {2, 0, 1, 5},
                                     {3, 5, 4, 0}, {4, 3, 5, 1}, {5, 4, 3, 2}};
// The apex of a pyramid has four edges and no single Jacobian: the four base corners' tetrahedra
// cover both diagonal splits of the pyramid.
constexpr int kPyramidCorners[4][4] = {{0, 1, 3, 4}, {1, 2, 0, 4}, {2, 3, 1, 4}, {3, 0, 2, 4}};
// Tetrahedra that split each cell exactly (volume).
constexpr int kHexTets[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
constexpr int kPrismTets[3][4] = {{0, 1, 2, 3}, {1, 2, 3, 4}, {2, 3, 4, 5}};
constexpr int kPyramidTets[2][4] = {{0, 1, 2, 4}, {0, 2, 3, 4}};

struct CellResult {
  double volume = 0.0;
  double minScaled = std::numeric_limits<double>::infinity();
  bool bad = false;
};

double scaled(double det, const Vec& a, const Vec& b, const Vec& c) {
  const double norms = a.norm() * b.norm() * c.norm();
  return norms > 0.0 ? det / norms : 0.0;
}

template <std::size_t N>
void corners3(const Vec* p, const int (&table)[N][4], CellResult& r) {
  for (const auto& t : table) {
    const Vec a = p[t[1]] - p[t[0]], b = p[t[2]] - p[t[0]], c = p[t[3]] - p[t[0]];
    const double det = a.dot(b.cross(c));
    r.minScaled = std::min(r.minScaled, scaled(det, a, b, c));
    if (!(det > 0.0)) r.bad = true;
  }
}

template <std::size_t N>
double tetVolume(const Vec* p, const int (&table)[N][4]) {
  double sum = 0.0;
  for (const auto& t : table) sum += (p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]]));
  return sum / 6.0;
}

// Corners of a polygon in the plane: the signed area of each corner's triangle.
void corners2(const Vec* p, int n, CellResult& r) {
  double area = 0.0;
  for (int i = 0; i < n; ++i) {
    const Vec& o = p[i];
    const Vec a = p[(i + 1) % n] - o, b = p[(i + n - 1) % n] - o;
    const double det = a.x() * b.y() - a.y() * b.x();
    const double norms = a.head<2>().norm() * b.head<2>().norm();
    r.minScaled = std::min(r.minScaled, norms > 0.0 ? det / norms : 0.0);
    if (!(det > 0.0)) r.bad = true;
    area += p[i].x() * p[(i + 1) % n].y() - p[(i + 1) % n].x() * p[i].y();
  }
  r.volume = area / 2.0;
}

CellResult checkCell(CellShape shape, const Vec* p) {
  CellResult r;
  switch (shape) {
    case CellShape::Triangle: corners2(p, 3, r); break;
    case CellShape::Quadrilateral: corners2(p, 4, r); break;
    case CellShape::Tetrahedron:
      corners3(p, kTetCorners, r);
      r.volume = tetVolume(p, kTetCorners);
      break;
    case CellShape::Hexahedron: {
      corners3(p, kHexCorners, r);
      // The centre: the trilinear map's derivatives there are the mean edge vectors per direction.
      const Vec du = (p[1] - p[0]) + (p[2] - p[3]) + (p[5] - p[4]) + (p[6] - p[7]);
      const Vec dv = (p[3] - p[0]) + (p[2] - p[1]) + (p[7] - p[4]) + (p[6] - p[5]);
      const Vec dw = (p[4] - p[0]) + (p[5] - p[1]) + (p[6] - p[2]) + (p[7] - p[3]);
      const double det = du.dot(dv.cross(dw));
      r.minScaled = std::min(r.minScaled, scaled(det, du, dv, dw));
      if (!(det > 0.0)) r.bad = true;
      r.volume = tetVolume(p, kHexTets);
      break;
    }
    case CellShape::Prism:
      corners3(p, kPrismCorners, r);
      r.volume = tetVolume(p, kPrismTets);
      break;
    case CellShape::Pyramid:
      corners3(p, kPyramidCorners, r);
      r.volume = tetVolume(p, kPyramidTets);
      break;
  }
  if (!(r.volume > 0.0)) r.bad = true;
  return r;
}

std::string shortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

}  // namespace

int cornerCount(CellShape shape) {
  switch (shape) {
    case CellShape::Triangle: return 3;
    case CellShape::Quadrilateral: return 4;
    case CellShape::Tetrahedron: return 4;
    case CellShape::Hexahedron: return 8;
    case CellShape::Prism: return 6;
    case CellShape::Pyramid: return 5;
  }
  return 0;
}

const char* cellShapeName(CellShape shape) {
  switch (shape) {
    case CellShape::Triangle: return "triangle";
    case CellShape::Quadrilateral: return "quadrilateral";
    case CellShape::Tetrahedron: return "tetrahedron";
    case CellShape::Hexahedron: return "hexahedron";
    case CellShape::Prism: return "prism";
    case CellShape::Pyramid: return "pyramid";
  }
  return "cell";
}

void ElementCells::add(CellShape shape, const std::int32_t* cornerIndices, std::int64_t id) {
  shapes.push_back(shape);
  cornerStarts.push_back(std::int64_t(corners.size()));
  corners.insert(corners.end(), cornerIndices, cornerIndices + cornerCount(shape));
  ids.push_back(id);
}

ElementQuality checkElementCells(const Eigen::MatrixX3d& points, const ElementCells& cells,
                                 const ElementQualityOptions& options) {
  ElementQuality q;
  q.cellCount = cells.cellCount();
  q.minVolume = std::numeric_limits<double>::infinity();
  q.maxVolume = -std::numeric_limits<double>::infinity();
  q.minScaledJacobian = std::numeric_limits<double>::infinity();
  Vec p[8];
  for (std::int64_t c = 0; c < cells.cellCount(); ++c) {
    const CellShape shape = cells.shapes[std::size_t(c)];
    const std::int32_t* corner = cells.corners.data() + cells.cornerStarts[std::size_t(c)];
    for (int k = 0; k < cornerCount(shape); ++k) {
      if (corner[k] < 0 || corner[k] >= points.rows())
        throw std::out_of_range("cell " + std::to_string(c) + ": point " + std::to_string(corner[k]) +
                                " is not one of the " + std::to_string(points.rows()) + " points");
      p[k] = points.row(corner[k]).transpose();
    }
    const CellResult r = checkCell(shape, p);
    q.minVolume = std::min(q.minVolume, r.volume);
    q.maxVolume = std::max(q.maxVolume, r.volume);
    q.totalVolume += r.volume;
    q.minScaledJacobian = std::min(q.minScaledJacobian, r.minScaled);
    if (r.bad) {
      ++q.badCells;
      if (q.firstBadCells.size() < options.listedIds)
        q.firstBadCells.push_back(cells.ids.empty() ? c : cells.ids[std::size_t(c)]);
    }
  }
  if (q.cellCount == 0) q.minVolume = q.maxVolume = q.minScaledJacobian = 0.0;
  return q;
}

std::string elementQualityText(const ElementQuality& q) {
  return "cells " + std::to_string(q.cellCount) + ", volume min " + shortNumber(q.minVolume) + " max " +
         shortNumber(q.maxVolume) + " (ratio " + shortNumber(q.volumeRatio()) + "), worst scaled Jacobian " +
         shortNumber(q.minScaledJacobian);
}

std::string badElementsText(const ElementQuality& q) {
  std::string ids;
  for (auto id : q.firstBadCells) ids += (ids.empty() ? "" : ", ") + std::to_string(id);
  return std::to_string(q.badCells) + (q.badCells == 1 ? " cell" : " cells") + " inverted or of zero volume (first: " +
         ids + ")";
}

}  // namespace ffdkit::meshio
