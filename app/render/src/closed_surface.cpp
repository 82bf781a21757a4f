#include "closed_surface.h"

#include <algorithm>
#include <vector>

namespace ffdkit::app {

namespace {

// At point a, the triangles' edges leaving a (a -> out[k]) and coming into it (in[k] -> a), one of
// each per triangle at a: the surface is closed and consistently oriented round a when no edge
// leaves twice and each edge leaving a to b comes back from b exactly once, that is when `in` is a
// permutation of `out`, whose values are distinct.
bool closedRound(int a, const Eigen::MatrixX3i& triangles, const scene_view_shapes::VertexFaces& faces,
                 std::vector<int>& out, std::vector<int>& in) {
  out.clear();
  in.clear();
  for (int k = faces.start[std::size_t(a)]; k < faces.start[std::size_t(a) + 1]; ++k) {
    const int f = faces.faces[std::size_t(k)];
    const int v[3] = {triangles(f, 0), triangles(f, 1), triangles(f, 2)};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) return false;  // a corner repeated
    const int i = v[0] == a ? 0 : v[1] == a ? 1 : 2;
    out.push_back(v[(i + 1) % 3]);
    in.push_back(v[(i + 2) % 3]);
  }
  if (out.empty()) return true;  // a point no triangle uses
  std::sort(out.begin(), out.end());
  std::sort(in.begin(), in.end());
  return std::adjacent_find(out.begin(), out.end()) == out.end() && out == in;
}

}  // namespace

bool closedOutwardSurface(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles,
                          const scene_view_shapes::VertexFaces& faces) {
  const Eigen::Index n = triangles.rows(), pointCount = points.rows();
  if (n < 4 || triangles.minCoeff() < 0 || triangles.maxCoeff() >= pointCount ||
      faces.start.size() != std::size_t(pointCount) + 1)
    return false;
  bool closed = true;
#pragma omp parallel reduction(&& : closed) if (pointCount >= 65536)
  {
    std::vector<int> out, in;
#pragma omp for schedule(static)
    for (Eigen::Index a = 0; a < pointCount; ++a) closed = closed && closedRound(int(a), triangles, faces, out, in);
  }
  if (!closed) return false;
  double volume = 0.0;  // about a point of the mesh, not the world's origin, against cancellation
  const Eigen::Vector3d origin = points.row(triangles(0, 0));
#pragma omp parallel for schedule(static) reduction(+ : volume) if (n >= 65536)
  for (Eigen::Index t = 0; t < n; ++t) {
    const Eigen::Vector3d pa = points.row(triangles(t, 0)).transpose() - origin,
                          pb = points.row(triangles(t, 1)).transpose() - origin,
                          pc = points.row(triangles(t, 2)).transpose() - origin;
    volume += pa.dot(pb.cross(pc));
  }
  return volume > 0.0;
}

}  // namespace ffdkit::app
