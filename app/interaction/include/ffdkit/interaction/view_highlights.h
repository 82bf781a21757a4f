#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/fold_check.h"
#include "ffdkit/interaction/transformer.h"
#include "ffdkit/widgets/widget_id.h"

namespace ffdkit::app {

/// A lattice control point singled out by the user (a pick target for "add widget to cell").
struct LatticePointRef {
  widgets::WidgetId lattice;
  Eigen::Index index = 0;  ///< flat index i + l*(j + m*k)
  friend bool operator==(const LatticePointRef&, const LatticePointRef&) = default;
};

/// A lattice's cells tinted by their fold-over verdict (ffd::checkFolding): "folds" red,
/// "unknown" amber, "positive" not drawn.
struct FoldTint {
  widgets::WidgetId lattice;       ///< the lattice
  std::array<int, 3> cellCounts{};  ///< cells along u, v, w
  /// One verdict per cell, flat index cu + cellCounts[0] (cv + cellCounts[1] cw).
  std::vector<ffd::CellFolding> cells;
  friend bool operator==(const FoldTint&, const FoldTint&) = default;  ///< equal when every field is
};

/// A lattice whose every cell ffd::checkFolding certified free of fold-over, with the revisions of
/// the lattice the verdict is for (WidgetModel::controlRevision, frameRevision): the view may rely
/// on it instead of checking the lattice again (SceneView culls back faces only over such lattices).
struct CertifiedLattice {
  widgets::WidgetId lattice;          ///< the lattice
  std::uint64_t controlRevision = 0;  ///< its control points' revision the check saw
  std::uint64_t frameRevision = 0;    ///< its rest lattice's revision the check saw
  friend bool operator==(const CertifiedLattice&, const CertifiedLattice&) = default;  ///< equal when every field is
};

/// The soft selection's reach, drawn as a sphere round the pivot during a transform.
struct SoftRadius {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< world
  double radius = 0.0;                               ///< world units
  friend bool operator==(const SoftRadius&, const SoftRadius&) = default;  ///< equal when both fields are
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
  std::vector<FoldTint> foldTints;    ///< lattices whose cells are not all certified free of fold-over
  std::vector<CertifiedLattice> certified;  ///< lattices checked and certified free of fold-over (no tint)
  std::optional<SoftRadius> softRadius;  ///< the soft selection's radius during a transform
  friend bool operator==(const ViewHighlights&, const ViewHighlights&) = default;  ///< equal when every field is
};

}  // namespace ffdkit::app
