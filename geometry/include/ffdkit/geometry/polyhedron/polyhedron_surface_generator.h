#pragma once

#include <optional>
#include <string>

#include "ffdkit/geometry/polyhedron/patch_surface.h"
#include "ffdkit/geometry/polyhedron/polygon_mesh.h"
#include "ffdkit/geometry/polyhedron/surface_tessellation.h"
#include "ffdkit/geometry/polyhedron/tensions.h"
#include "ffdkit/geometry/tessellation.h"

namespace ffdkit::geometry::polyhedron {

/// Parameters of the `polyhedron-surface` generator (issue 10): plain data that a scene keeps
/// so that the surface can be regenerated at another sampling density.
struct PolyhedronSurfaceParams {
  /// Built-in polyhedron (builtinMeshNames()); used when `mesh` is empty. Default "cube".
  std::string builtinMesh = "cube";
  /// Explicit polyhedron (e.g. read from a mesh file by the caller); overrides builtinMesh.
  std::optional<PolygonMesh> mesh;
  /// Vertex/edge tensions; default alpha = 0, beta = 1 everywhere (Nielson network).
  Tensions tensions;
  /// Split-leg rule; default the thesis face-based rule (S2).
  SplitLegRule splitRule = SplitLegRule::ThesisFaceBased;
  /// G1 scalars; default per-edge (the G1 configuration).
  G1Scalars g1Scalars = G1Scalars::PerEdge;
};

/// Sampling density of the tessellation.
struct PolyhedronSurfaceSampling {
  int samplesPerPatchSide = 8;  ///< n >= 1: n^2 triangles per patch; default 8
};

/// The polyhedron the params describe (mesh, or the built-in one).
/// @throws PolyhedronError for an unknown built-in name.
PolygonMesh resolvePolyhedron(const PolyhedronSurfaceParams& params);

/// Builds the surface and returns the welded tessellation with per-vertex normals.
/// Deterministic. @throws PolyhedronError (bad mesh, tensions, sampling; message says which).
TessellatedSurface generatePolyhedronSurfaceWithNormals(const PolyhedronSurfaceParams& params,
                                                       const PolyhedronSurfaceSampling& sampling = {});

/// The deformable object handed to scenes: generatePolyhedronSurfaceWithNormals(...).mesh.
TriangleMesh generatePolyhedronSurface(const PolyhedronSurfaceParams& params,
                                       const PolyhedronSurfaceSampling& sampling = {});

}  // namespace ffdkit::geometry::polyhedron
