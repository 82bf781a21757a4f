#include "ffdkit/interaction/point_selection.h"

#include <stdexcept>
#include <string>

namespace ffdkit::app {

PointSelection::PointSelection(widgets::WidgetId lattice, const Eigen::Vector3i& counts)
    : lattice_(lattice), counts_(counts) {
  if ((counts.array() < 1).any())
    throw std::invalid_argument("a point selection needs counts >= 1, got (" + std::to_string(counts.x()) + ", " +
                                std::to_string(counts.y()) + ", " + std::to_string(counts.z()) + ")");
  selected_.assign(static_cast<std::size_t>(counts.prod()), false);
}

void PointSelection::set(Eigen::Index index, bool on) {
  auto bit = selected_[static_cast<std::size_t>(index)];
  if (bit == on) return;
  bit = on;
  count_ += on ? 1 : -1;
  if (!on && active_ == index) active_.reset();
}

void PointSelection::pick(Eigen::Index index, SelectMode mode) {
  if (index < 0 || index >= pointCount())
    throw std::out_of_range("point " + std::to_string(index) + " outside the lattice's " + std::to_string(pointCount()) +
                            " points");
  switch (mode) {
    case SelectMode::Replace:
      selectNone();
      set(index, true);
      break;
    case SelectMode::Add: set(index, true); break;
    case SelectMode::Toggle: set(index, !contains(index)); break;
    case SelectMode::Subtract: set(index, false); break;
  }
  if (contains(index)) active_ = index;
}

void PointSelection::pickMany(const std::vector<Eigen::Index>& indices, SelectMode mode) {
  for (Eigen::Index i : indices)
    if (i < 0 || i >= pointCount())
      throw std::out_of_range("point " + std::to_string(i) + " outside the lattice's " + std::to_string(pointCount()) +
                              " points");
  if (mode == SelectMode::Replace) {
    const auto active = active_;
    selectNone();
    for (Eigen::Index i : indices) set(i, true);
    if (active && contains(*active)) active_ = active;
    return;
  }
  for (Eigen::Index i : indices) set(i, mode != SelectMode::Subtract);
}

void PointSelection::selectAll() {
  for (Eigen::Index i = 0; i < pointCount(); ++i) set(i, true);
}

void PointSelection::selectNone() {
  for (Eigen::Index i = 0; i < pointCount(); ++i) set(i, false);
  active_.reset();
}

void PointSelection::invert() {
  for (Eigen::Index i = 0; i < pointCount(); ++i) set(i, !contains(i));
}

void PointSelection::selectLinked(int axis, bool plane) {
  if (axis < 0 || axis > 2) throw std::invalid_argument("axis must be 0, 1 or 2, got " + std::to_string(axis));
  // Mark the rows (or planes) that hold a selected point, then select all of their points.
  const std::vector<Eigen::Index> seeds = indices();
  std::vector<bool> take(selected_.size(), false);
  for (Eigen::Index s : seeds) {
    const Eigen::Vector3i g = gridIndex(s);
    for (Eigen::Index i = 0; i < pointCount(); ++i) {
      const Eigen::Vector3i h = gridIndex(i);
      bool linked = true;
      if (plane) {
        linked = h[axis] == g[axis];
      } else {
        for (int a = 0; a < 3; ++a)
          if (a != axis && h[a] != g[a]) linked = false;
      }
      if (linked) take[static_cast<std::size_t>(i)] = true;
    }
  }
  for (Eigen::Index i = 0; i < pointCount(); ++i)
    if (take[static_cast<std::size_t>(i)]) set(i, true);
}

bool PointSelection::contains(Eigen::Index index) const {
  return index >= 0 && index < pointCount() && selected_[static_cast<std::size_t>(index)];
}

std::vector<Eigen::Index> PointSelection::indices() const {
  std::vector<Eigen::Index> out;
  out.reserve(static_cast<std::size_t>(count_));
  for (Eigen::Index i = 0; i < pointCount(); ++i)
    if (selected_[static_cast<std::size_t>(i)]) out.push_back(i);
  return out;
}

Eigen::Vector3i PointSelection::gridIndex(Eigen::Index flat) const {
  const auto l = static_cast<Eigen::Index>(counts_.x()), m = static_cast<Eigen::Index>(counts_.y());
  return {static_cast<int>(flat % l), static_cast<int>((flat / l) % m), static_cast<int>(flat / (l * m))};
}

Eigen::Index PointSelection::flatIndex(const Eigen::Vector3i& g) const {
  return g.x() + static_cast<Eigen::Index>(counts_.x()) * (g.y() + static_cast<Eigen::Index>(counts_.y()) * g.z());
}

std::vector<Eigen::Index> pointsInRectangle(const Eigen::Ref<const Eigen::MatrixX2d>& screen, const Eigen::Vector2d& a,
                                            const Eigen::Vector2d& b) {
  const Eigen::Vector2d lo = a.cwiseMin(b), hi = a.cwiseMax(b);
  std::vector<Eigen::Index> out;
  for (Eigen::Index i = 0; i < screen.rows(); ++i) {
    const Eigen::Vector2d p = screen.row(i).transpose();
    if ((p.array() >= lo.array()).all() && (p.array() <= hi.array()).all()) out.push_back(i);
  }
  return out;
}

}  // namespace ffdkit::app
