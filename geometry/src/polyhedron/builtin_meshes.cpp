#include "ffdkit/geometry/polyhedron/builtin_meshes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {
namespace {

// For convex solids only: makes every face counter-clockwise seen from outside, so that the
// hand-written corner lists below need not be checked one by one.
PolygonMesh orientedOutward(PolygonMesh mesh) {
  const Eigen::Vector3d centre = mesh.vertices.colwise().mean();
  for (auto& face : mesh.faces) {
    Eigen::Vector3d area = Eigen::Vector3d::Zero();
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < face.size(); ++k) {
      const Eigen::Vector3d a = mesh.vertices.row(face[k]);
      const Eigen::Vector3d b = mesh.vertices.row(face[(k + 1) % face.size()]);
      area += a.cross(b);
      centroid += a;
    }
    centroid /= static_cast<double>(face.size());
    if (area.dot(centroid - centre) < 0.0) std::reverse(face.begin(), face.end());
  }
  return mesh;
}

PolygonMesh prism(const std::vector<Eigen::Vector2d>& outline, double z0, double z1,
                  const std::vector<std::vector<int>>& capPieces, bool withTop) {
  const int n = static_cast<int>(outline.size());
  PolygonMesh mesh;
  mesh.vertices.resize(2 * n, 3);
  for (int k = 0; k < n; ++k) {
    mesh.vertices.row(k) << outline[k].x(), outline[k].y(), z0;
    mesh.vertices.row(n + k) << outline[k].x(), outline[k].y(), z1;
  }
  // Outline is counter-clockwise in the xy-plane: the bottom caps are seen from below.
  for (const auto& piece : capPieces) {
    std::vector<int> bottom(piece.rbegin(), piece.rend());
    mesh.faces.push_back(bottom);
  }
  for (int k = 0; k < n; ++k) mesh.faces.push_back({k, (k + 1) % n, n + (k + 1) % n, n + k});
  if (withTop) {
    for (const auto& piece : capPieces) {
      std::vector<int> top;
      for (int c : piece) top.push_back(n + c);
      mesh.faces.push_back(top);
    }
  }
  return mesh;
}

std::vector<Eigen::Vector2d> hexagon() {
  std::vector<Eigen::Vector2d> outline;
  for (int k = 0; k < 6; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 6.0;
    outline.emplace_back(std::cos(a), std::sin(a));
  }
  return outline;
}

std::vector<Eigen::Vector2d> lOutline() { return {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}}; }

}  // namespace

PolygonMesh tetrahedronMesh() {
  PolygonMesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  mesh.faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  return orientedOutward(mesh);
}

PolygonMesh cubeMesh() {
  PolygonMesh mesh;
  mesh.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) mesh.vertices.row(i) << (i & 1 ? 1 : -1), (i & 2 ? 1 : -1), (i & 4 ? 1 : -1);
  mesh.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return orientedOutward(mesh);
}

PolygonMesh octahedronMesh() {
  PolygonMesh mesh;
  mesh.vertices.resize(6, 3);
  mesh.vertices << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  for (int x : {0, 1}) {
    for (int y : {2, 3}) {
      for (int z : {4, 5}) mesh.faces.push_back({x, y, z});
    }
  }
  return orientedOutward(mesh);
}

PolygonMesh hexagonalPrismMesh() { return prism(hexagon(), 0.0, 1.0, {{0, 1, 2, 3, 4, 5}}, true); }

PolygonMesh openHexagonalPrismMesh() { return prism(hexagon(), 0.0, 1.0, {{0, 1, 2, 3, 4, 5}}, false); }

PolygonMesh lShapedPrismMesh() { return prism(lOutline(), 0.0, 0.5, {{0, 1, 2, 3, 4, 5}}, true); }

PolygonMesh lShapedPrismConvexMesh() {
  return prism(lOutline(), 0.0, 0.5, {{0, 1, 2, 3}, {0, 3, 4, 5}}, true);
}

PolygonMesh sphereMesh(int segments, int rings) {
  if (segments < 3 || rings < 2) {
    throw PolyhedronError("sphere mesh: expected segments >= 3 and rings >= 2, got " + std::to_string(segments) +
                          " x " + std::to_string(rings));
  }
  PolygonMesh mesh;
  const int ringVertices = segments * (rings - 1);
  mesh.vertices.resize(ringVertices + 2, 3);
  mesh.vertices.row(0) << 0, 0, 1;
  for (int r = 1; r < rings; ++r) {
    const double theta = std::numbers::pi * r / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / segments;
      mesh.vertices.row(1 + (r - 1) * segments + j) << std::sin(theta) * std::cos(phi),
          std::sin(theta) * std::sin(phi), std::cos(theta);
    }
  }
  const int south = ringVertices + 1;
  mesh.vertices.row(south) << 0, 0, -1;
  auto at = [&](int r, int j) { return 1 + (r - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) {
    mesh.faces.push_back({0, at(1, j), at(1, j + 1)});
    for (int r = 1; r + 1 < rings; ++r) mesh.faces.push_back({at(r, j), at(r + 1, j), at(r + 1, j + 1), at(r, j + 1)});
    mesh.faces.push_back({south, at(rings - 1, j + 1), at(rings - 1, j)});
  }
  return orientedOutward(mesh);
}

PolygonMesh torusMesh(int around, int tube, double majorRadius, double tubeRadius) {
  if (around < 3 || tube < 3 || !(tubeRadius > 0.0) || !(tubeRadius < majorRadius)) {
    throw PolyhedronError("torus mesh: expected around >= 3, tube >= 3 and 0 < r < R, got " + std::to_string(around) +
                          " x " + std::to_string(tube) + ", R " + std::to_string(majorRadius) + ", r " +
                          std::to_string(tubeRadius));
  }
  PolygonMesh mesh;
  mesh.vertices.resize(around * tube, 3);
  for (int i = 0; i < around; ++i) {
    const double u = 2.0 * std::numbers::pi * i / around;
    for (int j = 0; j < tube; ++j) {
      const double v = 2.0 * std::numbers::pi * j / tube;
      mesh.vertices.row(i * tube + j) << (majorRadius + tubeRadius * std::cos(v)) * std::cos(u),
          (majorRadius + tubeRadius * std::cos(v)) * std::sin(u), tubeRadius * std::sin(v);
    }
  }
  // (+u, +v) is counter-clockwise seen from outside: d/du x d/dv is the outward normal.
  auto at = [&](int i, int j) { return (i % around) * tube + (j % tube); };
  for (int i = 0; i < around; ++i) {
    for (int j = 0; j < tube; ++j) mesh.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
  }
  return mesh;
}

std::vector<std::string> builtinMeshNames() {
  return {"tetrahedron", "cube", "octahedron", "hexagonal-prism", "open-hexagonal-prism", "l-prism", "l-prism-convex"};
}

PolygonMesh builtinMesh(const std::string& name) {
  if (name == "tetrahedron") return tetrahedronMesh();
  if (name == "cube") return cubeMesh();
  if (name == "octahedron") return octahedronMesh();
  if (name == "hexagonal-prism") return hexagonalPrismMesh();
  if (name == "open-hexagonal-prism") return openHexagonalPrismMesh();
  if (name == "l-prism") return lShapedPrismMesh();
  if (name == "l-prism-convex") return lShapedPrismConvexMesh();
  std::string known;
  for (const auto& n : builtinMeshNames()) known += (known.empty() ? "" : ", ") + n;
  throw PolyhedronError("unknown built-in polyhedron '" + name + "' (known: " + known + ")");
}

}  // namespace ffdkit::geometry::polyhedron
