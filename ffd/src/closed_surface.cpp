#include "ffdkit/ffd/closed_surface.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace ffdkit::ffd {
namespace {

void checkRows(const Eigen::Ref<const Eigen::MatrixX3d>& points, const ClosedSurface& surface, const char* what) {
  if (points.rows() != surface.vertexCount())
    throw ConstraintError(std::string(what) + ": " + std::to_string(points.rows()) + " points for a surface over " +
                          std::to_string(surface.vertexCount()) + " vertices");
}

std::string edgeText(std::int64_t a, std::int64_t b) {
  return "(" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

}  // namespace

ClosedSurface::ClosedSurface(TriangleMatrix triangles, Eigen::Index vertexCount)
    : triangles_(std::move(triangles)), vertexCount_(vertexCount) {
  const Eigen::Index t = triangles_.rows();
  if (vertexCount < 0 || vertexCount > std::numeric_limits<int>::max())
    throw ConstraintError("closed surface: vertex count " + std::to_string(vertexCount) + " out of range");
  if (t == 0) throw ConstraintError("volume needs a closed surface: no triangles");
  // Directed edges (a, b) with the triangle they came from, sorted: each must be unique and have
  // its reverse.
  struct Edge {
    std::int64_t key;
    Eigen::Index triangle;
  };
  std::vector<Edge> edges;
  edges.reserve(static_cast<std::size_t>(3 * t));
  for (Eigen::Index r = 0; r < t; ++r) {
    for (int c = 0; c < 3; ++c) {
      const int v = triangles_(r, c);
      if (v < 0 || v >= vertexCount)
        throw ConstraintError("closed surface: triangle " + std::to_string(r) + " has vertex " + std::to_string(v) +
                              ", expected 0.." + std::to_string(vertexCount - 1));
    }
    const int a = triangles_(r, 0), b = triangles_(r, 1), c = triangles_(r, 2);
    if (a == b || b == c || a == c)
      throw ConstraintError("closed surface: triangle " + std::to_string(r) + " repeats a vertex " +
                            "(" + std::to_string(a) + ", " + std::to_string(b) + ", " + std::to_string(c) + ")");
    const int v[3] = {a, b, c};
    for (int k = 0; k < 3; ++k)
      edges.push_back({std::int64_t(v[k]) * vertexCount + v[(k + 1) % 3], r});
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.key < y.key; });
  for (std::size_t e = 0; e + 1 < edges.size(); ++e)
    if (edges[e].key == edges[e + 1].key) {
      const std::int64_t a = edges[e].key / vertexCount, b = edges[e].key % vertexCount;
      throw ConstraintError("volume needs a closed, consistently oriented surface: edge " + edgeText(a, b) +
                            " is used in the same direction by triangles " + std::to_string(edges[e].triangle) +
                            " and " + std::to_string(edges[e + 1].triangle));
    }
  for (const Edge& e : edges) {
    const std::int64_t a = e.key / vertexCount, b = e.key % vertexCount;
    const std::int64_t reverse = b * vertexCount + a;
    const auto it = std::lower_bound(edges.begin(), edges.end(), reverse,
                                     [](const Edge& x, std::int64_t k) { return x.key < k; });
    if (it == edges.end() || it->key != reverse)
      throw ConstraintError("volume needs a closed surface: edge " + edgeText(a, b) + " is used by 1 triangle (triangle " +
                            std::to_string(e.triangle) + "); the surface is open there");
  }
  // Vertex -> (b, c) pairs, CSR.
  offsets_.setZero(vertexCount + 1);
  for (Eigen::Index r = 0; r < t; ++r)
    for (int c = 0; c < 3; ++c) ++offsets_[triangles_(r, c) + 1];
  for (Eigen::Index v = 0; v < vertexCount; ++v) offsets_[v + 1] += offsets_[v];
  pairs_.resize(3 * t, 2);
  Eigen::VectorXi fill = offsets_.head(vertexCount);
  for (Eigen::Index r = 0; r < t; ++r)
    for (int c = 0; c < 3; ++c) {
      const int at = fill[triangles_(r, c)]++;
      pairs_(at, 0) = triangles_(r, (c + 1) % 3);
      pairs_(at, 1) = triangles_(r, (c + 2) % 3);
    }
}

double enclosedVolume(const Eigen::Ref<const Eigen::MatrixX3d>& points, const ClosedSurface& surface) {
  checkRows(points, surface, "enclosedVolume");
  const TriangleMatrix& f = surface.triangles();
  double sum = 0.0;
  for (Eigen::Index r = 0; r < f.rows(); ++r) {
    const Eigen::Vector3d a = points.row(f(r, 0)), b = points.row(f(r, 1)), c = points.row(f(r, 2));
    sum += a.dot(b.cross(c));
  }
  return sum / 6.0;
}

Eigen::Vector3d enclosedCentroid(const Eigen::Ref<const Eigen::MatrixX3d>& points, const ClosedSurface& surface) {
  checkRows(points, surface, "enclosedCentroid");
  const TriangleMatrix& f = surface.triangles();
  double volume6 = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (Eigen::Index r = 0; r < f.rows(); ++r) {
    const Eigen::Vector3d a = points.row(f(r, 0)), b = points.row(f(r, 1)), c = points.row(f(r, 2));
    const double det = a.dot(b.cross(c));
    volume6 += det;
    moment += det * (a + b + c);
  }
  if (volume6 == 0.0) throw ConstraintError("enclosedCentroid: the surface encloses zero volume");
  return moment / (4.0 * volume6);
}

}  // namespace ffdkit::ffd
