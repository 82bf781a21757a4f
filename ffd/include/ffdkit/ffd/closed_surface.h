#pragma once

#include <stdexcept>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ffdkit::ffd {

/// A shape constraint that is malformed or cannot be met: an open surface where a closed one is
/// needed, a constraint matrix of the wrong size, a volume no allowed control change reaches.
/// Messages say what was expected, what came, and where, e.g.
/// `volume needs a closed surface: edge (12, 40) is used by 1 triangle (triangle 7)`.
class ConstraintError : public std::invalid_argument {
 public:
  /// An error with `message`, which says what was expected, what came and where.
  explicit ConstraintError(const std::string& message) : std::invalid_argument(message) {}
};

using TriangleMatrix = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// The triangles of a closed, consistently oriented surface: every directed edge (a, b) of a
/// triangle appears exactly once, and its reverse (b, a) exactly once (a 2-manifold without
/// boundary; several components are allowed). Only such a surface encloses a volume.
class ClosedSurface {
 public:
  /// @param triangles  #triangles x 3 vertex indices, counter-clockwise seen from outside.
  /// @param vertexCount the number of points the indices refer to.
  /// @throws ConstraintError on an index out of [0, vertexCount), a triangle with a repeated
  ///         vertex, an edge used by one triangle only (open), or an edge used twice in the same
  ///         direction (inconsistent orientation or a non-manifold edge), naming the triangle.
  ClosedSurface(TriangleMatrix triangles, Eigen::Index vertexCount);

  /// The triangles, #triangles x 3, as given.
  const TriangleMatrix& triangles() const { return triangles_; }
  /// The number of points the indices refer to.
  Eigen::Index vertexCount() const { return vertexCount_; }

  /// Per vertex, the ordered pairs (b, c) of the triangles (v, b, c) around it (rotated so that
  /// v comes first), as CSR: pairs [offsets[v], offsets[v+1]). The volume's gradient at v is
  /// sum (x_b x x_c) / 6 over them; computed once so that gradients run in parallel over vertices.
  const Eigen::VectorXi& pairOffsets() const { return offsets_; }
  /// The pairs (b, c) of every vertex, rows [pairOffsets()[v], pairOffsets()[v+1]) for vertex v.
  const Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor>& pairs() const { return pairs_; }

 private:
  TriangleMatrix triangles_;
  Eigen::Index vertexCount_ = 0;
  Eigen::VectorXi offsets_;
  Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor> pairs_;
};

/// Enclosed volume of a closed surface by the divergence theorem: sum over triangles (a, b, c)
/// of a . (b x c) / 6 (positive for outward, counter-clockwise triangles).
/// @param points #vertexCount x 3.
/// @throws ConstraintError if points has the wrong number of rows.
double enclosedVolume(const Eigen::Ref<const Eigen::MatrixX3d>& points, const ClosedSurface& surface);

/// Centroid of the solid a closed surface bounds: sum over triangles of
/// det[a, b, c] (a + b + c) / 24, divided by enclosedVolume.
/// @throws ConstraintError on the wrong number of rows or a zero volume.
Eigen::Vector3d enclosedCentroid(const Eigen::Ref<const Eigen::MatrixX3d>& points, const ClosedSurface& surface);

}  // namespace ffdkit::ffd
