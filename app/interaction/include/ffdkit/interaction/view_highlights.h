#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/interaction/transformer.h"
#include "ffdkit/widgets/widget_id.h"

namespace ffdkit::app {

/// A lattice control point singled out by the user (a pick target for "add widget to cell").
struct LatticePointRef {
  widgets::WidgetId lattice;
  Eigen::Index index = 0;  ///< flat index i + l*(j + m*k)
  friend bool operator==(const LatticePointRef&, const LatticePointRef&) = default;
};

/// What the view emphasises; the model knows nothing about it.
struct ViewHighlights {
  std::optional<widgets::WidgetId> hovered;
  std::vector<widgets::WidgetId> selected;
  std::vector<widgets::WidgetId> visited;  ///< widgets the active gesture moves (its bindings)
  std::optional<LatticePointRef> point;    ///< a picked lattice point
  std::vector<LatticePointRef> selectedPoints;  ///< a lattice's edit mode: its selected points
  std::optional<Transformer> transformer;  ///< the manipulator of the selection, if shown
  std::optional<TransformerHandle> transformerHandle;  ///< its hovered or dragged handle
  std::vector<Eigen::Vector3d> pins;  ///< pinned object points (direct manipulation), where they are drawn
};

}  // namespace ffdkit::app
