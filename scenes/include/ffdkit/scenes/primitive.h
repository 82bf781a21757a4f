#pragma once

#include <optional>
#include <string_view>

#include <Eigen/Geometry>

#include "ffdkit/geometry/tessellation.h"

namespace ffdkit::scenes {

/// Primitives for trying a widget out (seed 001 l.2417).
enum class PrimitiveKind { Sphere, Cylinder, Cube, Cone, Torus, Plane };

/// Stable lower-case name used in files and the UI ("sphere", "cylinder", ...).
std::string_view primitiveKindName(PrimitiveKind kind);
/// Inverse of primitiveKindName; std::nullopt for an unknown name.
std::optional<PrimitiveKind> parsePrimitiveKind(std::string_view name);

struct PrimitiveOptions {
  PrimitiveKind kind = PrimitiveKind::Sphere;
  /// Subdivisions around (and along, where it applies); >= 3.
  int resolution = 32;
  /// Size of the primitive's bounding box before `placement`: the unit-size primitive is
  /// centred at the origin with its axis (cylinder, cone, torus normal, plane normal) along +z.
  double size = 1.0;
  /// World placement applied after building (rotation, translation, scale).
  Eigen::Affine3d placement = Eigen::Affine3d::Identity();
};

/// A closed (or, for Plane, open) triangle mesh of the primitive.
/// @throws std::invalid_argument for resolution < 3 or size <= 0 / non-finite.
geometry::TriangleMesh makePrimitive(const PrimitiveOptions& options);

}  // namespace ffdkit::scenes
