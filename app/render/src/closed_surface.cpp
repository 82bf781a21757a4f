#include "closed_surface.h"

namespace ffdkit::app {

namespace {

// How many triangles of `faces` at point a run along the directed edge (a, b).
int directedEdgeCount(const Eigen::MatrixX3i& triangles, const scene_view_shapes::VertexFaces& faces, int a, int b) {
  int count = 0;
  for (int k = faces.start[std::size_t(a)]; k < faces.start[std::size_t(a) + 1]; ++k) {
    const int f = faces.faces[std::size_t(k)];
    for (int i = 0; i < 3; ++i)
      if (triangles(f, i) == a && triangles(f, (i + 1) % 3) == b) ++count;
  }
  return count;
}

}  // namespace

bool closedOutwardSurface(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles,
                          const scene_view_shapes::VertexFaces& faces) {
  const Eigen::Index n = triangles.rows();
  if (n < 4 || triangles.minCoeff() < 0 || triangles.maxCoeff() >= points.rows() ||
      faces.start.size() != std::size_t(points.rows()) + 1) return false;
  bool closed = true;
  double volume = 0.0;  // about a point of the mesh, not the world's origin, against cancellation
  const Eigen::Vector3d origin = points.row(triangles(0, 0));
#pragma omp parallel for schedule(static) reduction(&& : closed) reduction(+ : volume) if (n >= 65536)
  for (Eigen::Index t = 0; t < n; ++t) {
    const int v[3] = {triangles(t, 0), triangles(t, 1), triangles(t, 2)};
    bool ok = v[0] != v[1] && v[1] != v[2] && v[2] != v[0];
    for (int i = 0; i < 3 && ok; ++i) {
      const int a = v[i], b = v[(i + 1) % 3];
      ok = directedEdgeCount(triangles, faces, a, b) == 1 && directedEdgeCount(triangles, faces, b, a) == 1;
    }
    closed = closed && ok;
    const Eigen::Vector3d pa = points.row(v[0]).transpose() - origin, pb = points.row(v[1]).transpose() - origin,
                          pc = points.row(v[2]).transpose() - origin;
    volume += pa.dot(pb.cross(pc));
  }
  return closed && volume > 0.0;
}

}  // namespace ffdkit::app
