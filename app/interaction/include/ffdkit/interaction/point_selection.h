#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/widgets/widget_id.h"

namespace ffdkit::app {

/// How a pick changes a point selection (Blender's edit mode: click replaces, Shift+click
/// toggles, Shift+box adds, Ctrl+box subtracts).
enum class SelectMode { Replace, Add, Toggle, Subtract };

/// The control points selected in a lattice's edit mode: a set of flat grid indices
/// i + l*(j + m*k) of one lattice with counts (l, m, n), and the active point (the last one
/// clicked: a pivot choice). Headless; the view draws it, the status bar counts it.
class PointSelection {
 public:
  PointSelection() = default;
  /// An empty selection of `lattice`'s points. @throws std::invalid_argument for a count < 1.
  PointSelection(widgets::WidgetId lattice, const Eigen::Vector3i& counts);

  widgets::WidgetId lattice() const { return lattice_; }
  const Eigen::Vector3i& counts() const { return counts_; }
  Eigen::Index pointCount() const { return static_cast<Eigen::Index>(selected_.size()); }

  /// One point, as a click does (Replace / Add / Toggle / Subtract); it becomes the active point
  /// unless it left the selection. @throws std::out_of_range for an index outside the lattice.
  void pick(Eigen::Index index, SelectMode mode);
  /// Several points at once (a box): Replace selects exactly them, Add and Toggle add them,
  /// Subtract removes them. The active point stays if still selected.
  void pickMany(const std::vector<Eigen::Index>& indices, SelectMode mode);
  void selectAll();
  void selectNone();
  void invert();
  /// Selects every point in the same index row along `axis` (the points that differ from a
  /// selected one in that index only), or with `plane`, every point in the same index plane
  /// normal to `axis` (same index along `axis`). @throws std::invalid_argument for an axis not
  /// in 0..2.
  void selectLinked(int axis, bool plane);

  bool contains(Eigen::Index index) const;
  /// Selected flat indices, ascending.
  std::vector<Eigen::Index> indices() const;
  Eigen::Index count() const { return count_; }
  bool empty() const { return count_ == 0; }
  std::optional<Eigen::Index> active() const { return active_; }

  /// (i, j, k) of a flat index, and back.
  Eigen::Vector3i gridIndex(Eigen::Index flat) const;
  Eigen::Index flatIndex(const Eigen::Vector3i& grid) const;

  friend bool operator==(const PointSelection&, const PointSelection&) = default;

 private:
  void set(Eigen::Index index, bool on);

  widgets::WidgetId lattice_;
  Eigen::Vector3i counts_ = Eigen::Vector3i::Zero();
  std::vector<bool> selected_;
  Eigen::Index count_ = 0;
  std::optional<Eigen::Index> active_;
};

/// The indices of the rows of `screen` (#points x 2, display pixels) that lie in the rectangle
/// spanned by corners `a` and `b` (inclusive, in any order): a box select over points the view
/// has projected (SceneView::displayPoint). Points behind the camera are the caller's to drop.
std::vector<Eigen::Index> pointsInRectangle(const Eigen::Ref<const Eigen::MatrixX2d>& screen, const Eigen::Vector2d& a,
                                            const Eigen::Vector2d& b);

}  // namespace ffdkit::app
