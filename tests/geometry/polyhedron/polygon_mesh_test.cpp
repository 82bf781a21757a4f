#include "ffdkit/geometry/polyhedron/polygon_mesh.h"

#include <limits>

#include <gtest/gtest.h>

#include "ffdkit/geometry/polyhedron/builtin_meshes.h"
#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {
namespace {

std::string validationError(const PolygonMesh& mesh) {
  try {
    validatePolygonMesh(mesh);
  } catch (const PolyhedronError& e) {
    return e.what();
  }
  return "";
}

TEST(PolygonMesh, AcceptsEveryBuiltinMesh) {
  for (const auto& name : builtinMeshNames()) EXPECT_NO_THROW(validatePolygonMesh(builtinMesh(name))) << name;
}

TEST(PolygonMesh, RejectsValenceTwoVertexOnAnEdge) {
  PolygonMesh mesh = cubeMesh();
  mesh.vertices.conservativeResize(9, 3);
  mesh.vertices.row(8) = 0.5 * (mesh.vertices.row(0) + mesh.vertices.row(1));
  for (auto& f : mesh.faces) {
    for (std::size_t k = 0; k < f.size(); ++k) {
      const int a = f[k], b = f[(k + 1) % f.size()];
      if ((a == 0 && b == 1) || (a == 1 && b == 0)) {
        f.insert(f.begin() + static_cast<long>(k) + 1, 8);
        break;
      }
    }
  }
  const std::string message = validationError(mesh);
  EXPECT_NE(message.find("vertex 8 has valence 2"), std::string::npos) << message;
}

TEST(PolygonMesh, RejectsValenceTwoBoundaryCorner) {
  PolygonMesh quad;
  quad.vertices.resize(4, 3);
  quad.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  quad.faces = {{0, 1, 2, 3}};
  const std::string message = validationError(quad);
  EXPECT_NE(message.find("valence 2 on the boundary"), std::string::npos) << message;
}

TEST(PolygonMesh, RejectsDegenerateFaces) {
  PolygonMesh collinear = tetrahedronMesh();
  collinear.vertices.row(2) = 0.5 * (collinear.vertices.row(0) + collinear.vertices.row(1));
  EXPECT_NE(validationError(collinear).find("degenerate face"), std::string::npos);
  PolygonMesh coincident = cubeMesh();
  coincident.vertices.row(1) = coincident.vertices.row(0);
  EXPECT_NE(validationError(coincident).find("coincide"), std::string::npos);
}

TEST(PolygonMesh, RejectsNonFiniteCoordinates) {
  PolygonMesh mesh = cubeMesh();
  mesh.vertices(3, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(validationError(mesh).find("vertex 3: expected finite"), std::string::npos);
}

TEST(PolygonMesh, BoundingBoxDiagonalOfCube) { EXPECT_NEAR(boundingBoxDiagonal(cubeMesh().vertices), 2.0 * std::sqrt(3.0), 1e-15); }

}  // namespace
}  // namespace ffdkit::geometry::polyhedron
