#pragma once

#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/polyhedron/mesh_topology.h"

namespace ffdkit::geometry::polyhedron {

/// A polyhedron as the designer models it: vertices and polygonal faces, closed or open.
/// Faces need not be planar (Kuriyama 1996, sec. 4.4) but must be consistently oriented,
/// counter-clockwise seen from outside.
struct PolygonMesh {
  Eigen::MatrixX3d vertices;             ///< #V x 3, one vertex per row
  std::vector<std::vector<int>> faces;  ///< #F index lists, each with >= 3 distinct vertices
};

/// Checks `mesh` and builds its topology. Documented handling of bad input: everything below
/// is rejected with a PolyhedronError naming the offending vertex/edge/face.
///  - non-finite coordinates; faces with < 3 corners, repeated or out-of-range indices;
///  - non-manifold edges (> 2 faces), inconsistent orientation, non-manifold (bow-tie)
///    vertices, vertices used by no face (all from MeshTopology::build);
///  - degenerate faces: an edge shorter than `relativeTolerance * L` or a vector area below
///    `relativeTolerance * L^2` (L = bounding-box diagonal);
///  - vertices of valence 2 (closed or on the boundary): their tangent frame T^s is
///    undetermined (Kuriyama 1996, sec. 4.2.2 does not cover it). Remove such a vertex or merge it
//into its edge.
/// @see Kuriyama 1996, sec. 4.2
MeshTopology validatePolygonMesh(const PolygonMesh& mesh, double relativeTolerance = 1e-12);

/// Bounding-box diagonal of the vertices (0 for an empty mesh); the length scale L of tolerances.
double boundingBoxDiagonal(const Eigen::MatrixX3d& points);

}  // namespace ffdkit::geometry::polyhedron
