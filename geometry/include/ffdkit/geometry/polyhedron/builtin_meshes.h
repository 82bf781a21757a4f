#pragma once

#include <string>
#include <vector>

#include "ffdkit/geometry/polyhedron/polygon_mesh.h"

namespace ffdkit::geometry::polyhedron {

/// Built-in test polyhedra, all counter-clockwise from outside.

/// Regular tetrahedron (1,1,1), (1,-1,-1), (-1,1,-1), (-1,-1,1).
PolygonMesh tetrahedronMesh();
/// Cube [-1,1]^3, 6 quads.
PolygonMesh cubeMesh();
/// Octahedron with vertices +-e_i, 8 triangles.
PolygonMesh octahedronMesh();
/// Hexagonal prism: corners (cos 2 pi k/6, sin 2 pi k/6, z), z in {0, 1}; 6 quads, 2 hexagons.
/// Vertices 0..5 are the bottom ring (z = 0), 6..11 the top ring (z = 1); the last face is the
/// top hexagon. Stand-in for Kuriyama 1996, Fig 4-3.
PolygonMesh hexagonalPrismMesh();
/// The hexagonal prism without its top hexagon (open, Kuriyama 1996, Fig 4-12).
PolygonMesh openHexagonalPrismMesh();
/// L-shaped prism: L polygon (0,0),(3,0),(3,1),(1,1),(1,3),(0,3), z in {0, 0.5}. The L faces
/// are concave, so their split points fall outside (Kuriyama 1996, Fig 4-17/4-21). Face 0 is the
/// bottom L (z = 0), face 1 the top L.
PolygonMesh lShapedPrismMesh();
/// The L-shaped prism with each L face split into the convex quads (0,0),(3,0),(3,1),(1,1) and
/// (0,0),(1,1),(1,3),(0,3) (Kuriyama 1996, Fig 4-18/4-22). Faces 0, 1 are the bottom quads.
PolygonMesh lShapedPrismConvexMesh();
/// Unit sphere: two poles and `rings - 1` latitude rings of `segments` points; triangles at the
/// poles, quads elsewhere ("sphere segments x rings").
/// @throws PolyhedronError if segments < 3 or rings < 2.
PolygonMesh sphereMesh(int segments, int rings);
/// Torus with major radius R, tube radius r, `around` x `tube` quads.
/// @throws PolyhedronError if around < 3, tube < 3 or not 0 < r < R.
PolygonMesh torusMesh(int around, int tube, double majorRadius = 2.0, double tubeRadius = 0.8);

/// Names accepted by builtinMesh(): tetrahedron, cube, octahedron, hexagonal-prism,
/// open-hexagonal-prism, l-prism, l-prism-convex.
std::vector<std::string> builtinMeshNames();
/// The built-in polyhedron called `name`.
/// @throws PolyhedronError for an unknown name (the message lists the known names).
PolygonMesh builtinMesh(const std::string& name);

}  // namespace ffdkit::geometry::polyhedron
