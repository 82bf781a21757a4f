#pragma once
// The boundary surface of a volume mesh: the faces that belong to one cell only, as triangles
// facing out of the mesh. It is what the app draws of a volume mesh; the lattice still deforms
// every point of the mesh (the surface's triangles index the volume mesh's own points).

#include <Eigen/Core>

#include "ffdkit/meshio/element_cells.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/meshio/openfoam.h"
#include "ffdkit/meshio/volume_mesh.h"

namespace ffdkit::meshio {

/// The faces of `cells` that no other cell shares, fan-triangulated, each turned to face out of
/// its cell (by the corner orders of element_cells.h); #T x 3 point indices. A face is matched by
/// its corner set, so two cells that share a face in either orientation hide it. A 2D cell
/// (triangle, quadrilateral) is a face itself: it comes out as it is (one or two triangles).
Eigen::MatrixX3i boundaryTriangles(const ElementCells& cells);

/// The boundary faces of an OpenFOAM polyMesh (those after the internal ones, which make up its
/// patches), fan-triangulated; OpenFOAM's faces point out of their owner, so the triangles face
/// out of the mesh. #T x 3 point indices.
Eigen::MatrixX3i boundaryTriangles(const PolyMeshCells& cells);

/// The surface drawn for `mesh`: every point of the mesh (#P x 3, so that deforming the surface
/// deforms the whole mesh) and its boundary triangles; a format whose cells are not read (Elmer,
/// LS-DYNA, Kratos, a UNV file without elements) gives its points alone, a point cloud. Call it
/// before VolumeMesh::takePoints.
MeshData volumeMeshSurface(const VolumeMesh& mesh);

}  // namespace ffdkit::meshio
