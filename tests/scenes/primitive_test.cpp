#include "ffdkit/scenes/primitive.h"

#include <map>
#include <stdexcept>
#include <utility>

#include <gtest/gtest.h>

namespace ffdkit::scenes {
namespace {

constexpr PrimitiveKind kAllKinds[] = {PrimitiveKind::Sphere, PrimitiveKind::Cylinder, PrimitiveKind::Cube,
                                       PrimitiveKind::Cone,   PrimitiveKind::Torus,    PrimitiveKind::Plane};

// Each undirected edge of a closed, consistently oriented mesh is used once in each direction.
void expectClosedAndConsistentlyOriented(const geometry::TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t)
    for (int e = 0; e < 3; ++e) ++directed[{mesh.triangles(t, e), mesh.triangles(t, (e + 1) % 3)}];
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " used " << count << " times";
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << "boundary edge " << edge.first << "-" << edge.second;
  }
}

TEST(Primitive, ClosedPrimitivesAreWatertightAndOriented) {
  for (PrimitiveKind kind : kAllKinds) {
    if (kind == PrimitiveKind::Plane) continue;
    SCOPED_TRACE(std::string(primitiveKindName(kind)));
    expectClosedAndConsistentlyOriented(makePrimitive({.kind = kind, .resolution = 12}));
  }
}

TEST(Primitive, SphereVerticesLieOnTheSphere) {
  const auto mesh = makePrimitive({.kind = PrimitiveKind::Sphere, .resolution = 24, .size = 2.0});
  ASSERT_GT(mesh.vertices.rows(), 100);
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i) EXPECT_NEAR(mesh.vertices.row(i).norm(), 1.0, 1e-12);
}

TEST(Primitive, FitsTheUnitBoxAndFollowsPlacement) {
  for (PrimitiveKind kind : kAllKinds) {
    Eigen::Affine3d placement = Eigen::Translation3d(1, 2, 3) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY());
    const auto plain = makePrimitive({.kind = kind, .resolution = 8});
    const auto placed = makePrimitive({.kind = kind, .resolution = 8, .placement = placement});
    EXPECT_LE(plain.vertices.cwiseAbs().maxCoeff(), 0.5 + 1e-12);
    ASSERT_EQ(plain.vertices.rows(), placed.vertices.rows());
    for (Eigen::Index i = 0; i < plain.vertices.rows(); ++i) {
      const Eigen::Vector3d expected = placement * Eigen::Vector3d(plain.vertices.row(i));
      EXPECT_NEAR((expected - Eigen::Vector3d(placed.vertices.row(i))).norm(), 0.0, 1e-12);
    }
  }
}

TEST(Primitive, NamesRoundTrip) {
  for (PrimitiveKind kind : kAllKinds) EXPECT_EQ(parsePrimitiveKind(primitiveKindName(kind)), kind);
  EXPECT_FALSE(parsePrimitiveKind("teapot").has_value());
}

TEST(Primitive, RejectsBadOptions) {
  EXPECT_THROW(makePrimitive({.kind = PrimitiveKind::Sphere, .resolution = 2}), std::invalid_argument);
  EXPECT_THROW(makePrimitive({.kind = PrimitiveKind::Cube, .size = 0.0}), std::invalid_argument);
  EXPECT_THROW(makePrimitive({.kind = PrimitiveKind::Cube, .size = std::nan("")}), std::invalid_argument);
}

}  // namespace
}  // namespace ffdkit::scenes
