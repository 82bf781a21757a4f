#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/widgets/affine_kind.h"
#include "ffdkit/widgets/cell.h"

namespace ffdkit::app {

/// A cell made from selected lattice points (Widgets > Make Cell): the spec, or why the points
/// are not a cell of the kind asked.
struct CellFromSelection {
  std::optional<widgets::CellSpec> spec;
  std::string why;  ///< when there is no spec: what the kind needs and what the selection is
};

/// The cell of kind `kind` whose points are exactly `indices` (flat grid indices of a lattice of
/// `counts` points per axis; any order, no duplicates), Kuriyama 1996, sec. 6.2.1:
/// - Point: one point. Edge: two neighbours along one axis (grid indices differ by 1 in one
///   index only). Face: the 4 corners of one grid quad (two axes span one step each, the third
///   is constant). Slab: every point of one index plane. Box: the 8 corners of one grid
///   hexahedron. Custom: any non-empty set.
/// A selection that does not fit gets no spec and a reason that says what the kind needs and
/// what the selection is ("an edge is 2 neighbouring points; (0,0,0) and (2,0,0) differ by 2
/// along i").
/// @throws std::invalid_argument for indices outside the grid or listed twice.
CellFromSelection cellFromSelection(const Eigen::Vector3i& counts, const std::vector<Eigen::Index>& indices,
                                    widgets::CellKind kind);

/// The kind a selection is, tried in the order Point, Edge, Face, Box, Slab (a 2x2 plane is a
/// face first, a 2x2x2 lattice a box); nullopt when it is none of them (a custom cell, which the
/// application asks about first) or empty.
std::optional<widgets::CellSpec> classifySelection(const Eigen::Vector3i& counts,
                                                   const std::vector<Eigen::Index>& indices);

/// Why a new affine widget of `kind` (at its default placement, the cell's centre) would do
/// nothing on a cell of `cellKind`, or nullopt if it acts: a rotate or scale widget on a point
/// cell turns or sizes the point about itself, which moves nothing (Kuriyama 1996, sec. 6.2.2 gives point
/// cells the mask {T}). Adding one is refused with this reason rather than left a silent no-op.
std::optional<std::string> affineRefusal(widgets::AffineKind kind, widgets::CellKind cellKind);

}  // namespace ffdkit::app
