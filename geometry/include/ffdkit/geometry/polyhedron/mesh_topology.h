#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace ffdkit::geometry::polyhedron {

/// Half-edge adjacency of a consistently oriented polygonal 2-manifold, closed or with
/// boundary. Every directed edge (a, b) of the mesh is a half-edge; a half-edge with no face
/// (face() == -1) lies outside a boundary edge.
///
/// Vertex rings follow Kuriyama 1996, sec. 4.3.1: at vertex v, ring edge e_i = ringHalfEdges(v)[i]
/// runs v -> w_i, counter-clockwise seen from outside, and face(e_i) is the patch/face Q_i lying
/// between e_i and e_{i+1}. A boundary vertex's ring starts and ends at its two boundary edges,
/// so face(e_last) == -1.
class MeshTopology {
 public:
  /// Builds the half-edges. Combinatorial checks only (geometry: validatePolygonMesh).
  /// @throws PolyhedronError for a face with < 3 corners, an index outside [0, vertexCount),
  ///   a vertex repeated in a face, an edge shared by more than two faces (non-manifold), two
  ///   faces traversing an edge in the same direction (inconsistent orientation), a vertex
  ///   whose faces form more than one fan (bow-tie), or a vertex used by no face.
  static MeshTopology build(const std::vector<std::vector<int>>& faces, int vertexCount);

  /// Number of vertices.
  int vertexCount() const { return static_cast<int>(rings_.size()); }
  /// Number of faces.
  int faceCount() const { return static_cast<int>(faces_.size()); }
  /// Number of half-edges.
  int halfEdgeCount() const { return static_cast<int>(from_.size()); }
  /// Number of (undirected) edges.
  int edgeCount() const { return static_cast<int>(edgeHalfEdge_.size()); }

  /// The vertices of face f, counter-clockwise.
  const std::vector<int>& faceVertices(int f) const { return faces_[f]; }
  /// Start vertex of half-edge he.
  int from(int he) const { return from_[he]; }
  /// End vertex of half-edge he.
  int to(int he) const { return to_[he]; }
  int face(int he) const { return face_[he]; }  ///< -1 outside a boundary edge
  /// The opposite half-edge of he.
  int twin(int he) const { return twin_[he]; }
  int edge(int he) const { return edge_[he]; }  ///< undirected edge id
  int edgeHalfEdge(int e) const { return edgeHalfEdge_[e]; }  ///< one of its two half-edges
  /// True when edge e has a face on one side only.
  bool isBoundaryEdge(int e) const;
  /// Half-edge from a to b, or -1 if a and b are not joined by an edge.
  int findHalfEdge(int a, int b) const;

  /// True when vertex v lies on the boundary.
  bool isBoundaryVertex(int v) const { return boundary_[v]; }
  /// Number of edges at vertex v.
  int valence(int v) const { return static_cast<int>(rings_[v].size()); }
  /// Outgoing half-edges e_1..e_n of v in counter-clockwise order (0-based in code).
  const std::vector<int>& ringHalfEdges(int v) const { return rings_[v]; }
  /// Position of outgoing half-edge `he` in the ring of from(he).
  int ringIndex(int he) const { return ringIndex_[he]; }

 private:
  std::vector<std::vector<int>> faces_;
  std::vector<int> from_, to_, face_, twin_, edge_, next_, prev_, ringIndex_;
  std::vector<int> edgeHalfEdge_;
  std::vector<std::vector<int>> rings_;
  std::vector<bool> boundary_;
  std::unordered_map<std::int64_t, int> lookup_;
};

}  // namespace ffdkit::geometry::polyhedron
