#include "ffdkit/interaction/soft_selection.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>

namespace ffdkit::app {

std::string_view falloffName(Falloff falloff) {
  switch (falloff) {
    case Falloff::Smooth: return "smooth";
    case Falloff::Sphere: return "sphere";
    case Falloff::Root: return "root";
    case Falloff::Linear: return "linear";
    case Falloff::Sharp: return "sharp";
    case Falloff::Constant: return "constant";
  }
  return "smooth";
}

double falloffWeight(Falloff falloff, double distance, double radius) {
  if (!(distance <= radius)) return 0.0;  // beyond the radius (or NaN)
  const double f = std::clamp((radius - distance) / radius, 0.0, 1.0);
  switch (falloff) {
    case Falloff::Smooth: return 3.0 * f * f - 2.0 * f * f * f;
    case Falloff::Sphere: return std::sqrt(std::max(0.0, 2.0 * f - f * f));
    case Falloff::Root: return std::sqrt(f);
    case Falloff::Linear: return f;
    case Falloff::Sharp: return f * f;
    case Falloff::Constant: return 1.0;
  }
  return f;
}

namespace {

void checkGrid(const Eigen::Ref<const Eigen::MatrixX3d>& points, const Eigen::Vector3i& counts,
               const std::vector<Eigen::Index>& selected) {
  if ((counts.array() < 1).any() || Eigen::Index(counts.prod()) != points.rows())
    throw std::invalid_argument("soft selection: " + std::to_string(points.rows()) + " points for a grid of " +
                                std::to_string(counts.x()) + " x " + std::to_string(counts.y()) + " x " +
                                std::to_string(counts.z()));
  for (Eigen::Index i : selected)
    if (i < 0 || i >= points.rows())
      throw std::invalid_argument("soft selection: point " + std::to_string(i) + " is not in the lattice (" +
                                  std::to_string(points.rows()) + " points)");
}

}  // namespace

Eigen::VectorXd selectionDistances(const Eigen::Ref<const Eigen::MatrixX3d>& points, const Eigen::Vector3i& counts,
                                   const std::vector<Eigen::Index>& selected, bool connected) {
  checkGrid(points, counts, selected);
  const Eigen::Index n = points.rows();
  Eigen::VectorXd distance = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  if (!connected) {
    for (Eigen::Index p = 0; p < n; ++p)
      for (Eigen::Index s : selected) distance(p) = std::min(distance(p), (points.row(p) - points.row(s)).norm());
    return distance;
  }
  // Dijkstra from every selected point at once over the grid's edges.
  using Entry = std::pair<double, Eigen::Index>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (Eigen::Index s : selected) {
    distance(s) = 0.0;
    queue.emplace(0.0, s);
  }
  const Eigen::Index l = counts.x(), m = counts.y();
  while (!queue.empty()) {
    const auto [d, p] = queue.top();
    queue.pop();
    if (d > distance(p)) continue;
    const Eigen::Index g[3] = {p % l, p / l % m, p / (l * m)};
    const Eigen::Index stride[3] = {1, l, l * m};
    for (int axis = 0; axis < 3; ++axis)
      for (int step : {-1, 1}) {
        const Eigen::Index next = g[axis] + step;
        if (next < 0 || next >= counts(axis)) continue;
        const Eigen::Index q = p + step * stride[axis];
        const double through = d + (points.row(p) - points.row(q)).norm();
        if (through < distance(q)) {
          distance(q) = through;
          queue.emplace(through, q);
        }
      }
  }
  return distance;
}

Eigen::VectorXd softSelectionWeights(const SoftSelection& soft, const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                     const Eigen::Vector3i& counts, const std::vector<Eigen::Index>& selected) {
  if (soft.enabled && !(soft.radius > 0.0 && std::isfinite(soft.radius)))
    throw std::invalid_argument("soft selection: the radius must be positive, got " + std::to_string(soft.radius));
  checkGrid(points, counts, selected);
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(points.rows());
  if (soft.enabled) {
    const Eigen::VectorXd distance = selectionDistances(points, counts, selected, soft.connectedOnly);
    for (Eigen::Index p = 0; p < points.rows(); ++p) weight(p) = falloffWeight(soft.falloff, distance(p), soft.radius);
  }
  for (Eigen::Index s : selected) weight(s) = 1.0;
  return weight;
}

Eigen::Affine3d partialMotion(const Eigen::Affine3d& motion, const Eigen::Vector3d& pivot, double weight) {
  const Eigen::Matrix3d L = motion.linear();
  const Eigen::Vector3d t = motion * pivot - pivot;
  Eigen::Matrix3d Lw;
  const bool rotation = (L.transpose() * L - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-12 &&
                        L.determinant() > 0.0;
  if (rotation) {
    const Eigen::AngleAxisd turn(L);
    Lw = Eigen::AngleAxisd(weight * turn.angle(), turn.axis()).toRotationMatrix();
  } else {
    Lw = Eigen::Matrix3d::Identity() + weight * (L - Eigen::Matrix3d::Identity());
  }
  Eigen::Affine3d out = Eigen::Affine3d::Identity();
  out.linear() = Lw;
  out.translation() = pivot - Lw * pivot + weight * t;
  return out;
}

}  // namespace ffdkit::app
