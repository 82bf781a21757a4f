#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/widgets/affine_mask.h"

namespace ffdkit::widgets {

/// Cell kinds (幾何胞体, Kuriyama 1996, sec. 6.2.1): Point, Edge and Face of the thesis, plus Slab (all
/// points of one index plane), Box (the 8 corners of one grid hexahedron) and Custom (any list).
enum class CellKind { Point, Edge, Face, Slab, Box, Custom };

/// Stable lower-case name used in files and the UI ("point", "edge", "face", ...).
std::string_view cellKindName(CellKind kind);
std::optional<CellKind> parseCellKind(std::string_view name);

/// Default attachment mask per cell kind (Kuriyama 1996, secs. 6.2.1, 6.2.2):
/// Point {T}; Edge, Face, Slab, Box {T, R}; Custom {T}.
AffineMask defaultAttachmentMask(CellKind kind);

/// Which lattice points a cell groups. Grid indices are (i, j, k), flat = i + l*(j + m*k).
struct CellSpec {
  CellKind kind = CellKind::Point;  ///< which points the cell groups
  /// Point: the point. Edge: its lower end. Face, Box: the lower corner.
  /// Slab: only base[axis] is used (the index of the plane).
  Eigen::Vector3i base = Eigen::Vector3i::Zero();
  /// Edge: the axis it runs along. Face, Slab: the normal axis. Unused otherwise.
  int axis = 0;
  /// Custom: flat point indices, at least one, no duplicates.
  std::vector<Eigen::Index> indices;

  /// The point (i, j, k).
  static CellSpec point(int i, int j, int k);
  /// The edge from (i, j, k) to the next point along axis `alongAxis` (0, 1, 2).
  static CellSpec edge(int i, int j, int k, int alongAxis);
  /// The quad with lower corner (i, j, k) in the plane normal to axis `normalAxis`.
  static CellSpec face(int i, int j, int k, int normalAxis);
  /// Every point of the plane `planeIndex` normal to axis `normalAxis`.
  static CellSpec slab(int normalAxis, int planeIndex);
  /// The 2x2x2 points with lower corner (i, j, k).
  static CellSpec box(int i, int j, int k);
  /// Any points, by flat index (at least one, no duplicates).
  static CellSpec custom(std::vector<Eigen::Index> flatIndices);

  friend bool operator==(const CellSpec&, const CellSpec&) = default;  ///< equal when every field is
};

/// Flat indices of the cell's points in a lattice of `counts` points per axis, in a fixed
/// order: Edge (lower, upper); Face the quad loop p00, p10, p11, p01 over its grid directions
/// (a, b) = (normal+1, normal+2) mod 3; Slab and Box with a (resp. i) fastest; Custom as given.
/// @throws WidgetError (InvalidArgument) for indices outside the grid, bad axes, empty or
///         duplicate custom indices.
std::vector<Eigen::Index> cellPointIndices(const Eigen::Vector3i& counts, const CellSpec& spec);

/// Rest frame of a cell (Kuriyama 1996, sec. 6.2.1): origin at the centroid of `restPoints` (#cell
/// x 3, in the order of cellPointIndices); axes: Point and Custom the lattice axes; Edge x along
/// the edge; Face, Slab x along the first grid direction and z along the normal; Box x, y along the
/// first two grid directions. `spec` supplies the grid layout; `counts` the lattice counts.
Eigen::Isometry3d cellRestFrame(const CellSpec& spec, const Eigen::Vector3i& counts,
                                const Eigen::Ref<const Eigen::MatrixX3d>& restPoints);

/// Current affine elements of a cell against its rest points (Kuriyama 1996, sec. 6.2.1):
///   A = Translate(c̄ + translation) * rotation * E diag(scale) E^T * Translate(-c̄),
/// with c̄ the rest centroid and E the rest frame's rotation. Scale is per cell axis.
struct CellAffine {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  ///< moves the rest centroid, lattice-local
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< turns about the rest centroid
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();  ///< per cell axis

  /// The masked matrix mask(A) about the rest frame (components left out are identity).
  Eigen::Affine3d matrix(const Eigen::Isometry3d& restFrame, AffineMask mask = AffineMask::trs()) const;
};

/// Fits CellAffine from the current points (#cell x 3) against the rest points (Kuriyama 1996,
/// sec. 6.2.1):
/// Point: translation only. Edge: centroid translation, minimal rotation of the edge direction,
/// scale = (length ratio, 1, 1). Face/Slab/Box/Custom: centroid translation, Kabsch rotation
/// (Kabsch 1976), per-axis least-squares scale in the cell's own axes (1 on a degenerate axis).
CellAffine fitCellAffine(const CellSpec& spec, const Eigen::Isometry3d& restFrame,
                         const Eigen::Ref<const Eigen::MatrixX3d>& restPoints,
                         const Eigen::Ref<const Eigen::MatrixX3d>& currentPoints);

}  // namespace ffdkit::widgets
