// Internal to ffd/: the tabulated inverse of the rest map, for Newton's first guesses
// (rest_solver.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "vector_clones.h"

namespace ffdkit::ffd::detail {

// The inverse map uvw(q) at the nodes of a kCells^3 grid over the rest points' bounding box,
// interpolated trilinearly: it starts Newton about 1e-4 from the solution instead of 1e-2 (the
// affine fit), which saves about one of the four evaluations per point. The nodes are solved by
// the caller (RestSolver::solveGridNode, independent, in any order and on any thread) and handed
// over with set(); before that, interpolate() finds nothing.
class InverseGrid {
 public:
  static constexpr int kCells = 16;
  static constexpr int kNodesPerAxis = kCells + 1;
  static constexpr std::int64_t kNodes = std::int64_t(kNodesPerAxis) * kNodesPerAxis * kNodesPerAxis;

  InverseGrid() = default;
  // The grid over the box [min, max] (local coordinates).
  InverseGrid(const Eigen::Vector3d& min, const Eigen::Vector3d& max)
      : min_(min), scale_(Eigen::Vector3d::Constant(kCells).cwiseQuotient((max - min).cwiseMax(1e-300))) {}

  // The point q of node `node` (i fastest).
  Eigen::Vector3d nodePoint(std::int64_t node) const {
    const std::int64_t i = node % kNodesPerAxis, j = node / kNodesPerAxis % kNodesPerAxis,
                       k = node / (kNodesPerAxis * kNodesPerAxis);
    return min_ + Eigen::Vector3d(double(i), double(j), double(k)).cwiseQuotient(scale_);
  }

  // The solved nodes: uvw per node, and whether its solve converged.
  void set(std::vector<Eigen::Vector3d> uvw, std::vector<char> valid) {
    uvw_ = std::move(uvw);
    valid_ = std::move(valid);
  }
  bool empty() const { return uvw_.empty(); }

  // Trilinear interpolation of the tabulated inverse map; false outside the grid or next to a
  // node that did not converge.
  FFDKIT_INLINE bool interpolate(const Eigen::Vector3d& q, Eigen::Vector3d& uvw) const {
    if (uvw_.empty()) return false;
    int i[3];
    double f[3];
    for (int a = 0; a < 3; ++a) {
      const double t = (q[a] - min_[a]) * scale_[a];
      if (!(t >= 0.0 && t < kCells)) return false;
      i[a] = static_cast<int>(t);
      f[a] = t - i[a];
    }
    const std::size_t base = i[0] + kNodesPerAxis * (i[1] + static_cast<std::size_t>(kNodesPerAxis) * i[2]);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int corner = 0; corner < 8; ++corner) {
      const int dx = corner & 1, dy = (corner >> 1) & 1, dz = corner >> 2;
      const std::size_t node = base + dx + kNodesPerAxis * (dy + static_cast<std::size_t>(kNodesPerAxis) * dz);
      if (!valid_[node]) return false;
      const double w = (dx ? f[0] : 1.0 - f[0]) * (dy ? f[1] : 1.0 - f[1]) * (dz ? f[2] : 1.0 - f[2]);
      sum += w * uvw_[node];
    }
    uvw = sum;
    return true;
  }

 private:
  Eigen::Vector3d min_ = Eigen::Vector3d::Zero(), scale_ = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> uvw_;
  std::vector<char> valid_;
};

}  // namespace ffdkit::ffd::detail
