// Internal to ffd/: the volume and first moment of a deformed closed surface, and their
// per-vertex gradients, for ShapeConstraints' per-vertex rows (the volume summed per vertex, the
// centroid of the solid).
#pragma once

#include <Eigen/Core>

#include "ffdkit/ffd/closed_surface.h"

namespace ffdkit::ffd::detail {

/// One pass over the triangles of `surface` with its vertices at x (#vertices x 3, WORLD), each
/// triangle (a, b, c) visited once and measured about `origin` (both sums are translation
/// invariant; measuring about the object keeps digits), det = a . (b x c):
///   volume           V = sum det / 6                                (enclosedVolume),
///   centroidResidual r = sum det ((a + b + c) / 24 - t / 6) = M - t V (M: the first moment),
/// with t = target - origin: r = 0 exactly where the solid's centroid M / V is `target`
/// (enclosedCentroid). Parallel over triangles for large surfaces.
struct SurfaceSums {
  double volume = 0.0;                                         ///< V
  Eigen::Vector3d centroidResidual = Eigen::Vector3d::Zero();  ///< M - t V
};
SurfaceSums surfaceSums(const Eigen::MatrixX3d& x, const Eigen::Vector3d& origin, const ClosedSurface& surface,
                        const Eigen::Vector3d& target);

/// Per-vertex gradients of the sums above with respect to the deformed vertices, for a batch of
/// vertices at a time (the adjoint pass of ShapeConstraints asks for them in its point order and
/// carries them to the control points at once: the gradients are never stored for all vertices).
/// About vertex v with the pairs (b, c) of its triangles (v, b, c) (ClosedSurface::pairs), all
/// measured about `origin`, n = sum b x c, W = sum (b x c) (v + b + c)^T, d = v . n:
///   dV/dv = n / 6,
///   dr_k/dv = W e_k / 24 - t_k n / 6 + d e_k / 24   (k = 0, 1, 2).
class SurfaceGradients {
 public:
  /// @param x the deformed vertices (#vertices x 3, WORLD), held by reference while in use.
  SurfaceGradients(const Eigen::MatrixX3d& x, const Eigen::Vector3d& origin, const Eigen::Vector3d& target)
      : x_(x), origin_(origin), target_(target - origin) {}

  /// Into out[stride i + (0..2)]: dV/dx of vertex vertices[i], i < count.
  void volume(const ClosedSurface& surface, const Eigen::Index* vertices, int count, double* out, int stride) const;
  /// Into out[stride i + 3 k + j]: dr_k/dx_j of vertex vertices[i], i < count.
  void centroid(const ClosedSurface& surface, const Eigen::Index* vertices, int count, double* out, int stride) const;

 private:
  const Eigen::MatrixX3d& x_;
  Eigen::Vector3d origin_;
  Eigen::Vector3d target_;  // about origin_
};

}  // namespace ffdkit::ffd::detail
