#pragma once

#include <array>

#include <Eigen/Core>

namespace ffdkit::geometry::polyhedron {

/// Values and homogeneous partial derivatives of a triangular patch at (u, v, w).
struct PatchDerivatives {
  Eigen::Vector3d point;  ///< the point
  ///@{
  /// d/du, d/dv, d/dw of the homogeneous form.
  Eigen::Vector3d du, dv, dw;
  ///@}
};

/// Quartic triangular Bezier patch whose three interior control points are rational blends
/// of two sub-points each (Kuriyama 1996, secs. 4.3.1, 4.3.2, eq. (4.11)-(4.12), (4.18)):
///   D211 = (v D^w_211 + w D^v_211) / (v + w),  D121 = (u D^w_121 + w D^u_121) / (u + w),
///   D112 = (u D^v_112 + v D^u_112) / (u + v).
/// D^s belongs to the edge s = 0 and is the only interior point in that edge's cross-boundary
/// derivative. Corners: A at u = 1, B at v = 1, C at w = 1; edges w = 0 (AB), v = 0 (AC),
/// u = 0 (BC). Barycentric arguments must satisfy u, v, w >= 0 and u + v + w = 1.
struct RationalQuarticTriangle {
  std::array<int, 3> corners{-1, -1, -1};  ///< network vertex ids of A, B, C
  /// Control points D_ijk (i the power of u, j of v) at index(i, j); the three interior
  /// slots (ijk != 0) are unused and stay zero.
  std::array<Eigen::Vector3d, 15> d;
  ///@{
  /// Sub-points of D211 for the edges w = 0 and v = 0.
  Eigen::Vector3d dw211 = Eigen::Vector3d::Zero(), dv211 = Eigen::Vector3d::Zero();
  ///@}
  ///@{
  /// Sub-points of D121 for the edges w = 0 and u = 0.
  Eigen::Vector3d dw121 = Eigen::Vector3d::Zero(), du121 = Eigen::Vector3d::Zero();
  ///@}
  ///@{
  /// Sub-points of D112 for the edges v = 0 and u = 0.
  Eigen::Vector3d dv112 = Eigen::Vector3d::Zero(), du112 = Eigen::Vector3d::Zero();
  ///@}

  RationalQuarticTriangle() { d.fill(Eigen::Vector3d::Zero()); }

  /// Slot of D_ijk (k = 4 - i - j) in `d`.
  static constexpr int index(int i, int j) { return 5 * i - i * (i - 1) / 2 + j; }

  /// Sub-point at corner slot `corner` (0 = A, 1 = B, 2 = C) belonging to the edge towards
  /// corner slot `other` (e.g. (0, 1) -> D^w_211, (2, 1) -> D^u_112).
  /// @throws std::invalid_argument unless corner, other are distinct slots in 0..2.
  Eigen::Vector3d& subPoint(int corner, int other);
  /// Sub-point at corner slot `corner` for the edge towards `other`, read-only.
  const Eigen::Vector3d& subPoint(int corner, int other) const;
  /// Slot (0, 1, 2) of network vertex `vertex` among `corners`, or -1.
  int cornerSlot(int vertex) const;

  /// Q(u, v, w) (Kuriyama 1996, sec. 4.3.2 evaluation form).
  Eigen::Vector3d evaluate(double u, double v, double w) const;
  /// Q and its homogeneous partials; the blends use the analytic partials of
  /// f(x, y; a, b) = x y (x a + y b) / (x + y), defined as 0 where x + y = 0 (Kuriyama 1996,
  /// sec. 4.3.2).
  PatchDerivatives evaluateWithPartials(double u, double v, double w) const;
  /// Unit normal (Q_u - Q_w) x (Q_v - Q_w), outward for a counter-clockwise (A, B, C); the zero
  /// vector where the patch is singular (e.g. a collapsed corner), never NaN.
  Eigen::Vector3d normal(double u, double v, double w) const;
};

/// Unit normal (du - dw) x (dv - dw) of evaluated partials; the zero vector where it vanishes.
Eigen::Vector3d unitNormal(const PatchDerivatives& derivatives);

/// Degree elevation of a cubic V0..V3 to quartic points E0..E4 (eq. (4.12)):
/// E_i = i/4 V_{i-1} + (1 - i/4) V_i.
std::array<Eigen::Vector3d, 5> elevateCubic(const std::array<Eigen::Vector3d, 4>& cubic);

}  // namespace ffdkit::geometry::polyhedron
