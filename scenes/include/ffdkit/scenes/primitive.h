#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include <Eigen/Geometry>

#include "ffdkit/geometry/tessellation.h"
#include "ffdkit/meshio/read_limits.h"

namespace ffdkit::scenes {

/// Primitives for trying a widget out (Kuriyama 1996, sec. 6.4).
enum class PrimitiveKind { Sphere, Cylinder, Cube, Cone, Torus, Plane };

/// Stable lower-case name used in files and the UI ("sphere", "cylinder", ...).
std::string_view primitiveKindName(PrimitiveKind kind);
/// Inverse of primitiveKindName; std::nullopt for an unknown name.
std::optional<PrimitiveKind> parsePrimitiveKind(std::string_view name);

/// What makePrimitive builds: a sphere, cube, cylinder, cone, torus or plane, and its sampling.
struct PrimitiveOptions {
  PrimitiveKind kind = PrimitiveKind::Sphere;  ///< which primitive
  /// Subdivisions around (and along, where it applies); >= 3.
  int resolution = 32;
  /// Size of the primitive's bounding box before `placement`: the unit-size primitive is
  /// centred at the origin with its axis (cylinder, cone, torus normal, plane normal) along +z.
  double size = 1.0;
  /// World placement applied after building (rotation, translation, scale).
  Eigen::Affine3d placement = Eigen::Affine3d::Identity();
};

/// What makePrimitive builds, counted from the options without building: its grids' vertices
/// before the seams and poles are welded, and their triangles before collapsed ones are
/// dropped (upper bounds; exact for a plane). Zero for a resolution < 3.
struct PrimitiveSize {
  std::uint64_t vertices = 0;  ///< vertices before welding (an upper bound)
  std::uint64_t triangles = 0;  ///< triangles before collapsed ones are dropped (an upper bound)
};
PrimitiveSize primitiveSize(const PrimitiveOptions& options);

/// Charges what makePrimitive keeps (primitiveSize: its vertices as points, its triangles) to
/// `budget`, before it is built. @throws meshio::ReadLimitError naming the primitive:
/// "primitive sphere at resolution 4096: up to 8394753 vertices: ... (--max-points)".
void chargePrimitive(meshio::ReadBudget& budget, const PrimitiveOptions& options);

/// Bytes makePrimitive holds per vertex while it welds (its hash map's node and bucket, the point
/// beside it, vector growth) and per triangle (its list before the mesh), freed when it returns.
/// With the kept vertices and triangles they cover the measured peak: a sphere at resolution
/// 4096 is charged 1.54 GB in all; `ffdkit-cli validate` of a scene holding just it peaks at
/// 1.50 GB resident.
inline constexpr std::uint64_t kPrimitiveWeldBytesPerVertex = 112;
inline constexpr std::uint64_t kPrimitiveBuildBytesPerTriangle = 12;

/// A closed (or, for Plane, open) triangle mesh of the primitive.
/// @throws std::invalid_argument for resolution < 3 or size <= 0 / non-finite.
geometry::TriangleMesh makePrimitive(const PrimitiveOptions& options);

}  // namespace ffdkit::scenes
