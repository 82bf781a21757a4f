#pragma once

#include <Eigen/Core>

#include "ffdkit/cad/cad_model.h"

namespace ffdkit::cad {

/// Options of tessellate() (OpenCASCADE's BRepMesh_IncrementalMesh).
struct TessellationOptions {
  /// Largest distance between a triangle and its face, in model units; 0 = 1e-3 x the model's
  /// bounding-box diagonal.
  double linearDeflection = 0.0;
  /// Largest angle between the normals at a triangle's corners and the face's, radians.
  double angularDeflection = 0.5;
  /// > 0: no triangle edge longer than this, in model units (0 = no limit). BRepMesh leaves a
  /// plane with its boundary's points only, which a lattice then deforms as flat triangles; the
  /// longest edges are then bisected (the midpoints on the straight edges, in every triangle that
  /// has the edge, so faces stay joined) until none is longer.
  double maxEdgeLength = 0.0;
};

/// Triangles of a CAD model, one triangle per row of `triangles` (indices into `points`), oriented
/// outwards for solids. Each face has its own vertices (a face's edge vertices are not merged with
/// its neighbour's).
struct CadTriangles {
  Eigen::MatrixX3d points;          ///< #P x 3, world
  Eigen::MatrixX3i triangles;       ///< #T x 3
  Eigen::VectorXi partOfTriangle;   ///< #T, the part each triangle belongs to
};

/// Tessellates every face of every part. The triangulation is also stored on the model's faces
/// (OpenCASCADE keeps it with the shapes; a later call with a coarser deflection reuses it).
/// @throws CadError if the deflections are not > 0 and finite, maxEdgeLength is negative or not
///         finite or would make more than 20 million triangles, or meshing fails.
CadTriangles tessellate(const CadModel& model, const TessellationOptions& options = {});

/// The volume a closed, outward-oriented triangle set encloses (divergence theorem).
double enclosedVolume(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles);

}  // namespace ffdkit::cad
