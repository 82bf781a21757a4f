#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ffdkit::app {

/// The falloff curves of soft selection, as Blender's proportional editing names them.
enum class Falloff { Smooth, Sphere, Root, Linear, Sharp, Constant };

/// "smooth", "sphere", "root", "linear", "sharp", "constant".
std::string_view falloffName(Falloff falloff);
/// Every falloff, in menu order.
inline constexpr Falloff kFalloffs[] = {Falloff::Smooth, Falloff::Sphere, Falloff::Root,
                                        Falloff::Linear, Falloff::Sharp,  Falloff::Constant};

/// The weight of a point at `distance` from the selection for a soft selection of `radius`
/// (both world units, radius > 0), as Blender's proportional editing computes it: with
/// f = (radius - distance) / radius, which runs from 1 at the selection to 0 at the radius,
///   smooth 3 f^2 - 2 f^3,  sphere sqrt(2 f - f^2),  root sqrt(f),  linear f,  sharp f^2,
///   constant 1;
/// 0 beyond the radius (distance > radius), 1 at distance 0.
double falloffWeight(Falloff falloff, double distance, double radius);

/// Soft selection (Blender's proportional editing) of a lattice's edit mode: a transform of the
/// selected points also moves the points within `radius` of them, each by its falloff weight.
struct SoftSelection {
  bool enabled = false;              ///< O toggles it
  double radius = 1.0;               ///< world units, > 0; the wheel or PageUp / PageDown changes it
  Falloff falloff = Falloff::Smooth; ///< the curve of the weight over the distance
  /// Distances along the lattice grid's edges (Blender's "connected only", Alt+O) instead of
  /// straight lines: a point near the selection in space but far along the grid moves less.
  bool connectedOnly = false;
};

/// Per point of a lattice grid, its distance to the nearest selected point: the straight-line
/// distance, or with `connected` the length of the shortest path along the grid's edges (the
/// lines between points whose (i, j, k) differ by one in one index; Dijkstra).
/// @param points   #points x 3 (world), row = flat index i + l*(j + m*k).
/// @param counts   (l, m, n), l*m*n = #points.
/// @param selected flat indices; 0 for them, infinity for every point when none is selected.
/// @throws std::invalid_argument on sizes that disagree or an index out of range.
Eigen::VectorXd selectionDistances(const Eigen::Ref<const Eigen::MatrixX3d>& points, const Eigen::Vector3i& counts,
                                   const std::vector<Eigen::Index>& selected, bool connected);

/// Per point, the weight a transform applies to it: 1 for a selected point, the falloff of its
/// selectionDistances for the others (0 beyond the radius, and for every unselected point when
/// the soft selection is off). Same arguments as selectionDistances.
/// @throws std::invalid_argument as selectionDistances, or for a radius that is not positive.
Eigen::VectorXd softSelectionWeights(const SoftSelection& soft, const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                     const Eigen::Vector3i& counts, const std::vector<Eigen::Index>& selected);

/// The part `weight` (in [0, 1]) of a world motion M made about `pivot`, as Blender applies a
/// proportional edit: M x = L (x - p) + p + t (t = M p - p, the pivot's displacement) becomes
///   L_w (x - p) + p + w t,
/// with L_w the rotation by w times L's angle about L's axis when L is a rotation, else
/// I + w (L - I) (a scale). Weight 1 gives M, weight 0 the identity.
Eigen::Affine3d partialMotion(const Eigen::Affine3d& motion, const Eigen::Vector3d& pivot, double weight);

}  // namespace ffdkit::app
