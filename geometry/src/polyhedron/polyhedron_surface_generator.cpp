#include "ffdkit/geometry/polyhedron/polyhedron_surface_generator.h"

#include <string>

#include "ffdkit/geometry/polyhedron/builtin_meshes.h"
#include "ffdkit/geometry/polyhedron/polyhedron_error.h"

namespace ffdkit::geometry::polyhedron {

PolygonMesh resolvePolyhedron(const PolyhedronSurfaceParams& params) {
  return params.mesh ? *params.mesh : builtinMesh(params.builtinMesh);
}

TessellatedSurface generatePolyhedronSurfaceWithNormals(const PolyhedronSurfaceParams& params,
                                                       const PolyhedronSurfaceSampling& sampling) {
  if (sampling.samplesPerPatchSide < 1) {
    throw PolyhedronError("polyhedron-surface sampling: expected samplesPerPatchSide >= 1, got " +
                          std::to_string(sampling.samplesPerPatchSide));
  }
  PatchSurfaceOptions options;
  options.splitRule = params.splitRule;
  options.g1Scalars = params.g1Scalars;
  const PatchSurface surface = PatchSurface::build(resolvePolyhedron(params), params.tensions, options);
  return tessellate(surface, sampling.samplesPerPatchSide);
}

TriangleMesh generatePolyhedronSurface(const PolyhedronSurfaceParams& params,
                                       const PolyhedronSurfaceSampling& sampling) {
  return generatePolyhedronSurfaceWithNormals(params, sampling).mesh;
}

}  // namespace ffdkit::geometry::polyhedron
