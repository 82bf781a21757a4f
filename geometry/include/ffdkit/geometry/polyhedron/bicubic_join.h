#pragma once

#include <array>

#include <Eigen/Core>

#include "ffdkit/geometry/polyhedron/patch_surface.h"
#include "ffdkit/geometry/polyhedron/rational_quartic_triangle.h"

namespace ffdkit::geometry::polyhedron {

/// Bicubic tensor-product Bezier net P[i][j] (i along u, j along w):
/// S(u, w) = sum P_ij B^3_i(u) B^3_j(w).
using BicubicNet = std::array<std::array<Eigen::Vector3d, 4>, 4>;

/// The triangle points next to a shared boundary that make a rational quartic triangle G1 to
/// a bicubic patch along the bicubic's row w = 0 and the triangle's edge w = 0 (
/// Kuriyama 1996 Kuriyama 1996, sec. 4.3.3, eq. (4.20)). The edge is shared as
/// D_{i,4-i,0} = i/4 P_{i-1,0} + (1 - i/4) P_{i,0}, so D_040 = P_00 (triangle corner B) and
/// D_400 = P_30 (corner A). The tangent-plane multiplier is lambda = l1 v + l2 u (l1 at the
/// P_00 end), as the printed formulas expand (Kuriyama 1996, sec. 4.3.3).
struct TriangleJoinRow {
  ///@{
  /// Boundary points of the triangle's other two edges.
  Eigen::Vector3d d031, d301;
  ///@}
  ///@{
  /// The w-edge sub-points.
  Eigen::Vector3d dw121, dw211;
  ///@}
};

/// Given the bicubic net and l1, l2 (any reals; 0 makes the cross legs opposite), the
/// triangle row of eq. (4.20).
TriangleJoinRow triangleRowFromBicubic(const BicubicNet& net, double l1, double l2);

/// Writes the shared boundary (degree-elevated row P_i0) and triangleRowFromBicubic into
/// `triangle`, leaving its other control points as they are.
void joinTriangleToBicubic(RationalQuarticTriangle& triangle, const BicubicNet& net, double l1, double l2);

/// The other direction (sec. 4.3.3): given the triangle (its w = 0 edge must be the elevated
/// P_00..P_30, which is taken from `row0`) compute the bicubic's second row P_01..P_31.
/// Always solvable.
std::array<Eigen::Vector3d, 4> bicubicSecondRowFromTriangle(const RationalQuarticTriangle& triangle,
                                                           const std::array<Eigen::Vector3d, 4>& row0, double l1,
                                                           double l2);

/// The same patch with its corners relabelled: slot s of the result is slot order[s] of
/// `patch` (control points and sub-points move with their corners; the surface is unchanged).
/// @throws std::invalid_argument unless order is a permutation of {0, 1, 2}.
RationalQuarticTriangle relabelled(const RationalQuarticTriangle& patch, const std::array<int, 3>& order);

/// A bicubic patch joined G1 to an open patch surface across its boundary curve from network
/// vertex a to b (sec. 4.3.3, "given the triangle, compute the second row"): row 0 is the network
/// cubic (P_00 = a, P_30 = b), row 1 comes from bicubicSecondRowFromTriangle with the triangle
/// relabelled so that the curve is its w = 0 edge, rows 2 and 3 are the caller's (they do not
/// affect G1). lambda = l1 v + l2 u as in eq. (4.20).
/// @throws PolyhedronError if (a, b) is not a boundary curve of the surface.
BicubicNet bicubicAcrossBoundary(const PatchSurface& surface, int a, int b, const std::array<Eigen::Vector3d, 4>& row2,
                                 const std::array<Eigen::Vector3d, 4>& row3, double l1 = 0.0, double l2 = 0.0);

/// The surface patch next to boundary curve (a, b), relabelled as bicubicAcrossBoundary uses it
/// (B = a, A = b, the curve is its w = 0 edge).
RationalQuarticTriangle boundaryPatchForJoin(const PatchSurface& surface, int a, int b);

/// S(u, w) and its partials d/du, d/dw.
struct BicubicPoint {
  ///@{
  /// S(u, w), dS/du and dS/dw.
  Eigen::Vector3d point, du, dw;
  ///@}
};
BicubicPoint evaluateBicubic(const BicubicNet& net, double u, double w);

}  // namespace ffdkit::geometry::polyhedron
