#include "lod_proxy.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include <Eigen/Geometry>

namespace ffdkit::app {
namespace {

ProxyMesh wholeMesh(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles) {
  ProxyMesh proxy;
  proxy.vertices.resize(static_cast<std::size_t>(points.rows()));
  std::iota(proxy.vertices.begin(), proxy.vertices.end(), Eigen::Index{0});
  proxy.triangles = triangles;
  return proxy;
}

}  // namespace

ProxyMesh clusterVertices(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles, Eigen::Index targetVertices) {
  const Eigen::Index n = points.rows();
  const Eigen::Index m = triangles.rows();
  if (m == 0 || n <= std::max<Eigen::Index>(targetVertices, 1)) return wholeMesh(points, triangles);
  // The proxy's triangles are keyed by their three proxy indices packed in 21 bits each.
  const Eigen::Index target = std::min<Eigen::Index>(targetVertices, Eigen::Index{1} << 20);

  double area = 0.0;
#pragma omp parallel for reduction(+ : area) schedule(static)
  for (Eigen::Index t = 0; t < m; ++t) {
    const Eigen::Vector3d a = points.row(triangles(t, 0));
    area += 0.5 * (points.row(triangles(t, 1)).transpose() - a).cross(points.row(triangles(t, 2)).transpose() - a).norm();
  }
  const Eigen::Vector3d lo = points.colwise().minCoeff();
  const Eigen::Vector3d hi = points.colwise().maxCoeff();
  if (!(area > 0.0) || !std::isfinite(area) || !lo.allFinite() || !hi.allFinite()) return wholeMesh(points, triangles);
  double cell = std::sqrt(area / static_cast<double>(target));
  // Cells per axis, their product kept well inside 64 bits.
  Eigen::Array3d cells;
  for (;;) {
    cells = ((hi - lo).array() / cell).floor() + 1.0;
    if (cells.prod() < 1e18) break;
    cell *= 2.0;
  }
  const auto cellOf = [&](Eigen::Index v) {
    std::uint64_t key = 0;
    for (int axis = 2; axis >= 0; --axis) {
      const double at = std::clamp(std::floor((points(v, axis) - lo[axis]) / cell), 0.0, cells[axis] - 1.0);
      key = key * static_cast<std::uint64_t>(cells[axis]) + static_cast<std::uint64_t>(at);
    }
    return key;
  };

  // The stand-in of each vertex: the first vertex (in mesh order) of its cell.
  std::vector<std::uint64_t> keys(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
  for (Eigen::Index v = 0; v < n; ++v) keys[static_cast<std::size_t>(v)] = cellOf(v);
  std::unordered_map<std::uint64_t, int> first;
  first.reserve(static_cast<std::size_t>(2 * target));
  std::vector<int> standIn(static_cast<std::size_t>(n));
  for (Eigen::Index v = 0; v < n; ++v)
    standIn[static_cast<std::size_t>(v)] = first.try_emplace(keys[static_cast<std::size_t>(v)], static_cast<int>(v)).first->second;
  keys = {};

  // The triangles over three distinct cells, once each.
  std::vector<Eigen::Vector3i> kept;
  kept.reserve(static_cast<std::size_t>(3 * target));
  std::unordered_set<std::uint64_t> seen;
  seen.reserve(static_cast<std::size_t>(3 * target));
  std::unordered_map<int, int> proxyIndex;  // stand-in -> dense index in order of first use (for the key)
  proxyIndex.reserve(static_cast<std::size_t>(2 * target));
  for (Eigen::Index t = 0; t < m; ++t) {
    const int a = standIn[static_cast<std::size_t>(triangles(t, 0))];
    const int b = standIn[static_cast<std::size_t>(triangles(t, 1))];
    const int c = standIn[static_cast<std::size_t>(triangles(t, 2))];
    if (a == b || b == c || a == c) continue;
    std::uint64_t k[3];
    int i = 0;
    for (int s : {a, b, c}) k[i++] = static_cast<std::uint64_t>(proxyIndex.try_emplace(s, int(proxyIndex.size())).first->second);
    std::sort(k, k + 3);
    if (k[2] >= (std::uint64_t{1} << 21)) continue;  // beyond the key's range: not reached for targets <= 2^20
    if (!seen.insert((k[0] << 42) | (k[1] << 21) | k[2]).second) continue;
    kept.emplace_back(a, b, c);
  }

  ProxyMesh proxy;
  proxy.vertices.reserve(proxyIndex.size());
  for (const auto& [standInVertex, unused] : proxyIndex) proxy.vertices.push_back(standInVertex);
  std::sort(proxy.vertices.begin(), proxy.vertices.end());
  std::unordered_map<int, int> dense;
  dense.reserve(proxy.vertices.size());
  for (std::size_t i = 0; i < proxy.vertices.size(); ++i) dense.emplace(static_cast<int>(proxy.vertices[i]), static_cast<int>(i));
  proxy.triangles.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t t = 0; t < kept.size(); ++t)
    for (int corner = 0; corner < 3; ++corner) proxy.triangles(static_cast<Eigen::Index>(t), corner) = dense.at(kept[t][corner]);
  return proxy;
}

}  // namespace ffdkit::app
