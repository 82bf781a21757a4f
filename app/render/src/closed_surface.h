#pragma once

// Whether a triangle mesh bounds a solid and faces out of it (private to ffdkit::render): what
// SurfaceMapper needs to cull back faces without changing a pixel (surface_mapper.h). Eigen only.

#include <Eigen/Core>

#include "scene_view_shapes.h"

namespace ffdkit::app {

/// True when `triangles` (#triangles x 3, indexing the rows of `points`, #points x 3) are a closed,
/// consistently oriented surface facing outwards: every directed edge (a, b) of a triangle belongs
/// to no other triangle and its reverse (b, a) to exactly one (so each edge joins exactly two
/// triangles, which run along it in opposite directions), no triangle repeats a corner, and the
/// enclosed signed volume, the sum of pa . (pb x pc) / 6 over the triangles, is positive (the
/// triangles run counter-clockwise seen from outside, as the GL's front faces do). `faces` lists
/// the triangles at each point (vertexFaces(triangles, #points)). In parallel; O(#triangles) for
/// bounded vertex valence. It cannot tell a surface that passes through itself.
bool closedOutwardSurface(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles,
                          const scene_view_shapes::VertexFaces& faces);

}  // namespace ffdkit::app
