#pragma once

// The VTK data of an object SceneView draws (private to ffdkit::render): its points in float32,
// as the GPU draws them, relative to an origin of the object (the actor is placed there), so that
// their rounding is relative to the object's size, not to its distance from the world origin (a
// scan in map coordinates), and its cells with 32-bit indices. The view only draws these arrays:
// picking, measuring and export read the exact double points of the model and the deformer
// (scenes::SceneDeformer::points), never the view's. Per vertex of a closed triangle mesh (two
// triangles per vertex) this holds 12 bytes of points and 32 of cells, against 24 and 64 for
// double points and VTK's default 64-bit cells.

#include <Eigen/Core>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include "ffdkit/meshio/mesh_data.h"

namespace ffdkit::app::object_arrays {

/// Writes `points` - `origin` (#points x 3, double) into `drawn` as float32 (each coordinate of
/// the difference rounded to the nearest float), resized to #points and marked modified. In
/// parallel for large meshes.
void setFloatPoints(vtkPoints* drawn, const Eigen::MatrixX3d& points, const Eigen::Vector3d& origin);

/// The inverse of setFloatPoints: the drawn points plus `origin`, in world coordinates (#points x 3).
Eigen::MatrixX3d worldPoints(vtkPoints* drawn, const Eigen::Vector3d& origin);

/// The polydata of an object's mesh at `points` (#points x 3) relative to `origin` (as
/// setFloatPoints): float32 points, its triangles
/// and its segments (with neither, one vertex cell per point) as cells with 32-bit offsets and
/// connectivity.
vtkSmartPointer<vtkPolyData> objectPolyData(const meshio::MeshData& mesh, const Eigen::MatrixX3d& points,
                                            const Eigen::Vector3d& origin);

}  // namespace ffdkit::app::object_arrays
