#include "ffdkit/render/curvature_comb.h"

#include <cmath>

#include <Eigen/Geometry>

namespace ffdkit::app {

CurvatureComb curvatureComb(const Eigen::MatrixX3d& points, bool closed, double scale) {
  const Eigen::Index n = points.rows();
  CurvatureComb comb;
  const Eigen::Index first = closed ? 0 : 1;
  const Eigen::Index last = closed ? n : n - 1;  // exclusive
  const Eigen::Index count = (n >= 3 && last > first) ? last - first : 0;
  comb.bases.resize(count, 3);
  comb.tips.resize(count, 3);
  comb.curvature.resize(count);
  for (Eigen::Index k = 0; k < count; ++k) {
    const Eigen::Index i = first + k;
    const Eigen::Vector3d b = points.row(i).transpose();
    const Eigen::Vector3d a = points.row((i + n - 1) % n).transpose();
    const Eigen::Vector3d c = points.row((i + 1) % n).transpose();
    // The circle through a, b, c: centre relative to b is
    // ((|u|^2 v - |v|^2 u) x (u x v)) / (2 |u x v|^2) with u = a - b, v = c - b.
    const Eigen::Vector3d u = a - b, v = c - b;
    const Eigen::Vector3d w = u.cross(v);
    const double w2 = w.squaredNorm();
    const double lengths = u.norm() * v.norm() * (c - a).norm();
    double kappa = 0.0;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    // Straight (or repeated points): no circle, zero curvature.
    if (lengths > 0.0 && w2 > 1e-24 * lengths * lengths) {
      kappa = 2.0 * std::sqrt(w2) / lengths;
      const Eigen::Vector3d centre = (u.squaredNorm() * v - v.squaredNorm() * u).cross(w) / (2.0 * w2);
      normal = centre.normalized();
    }
    comb.bases.row(k) = b.transpose();
    comb.tips.row(k) = (b + scale * kappa * normal).transpose();
    comb.curvature(k) = kappa;
  }
  return comb;
}

std::vector<std::vector<int>> segmentChains(const Eigen::MatrixX2i& segments, Eigen::Index pointCount) {
  // Adjacency of at most two neighbours per point is the common case; branching points end chains.
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(pointCount));
  for (Eigen::Index s = 0; s < segments.rows(); ++s) {
    const int a = segments(s, 0), b = segments(s, 1);
    if (a < 0 || b < 0 || a >= pointCount || b >= pointCount || a == b) continue;
    neighbours[static_cast<std::size_t>(a)].push_back(b);
    neighbours[static_cast<std::size_t>(b)].push_back(a);
  }
  std::vector<std::vector<char>> used(static_cast<std::size_t>(pointCount));
  for (std::size_t i = 0; i < neighbours.size(); ++i) used[i].assign(neighbours[i].size(), 0);
  auto markUsed = [&](int from, int to) {
    auto& list = neighbours[static_cast<std::size_t>(from)];
    for (std::size_t k = 0; k < list.size(); ++k)
      if (list[k] == to && !used[static_cast<std::size_t>(from)][k]) {
        used[static_cast<std::size_t>(from)][k] = 1;
        return;
      }
  };
  auto nextFree = [&](int from) -> int {
    const auto& list = neighbours[static_cast<std::size_t>(from)];
    for (std::size_t k = 0; k < list.size(); ++k)
      if (!used[static_cast<std::size_t>(from)][k]) return list[k];
    return -1;
  };
  std::vector<std::vector<int>> chains;
  auto walk = [&](int start) {
    std::vector<int> chain{start};
    int here = start;
    for (int next = nextFree(here); next >= 0; next = nextFree(here)) {
      markUsed(here, next);
      markUsed(next, here);
      chain.push_back(next);
      here = next;
      if (neighbours[static_cast<std::size_t>(here)].size() != 2) break;  // an end or a branch
    }
    if (chain.size() >= 2) chains.push_back(std::move(chain));
  };
  // Open chains first, from their ends (and branch points); then what is left are cycles.
  for (int i = 0; i < static_cast<int>(pointCount); ++i)
    if (neighbours[static_cast<std::size_t>(i)].size() != 2)
      while (nextFree(i) >= 0) walk(i);
  for (int i = 0; i < static_cast<int>(pointCount); ++i)
    while (nextFree(i) >= 0) walk(i);
  return chains;
}

}  // namespace ffdkit::app
