#pragma once

// The level-of-detail proxy of a large triangle mesh (private to ffdkit::render; SceneView draws
// it while things move, LevelOfDetail). Eigen only: no VTK here.
//
// Vertex clustering (Rossignac and Borrel 1993, "Multi-resolution 3D approximations for rendering
// complex scenes"): the mesh's bounding box is cut into cubic cells; the first vertex of the mesh
// in each occupied cell stands for the cell, every triangle is mapped to the stand-ins of its three
// corners, and the triangles whose corners fall in fewer than three cells, or repeat a triangle
// already kept, are dropped. The proxy's vertices are thus a SUBSET of the mesh's vertices: its
// deformed points are the mesh's deformed points at those indices, whatever deforms them (no
// embedding of its own), and it needs no precomputation beyond this one pass.

#include <vector>

#include <Eigen/Core>

namespace ffdkit::app {

/// A decimation of a triangle mesh whose vertices are some of the mesh's vertices.
struct ProxyMesh {
  /// The mesh's index of each proxy vertex, increasing.
  std::vector<Eigen::Index> vertices;
  /// The proxy's triangles, as indices into `vertices`, each with the orientation of the first
  /// mesh triangle that mapped to it.
  Eigen::MatrixX3i triangles;
};

/// Clusters the vertices of the mesh (`points`, #points x 3, its `triangles` indexing them) on a
/// grid whose cell is chosen so that about `targetVertices` cells are occupied (the cell's edge
/// sqrt(area / targetVertices) for the mesh's surface area). Deterministic: the same mesh gives the
/// same proxy. A mesh with no triangle, or of no more than `targetVertices` vertices, gives every
/// vertex and every triangle (the mesh itself). Unreferenced vertices are left out.
ProxyMesh clusterVertices(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles, Eigen::Index targetVertices);

}  // namespace ffdkit::app
