#include "ffdkit/scenes/primitive.h"

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace ffdkit::scenes {
namespace {

constexpr double kPi = std::numbers::pi;

// Hash of a weld cell (three rounded coordinates).
struct CellHash {
  std::size_t operator()(const std::array<long long, 3>& key) const {
    std::size_t h = std::hash<long long>()(key[0]);
    h = h * 0x9E3779B97F4A7C15ull + std::hash<long long>()(key[1]);
    h = h * 0x9E3779B97F4A7C15ull + std::hash<long long>()(key[2]);
    return h ^ (h >> 29);
  }
};

// Collects triangles from parametric grids and welds coincident vertices, so that seams
// (the sphere's date line, the cube's edges, a cap's rim) share their vertices and the
// mesh is crack-free when a lattice deforms it.
class MeshBuilder {
 public:
  explicit MeshBuilder(double weldTolerance) : weldTolerance_(weldTolerance) {}

  int vertex(const Eigen::Vector3d& p) {
    const std::array<long long, 3> key{std::llround(p.x() / weldTolerance_),
                                       std::llround(p.y() / weldTolerance_),
                                       std::llround(p.z() / weldTolerance_)};
    auto [it, inserted] = ids_.try_emplace(key, static_cast<int>(points_.size()));
    if (inserted) points_.push_back(p);
    return it->second;
  }

  void triangle(int a, int b, int c) {
    if (a == b || b == c || c == a) return;  // collapsed at a pole or apex
    triangles_.push_back({a, b, c});
  }

  // A (nu+1) x (nv+1) grid of f(u, v), u, v in [0, 1], two triangles per quad, oriented so
  // that df/du x df/dv points outwards.
  void grid(int nu, int nv, const std::function<Eigen::Vector3d(double, double)>& f) {
    std::vector<int> ids((nu + 1) * (nv + 1));
    for (int j = 0; j <= nv; ++j)
      for (int i = 0; i <= nu; ++i) ids[j * (nu + 1) + i] = vertex(f(double(i) / nu, double(j) / nv));
    for (int j = 0; j < nv; ++j) {
      for (int i = 0; i < nu; ++i) {
        const int a = ids[j * (nu + 1) + i], b = ids[j * (nu + 1) + i + 1];
        const int c = ids[(j + 1) * (nu + 1) + i + 1], d = ids[(j + 1) * (nu + 1) + i];
        triangle(a, b, c);
        triangle(a, c, d);
      }
    }
  }

  geometry::TriangleMesh finish(const Eigen::Affine3d& placement) const {
    geometry::TriangleMesh mesh;
    mesh.vertices.resize(static_cast<Eigen::Index>(points_.size()), 3);
    for (std::size_t i = 0; i < points_.size(); ++i)
      mesh.vertices.row(static_cast<Eigen::Index>(i)) = (placement * points_[i]).transpose();
    mesh.triangles.resize(static_cast<Eigen::Index>(triangles_.size()), 3);
    const bool flips = placement.linear().determinant() < 0;
    for (std::size_t t = 0; t < triangles_.size(); ++t) {
      const auto& tri = triangles_[t];
      mesh.triangles.row(static_cast<Eigen::Index>(t)) =
          flips ? Eigen::RowVector3i(tri[0], tri[2], tri[1]) : Eigen::RowVector3i(tri[0], tri[1], tri[2]);
    }
    return mesh;
  }

 private:
  double weldTolerance_;
  // Hashed, not ordered: the vertex order is the order of first insertion either way, and a
  // sphere at resolution 4096 welds 8.4M vertices.
  std::unordered_map<std::array<long long, 3>, int, CellHash> ids_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::array<int, 3>> triangles_;
};

Eigen::Vector3d onCircle(double radius, double turn, double z) {
  return {radius * std::cos(2 * kPi * turn), radius * std::sin(2 * kPi * turn), z};
}

// The parametric grids of the unit primitive: calls grid(nu, nv, f) for each, f(u, v) for u, v in
// [0, 1]. The one home of each kind's shape, for building (makePrimitive) and for counting
// (primitiveSize).
template <class Grid>
void primitiveGrids(PrimitiveKind kind, int n, Grid&& grid) {
  const double r = 0.5;  // unit-size primitives fill [-0.5, 0.5]^3
  switch (kind) {
    case PrimitiveKind::Sphere:
      grid(n, std::max(2, n / 2), [&](double u, double v) {
        const double polar = kPi * (1.0 - v);  // v = 0 south pole, v = 1 north pole
        return onCircle(r * std::sin(polar), u, r * std::cos(polar));
      });
      break;
    case PrimitiveKind::Cylinder: {
      const int rings = std::max(1, n / 4);
      grid(n, n, [&](double u, double v) { return onCircle(r, u, v - r); });
      grid(n, rings, [&](double u, double v) { return onCircle(r * (1 - v), u, r); });
      grid(n, rings, [&](double u, double v) { return onCircle(r * v, u, -r); });
      break;
    }
    case PrimitiveKind::Cone: {
      const int rings = std::max(1, n / 4);
      grid(n, n, [&](double u, double v) { return onCircle(r * (1 - v), u, v - r); });
      grid(n, rings, [&](double u, double v) { return onCircle(r * v, u, -r); });
      break;
    }
    case PrimitiveKind::Torus: {
      const double tube = 0.15, centre = r - tube;
      grid(n, std::max(3, n / 2), [&](double u, double v) {
        const double ring = centre + tube * std::cos(2 * kPi * v);
        return onCircle(ring, u, tube * std::sin(2 * kPi * v));
      });
      break;
    }
    case PrimitiveKind::Plane:
      grid(n, n, [&](double u, double v) { return Eigen::Vector3d(u - r, v - r, 0.0); });
      break;
    case PrimitiveKind::Cube:
      // Each face is an n x n grid so that a lattice has vertices to move.
      for (int axis = 0; axis < 3; ++axis) {
        for (double side : {-1.0, 1.0}) {
          const int a = (axis + 1) % 3, c = (axis + 2) % 3;
          grid(n, n, [&](double u, double v) {
            Eigen::Vector3d p;
            p[axis] = side * r;
            // Swap the in-face axes on the negative side so that every face faces outwards.
            p[side > 0 ? a : c] = u - r;
            p[side > 0 ? c : a] = v - r;
            return p;
          });
        }
      }
      break;
  }
}

}  // namespace

std::string_view primitiveKindName(PrimitiveKind kind) {
  switch (kind) {
    case PrimitiveKind::Sphere: return "sphere";
    case PrimitiveKind::Cylinder: return "cylinder";
    case PrimitiveKind::Cube: return "cube";
    case PrimitiveKind::Cone: return "cone";
    case PrimitiveKind::Torus: return "torus";
    case PrimitiveKind::Plane: return "plane";
  }
  return "unknown";
}

std::optional<PrimitiveKind> parsePrimitiveKind(std::string_view name) {
  for (auto k : {PrimitiveKind::Sphere, PrimitiveKind::Cylinder, PrimitiveKind::Cube,
                 PrimitiveKind::Cone, PrimitiveKind::Torus, PrimitiveKind::Plane}) {
    if (primitiveKindName(k) == name) return k;
  }
  return std::nullopt;
}

PrimitiveSize primitiveSize(const PrimitiveOptions& options) {
  PrimitiveSize size;
  if (options.resolution < 3) return size;
  primitiveGrids(options.kind, options.resolution, [&](int nu, int nv, const auto&) {
    size.vertices += std::uint64_t(nu + 1) * std::uint64_t(nv + 1);
    size.triangles += 2 * std::uint64_t(nu) * std::uint64_t(nv);
  });
  return size;
}

void chargePrimitive(meshio::ReadBudget& budget, const PrimitiveOptions& options) {
  const PrimitiveSize size = primitiveSize(options);
  const std::string what =
      "primitive " + std::string(primitiveKindName(options.kind)) + " at resolution " + std::to_string(options.resolution);
  budget.chargePoints(size.vertices, what + ": up to " + std::to_string(size.vertices) + " vertices");
  budget.chargeBytes(size.triangles, 3 * sizeof(int), what + ": its triangles");
}

geometry::TriangleMesh makePrimitive(const PrimitiveOptions& options) {
  const int n = options.resolution;
  if (n < 3) {
    throw std::invalid_argument("primitive '" + std::string(primitiveKindName(options.kind)) +
                                "': resolution must be >= 3, got " + std::to_string(n));
  }
  if (!(options.size > 0.0) || !std::isfinite(options.size)) {
    throw std::invalid_argument("primitive '" + std::string(primitiveKindName(options.kind)) +
                                "': size must be positive and finite, got " + std::to_string(options.size));
  }
  if (!options.placement.matrix().allFinite()) {
    throw std::invalid_argument("primitive placement has non-finite entries");
  }
  MeshBuilder b(1e-9);
  primitiveGrids(options.kind, n, [&](int nu, int nv, const auto& f) { b.grid(nu, nv, f); });
  return b.finish(options.placement * Eigen::Scaling(options.size));
}

}  // namespace ffdkit::scenes
