#include "ffdkit/geometry/polyhedron/bicubic_join.h"

#include <stdexcept>
#include <string>

#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {
namespace {

using T = RationalQuarticTriangle;

std::array<double, 4> bernstein3(double t) {
  const double r = 1.0 - t;
  return {r * r * r, 3.0 * r * r * t, 3.0 * r * t * t, t * t * t};
}

std::array<double, 4> bernstein3Derivative(double t) {
  const double r = 1.0 - t;
  return {-3.0 * r * r, 3.0 * r * r - 6.0 * r * t, 6.0 * r * t - 3.0 * t * t, 3.0 * t * t};
}

}  // namespace

TriangleJoinRow triangleRowFromBicubic(const BicubicNet& p, double l1, double l2) {
  const Eigen::Vector3d d040 = p[0][0];
  const Eigen::Vector3d d130 = 0.25 * p[0][0] + 0.75 * p[1][0];
  const Eigen::Vector3d d220 = 0.5 * (p[1][0] + p[2][0]);
  const Eigen::Vector3d d310 = 0.75 * p[2][0] + 0.25 * p[3][0];
  // Eq. (4.20), sec. 4.3.3, as printed (Kuriyama 1996, sec. 4.3.3).
  TriangleJoinRow row;
  row.d031 = d040 - 0.75 * (l1 * (p[1][0] - p[0][0]) + (p[0][1] - p[0][0]));
  row.d301 = d310 - 0.75 * (l2 * (p[3][0] - p[2][0]) + (p[3][1] - p[3][0]));
  row.dw121 = d130 - 0.25 * (l2 * (p[1][0] - p[0][0]) + 2.0 * l1 * (p[2][0] - p[1][0]) + 3.0 * (p[1][1] - p[1][0]));
  row.dw211 = d220 - 0.25 * (l1 * (p[3][0] - p[2][0]) + 2.0 * l2 * (p[2][0] - p[1][0]) + 3.0 * (p[2][1] - p[2][0]));
  return row;
}

void joinTriangleToBicubic(RationalQuarticTriangle& triangle, const BicubicNet& net, double l1, double l2) {
  const std::array<Eigen::Vector3d, 5> edge = {
      net[0][0], 0.25 * net[0][0] + 0.75 * net[1][0], 0.5 * (net[1][0] + net[2][0]),
      0.75 * net[2][0] + 0.25 * net[3][0], net[3][0]};
  for (int i = 0; i <= 4; ++i) triangle.d[T::index(i, 4 - i)] = edge[i];
  const TriangleJoinRow row = triangleRowFromBicubic(net, l1, l2);
  triangle.d[T::index(0, 3)] = row.d031;
  triangle.d[T::index(3, 0)] = row.d301;
  triangle.dw121 = row.dw121;
  triangle.dw211 = row.dw211;
}

std::array<Eigen::Vector3d, 4> bicubicSecondRowFromTriangle(const RationalQuarticTriangle& t,
                                                           const std::array<Eigen::Vector3d, 4>& p, double l1,
                                                           double l2) {
  const Eigen::Vector3d& d040 = t.d[T::index(0, 4)];
  const Eigen::Vector3d& d130 = t.d[T::index(1, 3)];
  const Eigen::Vector3d& d220 = t.d[T::index(2, 2)];
  const Eigen::Vector3d& d310 = t.d[T::index(3, 1)];
  const Eigen::Vector3d& d031 = t.d[T::index(0, 3)];
  const Eigen::Vector3d& d301 = t.d[T::index(3, 0)];
  // Eq. (4.20) solved for P_i1.
  return {p[0] + 4.0 / 3.0 * (d040 - d031) - l1 * (p[1] - p[0]),
          p[1] + (4.0 * (d130 - t.dw121) - l2 * (p[1] - p[0]) - 2.0 * l1 * (p[2] - p[1])) / 3.0,
          p[2] + (4.0 * (d220 - t.dw211) - l1 * (p[3] - p[2]) - 2.0 * l2 * (p[2] - p[1])) / 3.0,
          p[3] + 4.0 / 3.0 * (d310 - d301) - l2 * (p[3] - p[2])};
}

RationalQuarticTriangle relabelled(const RationalQuarticTriangle& patch, const std::array<int, 3>& order) {
  const bool permutation = order[0] != order[1] && order[1] != order[2] && order[0] != order[2] &&
                           order[0] >= 0 && order[1] >= 0 && order[2] >= 0 && order[0] < 3 && order[1] < 3 && order[2] < 3;
  if (!permutation) throw std::invalid_argument("relabelled: expected a permutation of {0, 1, 2}");
  RationalQuarticTriangle out;
  for (int s = 0; s < 3; ++s) out.corners[s] = patch.corners[order[s]];
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; i + j <= 4; ++j) {
      const int exponents[3] = {i, j, 4 - i - j};
      int old[3];
      for (int s = 0; s < 3; ++s) old[order[s]] = exponents[s];
      out.d[T::index(i, j)] = patch.d[T::index(old[0], old[1])];
    }
  }
  for (int c = 0; c < 3; ++c) {
    for (int o = 0; o < 3; ++o) {
      if (c != o) out.subPoint(c, o) = patch.subPoint(order[c], order[o]);
    }
  }
  return out;
}

RationalQuarticTriangle boundaryPatchForJoin(const PatchSurface& surface, int a, int b) {
  const MeshTopology& topo = surface.triangulated().topology;
  const int he = topo.findHalfEdge(a, b);
  if (he < 0 || !topo.isBoundaryEdge(topo.edge(he))) {
    throw PolyhedronError("bicubic join: (" + std::to_string(a) + ", " + std::to_string(b) +
                          ") is not a boundary curve of the surface");
  }
  const int face = topo.face(he) >= 0 ? topo.face(he) : topo.face(topo.twin(he));
  const RationalQuarticTriangle& patch = surface.patches()[face];
  const int sa = patch.cornerSlot(a), sb = patch.cornerSlot(b);
  return relabelled(patch, {sb, sa, 3 - sa - sb});
}

BicubicNet bicubicAcrossBoundary(const PatchSurface& surface, int a, int b, const std::array<Eigen::Vector3d, 4>& row2,
                                 const std::array<Eigen::Vector3d, 4>& row3, double l1, double l2) {
  const RationalQuarticTriangle triangle = boundaryPatchForJoin(surface, a, b);
  const std::array<Eigen::Vector3d, 4> row0 = surface.curve(a, b);
  const std::array<Eigen::Vector3d, 4> row1 = bicubicSecondRowFromTriangle(triangle, row0, l1, l2);
  BicubicNet net;
  for (int i = 0; i < 4; ++i) net[i] = {row0[i], row1[i], row2[i], row3[i]};
  return net;
}

BicubicPoint evaluateBicubic(const BicubicNet& net, double u, double w) {
  const auto bu = bernstein3(u), bw = bernstein3(w);
  const auto du = bernstein3Derivative(u), dw = bernstein3Derivative(w);
  BicubicPoint out{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      out.point += bu[i] * bw[j] * net[i][j];
      out.du += du[i] * bw[j] * net[i][j];
      out.dw += bu[i] * dw[j] * net[i][j];
    }
  }
  return out;
}

}  // namespace ffdkit::geometry::polyhedron
