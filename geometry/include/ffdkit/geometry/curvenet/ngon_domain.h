#pragma once

#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/curvenet/jet.h"

namespace ffdkit::geometry::curvenet {

/// The regular N-gon domain of an N-sided patch with Loop-DeRose generalised barycentric
/// coordinates, the per-side orthogonal variables and the transfinite blending functions.
/// Vertices p_k = (cos th_k, sin th_k), th_k = -pi/2 - pi/N + 2 pi k / N (CCW, edge e_0 at the
/// bottom); edge e_k = [p_k, p_{k+1}] carries side k. Indices are cyclic mod N.
/// @see Kuriyama 1996, sec. 2.4.2 (barycentrics), eq. (5.1) sec. 5.2.1, eq. (5.3) sec. 5.2.2;
///      Kuriyama 1996, secs. 2.4.2, 5.2.1, 5.2.2.
class NGonDomain {
 public:
  /// @throws std::invalid_argument if sides < 3.
  explicit NGonDomain(int sides);

  /// Number of sides N.
  int sides() const { return n_; }
  /// Vertex p_k of the regular N-gon.
  Eigen::Vector2d vertex(int k) const;

  /// b_i(p), i = 0..N-1, as jets in (x, y). Computed in product form (never a / (a a)) so it is
  /// defined on edges and at vertices.
  std::vector<Jet> barycentric(const Eigen::Vector2d& p) const;

  /// u~_i of eq. (5.1): 0 at p_i, 1 at p_{i+1} along e_i; for odd N the 0/0 at the opposite
  /// vertex is guarded with 0.5 (B_i = 0 there, Kuriyama 1996, sec. 5.2.1).
  Jet uTilde(int i, const std::vector<Jet>& b) const;

  /// d_i = 1 - b_i - b_{i+1}: zero on e_i, the distance-like factor of v_i = F_i(u~) d_i.
  Jet distance(int i, const std::vector<Jet>& b) const;

  /// B_i^m = (b_i b_{i+1})^m / sum_k (b_k b_{k+1})^m, eq. (5.3), with the thesis' 1/2 rule at
  /// exact vertex hits (sec. 5.2.2). The products are scaled by their maximum first (the scale
  /// cancels) so that high m does not underflow.
  std::vector<Jet> blend(const std::vector<Jet>& b, int exponent) const;

  /// Index k if p is within tol of vertex p_k, else -1.
  int vertexAt(const Eigen::Vector2d& p, double tol = 1e-14) const;

 private:
  int n_;
  std::vector<Eigen::Vector2d> vertices_;
};

}  // namespace ffdkit::geometry::curvenet
