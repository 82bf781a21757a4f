#include "ffdkit/geometry/polyhedron/mesh_topology.h"

#include <algorithm>
#include <string>

#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {
namespace {

std::int64_t key(int a, int b, int n) { return static_cast<std::int64_t>(a) * n + b; }

std::string edgeName(int a, int b) { return "(" + std::to_string(a) + ", " + std::to_string(b) + ")"; }

}  // namespace

bool MeshTopology::isBoundaryEdge(int e) const {
  const int he = edgeHalfEdge_[e];
  return face_[he] < 0 || face_[twin_[he]] < 0;
}

int MeshTopology::findHalfEdge(int a, int b) const {
  const int n = vertexCount();
  if (a < 0 || b < 0 || a >= n || b >= n) return -1;
  const auto it = lookup_.find(key(a, b, n));
  return it == lookup_.end() ? -1 : it->second;
}

MeshTopology MeshTopology::build(const std::vector<std::vector<int>>& faces, int vertexCount) {
  if (vertexCount < 0) throw PolyhedronError("mesh topology: vertex count must be >= 0, got " + std::to_string(vertexCount));
  MeshTopology t;
  t.faces_ = faces;
  const int n = vertexCount;
  // Undirected use counts first, so that a third face on an edge is reported as
  // non-manifold rather than as an orientation clash.
  std::unordered_map<std::int64_t, int> undirectedUses;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& c = faces[f];
    const std::string where = "face " + std::to_string(f);
    if (c.size() < 3) {
      throw PolyhedronError(where + ": expected >= 3 corners, got " + std::to_string(c.size()));
    }
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (c[k] < 0 || c[k] >= n) {
        throw PolyhedronError(where + ": vertex index " + std::to_string(c[k]) + " outside [0, " +
                              std::to_string(n) + ")");
      }
      for (std::size_t l = 0; l < k; ++l) {
        if (c[l] == c[k]) {
          throw PolyhedronError(where + ": vertex " + std::to_string(c[k]) + " appears twice (degenerate face)");
        }
      }
    }
    for (std::size_t k = 0; k < c.size(); ++k) {
      const int a = c[k], b = c[(k + 1) % c.size()];
      const int uses = ++undirectedUses[key(std::min(a, b), std::max(a, b), n)];
      if (uses > 2) {
        throw PolyhedronError("non-manifold edge " + edgeName(std::min(a, b), std::max(a, b)) +
                              ": expected at most 2 faces, face " + std::to_string(f) + " is the third");
      }
    }
  }
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& c = faces[f];
    const int first = static_cast<int>(t.from_.size());
    const int m = static_cast<int>(c.size());
    for (int k = 0; k < m; ++k) {
      const int a = c[k], b = c[(k + 1) % m];
      const int he = static_cast<int>(t.from_.size());
      if (!t.lookup_.emplace(key(a, b, n), he).second) {
        throw PolyhedronError("inconsistent orientation: edge " + edgeName(a, b) +
                              " is traversed in the same direction by face " + std::to_string(f) +
                              " and another face; expected all faces counter-clockwise from outside");
      }
      t.from_.push_back(a);
      t.to_.push_back(b);
      t.face_.push_back(static_cast<int>(f));
      t.next_.push_back(first + (k + 1) % m);
      t.prev_.push_back(first + (k + m - 1) % m);
    }
  }
  const int faceHalfEdges = static_cast<int>(t.from_.size());
  for (int he = 0; he < faceHalfEdges; ++he) {
    const int a = t.from_[he], b = t.to_[he];
    if (t.lookup_.find(key(b, a, n)) == t.lookup_.end()) {
      const int out = static_cast<int>(t.from_.size());
      t.lookup_.emplace(key(b, a, n), out);
      t.from_.push_back(b);
      t.to_.push_back(a);
      t.face_.push_back(-1);
      t.next_.push_back(-1);
      t.prev_.push_back(-1);
    }
  }
  const int h = static_cast<int>(t.from_.size());
  t.twin_.assign(h, -1);
  t.edge_.assign(h, -1);
  for (int he = 0; he < h; ++he) {
    t.twin_[he] = t.lookup_.at(key(t.to_[he], t.from_[he], n));
    if (t.edge_[he] < 0) {
      t.edge_[he] = t.edge_[t.twin_[he]] = static_cast<int>(t.edgeHalfEdge_.size());
      t.edgeHalfEdge_.push_back(he);
    }
  }

  // Rings: the next outgoing half-edge after v->w_i (face Q_i) is the twin of the half-edge
  // entering v in Q_i, i.e. v->w_{i+1} (Kuriyama 1996, sec. 4.3.1 ring convention).
  std::vector<std::vector<int>> outgoing(n);
  for (int he = 0; he < h; ++he) outgoing[t.from_[he]].push_back(he);
  t.rings_.assign(n, {});
  t.boundary_.assign(n, false);
  t.ringIndex_.assign(h, -1);
  for (int v = 0; v < n; ++v) {
    if (outgoing[v].empty()) {
      throw PolyhedronError("vertex " + std::to_string(v) + " is used by no face; expected every vertex on a face");
    }
    int start = -1;
    int starts = 0;
    for (int he : outgoing[v]) {
      if (t.face_[he] >= 0 && t.face_[t.twin_[he]] < 0) {
        ++starts;
        start = he;
      }
    }
    if (starts > 1) {
      throw PolyhedronError("non-manifold vertex " + std::to_string(v) + ": it joins " + std::to_string(starts) +
                            " separate fans of faces (bow-tie); expected one fan");
    }
    t.boundary_[v] = starts == 1;
    if (start < 0) start = outgoing[v].front();
    std::vector<int>& ring = t.rings_[v];
    int he = start;
    do {
      ring.push_back(he);
      if (t.face_[he] < 0) break;  // reached the closing boundary edge
      he = t.twin_[t.prev_[he]];
    } while (he != start && ring.size() <= outgoing[v].size());
    if (ring.size() != outgoing[v].size()) {
      throw PolyhedronError("non-manifold vertex " + std::to_string(v) + ": its faces form more than one fan (" +
                            std::to_string(ring.size()) + " of " + std::to_string(outgoing[v].size()) +
                            " edges reached walking around it)");
    }
    for (std::size_t i = 0; i < ring.size(); ++i) t.ringIndex_[ring[i]] = static_cast<int>(i);
  }
  return t;
}

}  // namespace ffdkit::geometry::polyhedron
