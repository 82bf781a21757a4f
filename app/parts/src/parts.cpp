#include "ffdkit/parts/parts.h"

#include <numbers>

#include "ffdkit/scenes/primitive.h"

namespace ffdkit::app {
namespace {

using scenes::PrimitiveKind;

// Appends a primitive of unit size scaled by `scale` and moved by `placement` to `mesh`.
void add(geometry::TriangleMesh& mesh, PrimitiveKind kind, const Eigen::Vector3d& scale,
         const Eigen::Affine3d& placement = Eigen::Affine3d::Identity()) {
  scenes::PrimitiveOptions options;
  options.kind = kind;
  options.resolution = 24;
  options.placement = placement * Eigen::Scaling(scale);
  const geometry::TriangleMesh piece = scenes::makePrimitive(options);
  const Eigen::Index offset = mesh.vertices.rows();
  mesh.vertices.conservativeResize(offset + piece.vertices.rows(), 3);
  mesh.vertices.bottomRows(piece.vertices.rows()) = piece.vertices;
  mesh.triangles.conservativeResize(mesh.triangles.rows() + piece.triangles.rows(), 3);
  mesh.triangles.bottomRows(piece.triangles.rows()) = piece.triangles.array() + static_cast<int>(offset);
}

Eigen::Affine3d at(double x, double y, double z) { return Eigen::Affine3d(Eigen::Translation3d(x, y, z)); }
Eigen::Affine3d alongX(double x, double y, double z) {
  return at(x, y, z) * Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY());
}

}  // namespace

std::vector<std::string> partNames() { return {"crank", "lever", "screw", "wheel"}; }

std::optional<geometry::TriangleMesh> partMesh(std::string_view name) {
  geometry::TriangleMesh mesh;
  if (name == "crank") {  // a hub on the z axis, an arm along x, a knob standing up at its end
    add(mesh, PrimitiveKind::Cylinder, {0.25, 0.25, 0.2});
    add(mesh, PrimitiveKind::Cube, {0.5, 0.1, 0.08}, at(0.2, 0.0, 0.0));
    add(mesh, PrimitiveKind::Cylinder, {0.12, 0.12, 0.45}, at(0.42, 0.0, 0.22));
  } else if (name == "lever") {  // a long bar along x with a ball grip
    add(mesh, PrimitiveKind::Cylinder, {0.07, 0.07, 0.8}, alongX(0.0, 0.0, 0.0));
    add(mesh, PrimitiveKind::Sphere, {0.2, 0.2, 0.2}, at(0.4, 0.0, 0.0));
  } else if (name == "screw") {  // a threaded shaft on the z axis (tori as threads) with a head
    add(mesh, PrimitiveKind::Cylinder, {0.12, 0.12, 0.8});
    for (int i = 0; i < 6; ++i) add(mesh, PrimitiveKind::Torus, {0.3, 0.3, 0.08}, at(0.0, 0.0, -0.35 + 0.11 * i));
    add(mesh, PrimitiveKind::Cylinder, {0.5, 0.5, 0.12}, at(0.0, 0.0, 0.44));
  } else if (name == "wheel") {  // a rim, a hub and four spokes in the xy plane
    add(mesh, PrimitiveKind::Torus, {1.0, 1.0, 0.1});
    add(mesh, PrimitiveKind::Cylinder, {0.18, 0.18, 0.15});
    add(mesh, PrimitiveKind::Cube, {0.85, 0.05, 0.05});
    add(mesh, PrimitiveKind::Cube, {0.05, 0.85, 0.05});
  } else {
    return std::nullopt;
  }
  return mesh;
}

}  // namespace ffdkit::app
