#include "ffdkit/geometry/polyhedron/surface_tessellation.h"

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {

TessellatedSurface tessellate(const PatchSurface& surface, int samplesPerPatchSide) {
  const int n = samplesPerPatchSide;
  if (n < 1) throw PolyhedronError("tessellation: expected >= 1 sample per patch side, got " + std::to_string(n));
  const auto& net = surface.triangulated();
  const MeshTopology& topo = net.topology;
  const auto& patches = surface.patches();
  const int networkVertices = topo.vertexCount();
  const int patchCount = static_cast<int>(patches.size());
  const int perPatchInterior = n >= 3 ? (n - 1) * (n - 2) / 2 : 0;
  const int vertexCount = networkVertices + topo.edgeCount() * (n - 1) + patchCount * perPatchInterior;

  TessellatedSurface out;
  out.mesh.vertices.resize(vertexCount, 3);
  out.normals = Eigen::MatrixX3d::Zero(vertexCount, 3);
  std::vector<bool> placed(vertexCount, false);
  out.mesh.triangles.resize(static_cast<Eigen::Index>(patchCount) * n * n, 3);
  out.trianglePatch.resize(static_cast<Eigen::Index>(patchCount) * n * n);

  int nextInterior = networkVertices + topo.edgeCount() * (n - 1);
  int triangle = 0;
  std::vector<int> local((n + 1) * (n + 2) / 2);
  auto localIndex = [n](int i, int j) { return i * (n + 1) - i * (i - 1) / 2 + j; };
  for (int t = 0; t < patchCount; ++t) {
    const auto& patch = patches[t];
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const int k = n - i - j;
        const int idx[3] = {i, j, k};
        int id = -1;
        int zeros = (i == 0) + (j == 0) + (k == 0);
        if (zeros == 2) {
          id = patch.corners[i == n ? 0 : j == n ? 1 : 2];
        } else if (zeros == 1) {
          // On a curve: weld by (curve, step counted from its lower-id end).
          const int off = i == 0 ? 0 : j == 0 ? 1 : 2;
          const int a = patch.corners[(off + 1) % 3], b = patch.corners[(off + 2) % 3];
          const int weightOfA = idx[(off + 1) % 3];
          const int he = topo.findHalfEdge(a, b);
          const int step = a < b ? n - weightOfA : weightOfA;
          id = networkVertices + topo.edge(he) * (n - 1) + (step - 1);
        } else {
          id = nextInterior++;
        }
        local[localIndex(i, j)] = id;
        const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n, w = static_cast<double>(k) / n;
        const PatchDerivatives d = patch.evaluateWithPartials(u, v, w);
        if (!placed[id]) {
          out.mesh.vertices.row(id) = d.point.transpose();
          placed[id] = true;
        }
        out.normals.row(id) += unitNormal(d).transpose();
      }
    }
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        // (i+1, j) -> (i, j+1) -> (i, j) keeps the A, B, C orientation of the patch.
        out.mesh.triangles.row(triangle) << local[localIndex(i + 1, j)], local[localIndex(i, j + 1)],
            local[localIndex(i, j)];
        out.trianglePatch[triangle++] = t;
        if (i + j + 1 < n) {
          out.mesh.triangles.row(triangle) << local[localIndex(i + 1, j)], local[localIndex(i + 1, j + 1)],
              local[localIndex(i, j + 1)];
          out.trianglePatch[triangle++] = t;
        }
      }
    }
  }
  Eigen::MatrixX3d fallback = Eigen::MatrixX3d::Zero(vertexCount, 3);
  for (int f = 0; f < out.mesh.triangles.rows(); ++f) {
    const Eigen::Vector3d a = out.mesh.vertices.row(out.mesh.triangles(f, 0));
    const Eigen::Vector3d b = out.mesh.vertices.row(out.mesh.triangles(f, 1));
    const Eigen::Vector3d c = out.mesh.vertices.row(out.mesh.triangles(f, 2));
    const Eigen::RowVector3d area = (b - a).cross(c - a).transpose();
    for (int k = 0; k < 3; ++k) fallback.row(out.mesh.triangles(f, k)) += area;
  }
  for (int v = 0; v < vertexCount; ++v) {
    double length = out.normals.row(v).norm();
    if (!(length > 1e-8)) {
      out.normals.row(v) = fallback.row(v);
      length = out.normals.row(v).norm();
    }
    if (length > 0.0 && std::isfinite(length)) {
      out.normals.row(v) /= length;
    } else {
      out.normals.row(v) << 0.0, 0.0, 1.0;  // fully degenerate sample: any unit vector beats NaN
    }
  }
  return out;
}

}  // namespace ffdkit::geometry::polyhedron
