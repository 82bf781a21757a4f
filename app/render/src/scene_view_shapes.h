#pragma once

// The VTK data SceneView draws (private to ffdkit::render): object meshes with their normals and
// zebra coordinates, curvature combs, lattices, points and widget glyphs. SceneView decides
// what to build and when; these functions only build it.

#include <array>
#include <vector>

#include <Eigen/Core>
#include <vtkFloatArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTexture.h>

#include "ffdkit/ffd/fold_check.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::app::scene_view_shapes {

/// Writes `points` (#points x 3) into `vtkPts` (resized, marked modified).
void setPoints(vtkPoints* vtkPts, const Eigen::MatrixX3d& points);

/// Which triangles touch each vertex (compressed rows), built once per object: normals are
/// then gathered per vertex without write races, in parallel.
struct VertexFaces {
  std::vector<int> start;  ///< #points + 1
  std::vector<int> faces;
};

VertexFaces vertexFaces(const Eigen::MatrixX3i& triangles, Eigen::Index pointCount);

/// out[t] = value(a, b, c, e1, e2) for each triangle t = (a, b, c) of `triangles` over
/// `points` (#points x 3, column-major), with e1 = pb - pa, e2 = pc - pa in double; the result
/// stored as float. In parallel (each t written once).
template <class FaceValue>
void perFace(const Eigen::MatrixX3i& triangles, const Eigen::MatrixX3d& points, std::vector<Eigen::Vector3f>& out,
             FaceValue value) {
  const Eigen::Index n = points.rows();
  const Eigen::Index m = triangles.rows();
  out.resize(static_cast<std::size_t>(m));
  const double* x = points.data();  // column-major: x, y, z columns
  const double* y = x + n;
  const double* z = y + n;
#pragma omp parallel for schedule(static)
  for (Eigen::Index t = 0; t < m; ++t) {
    const int a = triangles(t, 0), b = triangles(t, 1), c = triangles(t, 2);
    const Eigen::Vector3d pa(x[a], y[a], z[a]);
    const Eigen::Vector3d e1 = Eigen::Vector3d(x[b], y[b], z[b]) - pa;
    const Eigen::Vector3d e2 = Eigen::Vector3d(x[c], y[c], z[c]) - pa;
    out[static_cast<std::size_t>(t)] = value(a, b, c, e1, e2).template cast<float>();
  }
}

/// The sum of `faces` over the triangles of vertex i (vf).
inline Eigen::Vector3f vertexSum(const VertexFaces& vf, const std::vector<Eigen::Vector3f>& faces, Eigen::Index i) {
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  for (int k = vf.start[static_cast<std::size_t>(i)]; k < vf.start[static_cast<std::size_t>(i) + 1]; ++k)
    sum += faces[static_cast<std::size_t>(vf.faces[static_cast<std::size_t>(k)])];
  return sum;
}

/// The two passes of updateNormals: each triangle's area vector (b - a) x (c - a), in double,
/// stored as float ...
void faceAreaVectors(const Eigen::MatrixX3i& triangles, const Eigen::MatrixX3d& points,
                     std::vector<Eigen::Vector3f>& faceNormals);
/// ... then per vertex the sum over its triangles (vf), normalised into out[3 i .. 3 i + 2]
/// (+z where the sum is 0); the sums themselves into the rows of `sums` (n x 3) when not null. No write races.
void gatherNormals(const VertexFaces& vf, const std::vector<Eigen::Vector3f>& faceNormals, Eigen::Index n, float* out,
                   Eigen::MatrixX3f* sums);

/// Area-weighted vertex normals of a triangle mesh into `normals` (#points x 3 floats);
/// `faceNormals` is scratch space kept between calls.
void updateNormals(vtkFloatArray* normals, const Eigen::MatrixX3i& triangles, const VertexFaces& vf,
                   const Eigen::MatrixX3d& points, std::vector<Eigen::Vector3f>& faceNormals);

/// Zebra texture coordinates from the vertex normals (see zebraTexture).
void updateZebraCoordinates(vtkFloatArray* tcoords, vtkFloatArray* normals, const Eigen::Vector3d& direction,
                            int stripes);

/// The repeated two-texel (dark, light) stripe texture, not interpolated.
vtkSmartPointer<vtkTexture> zebraTexture();

/// Tooth length per unit curvature of a curve object's comb (chains of rest points).
double combFactor(const std::vector<std::vector<int>>& chains, const Eigen::MatrixX3d& restPoints, double scale,
                  double diagonal);

/// The curvature comb of every chain, as lines: the teeth and the polyline through their tips.
vtkSmartPointer<vtkPolyData> combPolyData(const std::vector<std::vector<int>>& chains, const Eigen::MatrixX3d& points,
                                          double scale);

/// An object's mesh (its triangles or segments) at `points` (#points x 3).
vtkSmartPointer<vtkPolyData> toPolyData(const meshio::MeshData& mesh, const Eigen::MatrixX3d& points);

/// Lattice points as vertices and the grid lines between neighbours as lines (n: counts).
vtkSmartPointer<vtkPolyData> latticePolyData(const Eigen::MatrixX3d& points, const Eigen::Vector3i& n);

/// The six boundary sides of a lattice as quads (drawn translucent for a selected lattice).
vtkSmartPointer<vtkPolyData> latticeFacesPolyData(const Eigen::MatrixX3d& points, const Eigen::Vector3i& n);

/// The colour of a fold-over verdict's tint: red where the cell folds, amber where it is unknown.
Eigen::Vector3d foldColour(ffd::CellFolding verdict);

/// The cells of `lattice` (world: its frame applied) whose verdict (`cells`, flat index
/// cu + cellCounts[0] (cv + cellCounts[1] cw), ffd::checkFolding) is not Positive, as the six
/// sides of each cell's image under the lattice map, each side `samples` x `samples` quads,
/// coloured per cell by foldColour (RGB unsigned-char cell scalars).
vtkSmartPointer<vtkPolyData> foldTintPolyData(const ffd::Lattice& lattice, const std::array<int, 3>& cellCounts,
                                              const std::vector<ffd::CellFolding>& cells, int samples = 8);

/// The soft selection's reach: three great circles (normal to x, y, z) of the sphere of `radius`
/// about `centre`, as lines of `segments` pieces each.
vtkSmartPointer<vtkPolyData> sphereCirclesPolyData(const Eigen::Vector3d& centre, double radius, int segments = 96);

/// Points as vertices.
vtkSmartPointer<vtkPolyData> pointsPolyData(const Eigen::MatrixX3d& points);

/// A glyph's shape in the widget frame at size 1, as widgets::GlyphShape gives it (what
/// WidgetModel::pick hits).
vtkSmartPointer<vtkPolyData> glyphShape(const widgets::Glyph& glyph, widgets::AffineKind kind);

/// The colour of an affine widget kind (translate red, rotate green, scale blue).
Eigen::Vector3d kindColour(widgets::AffineKind kind);

}  // namespace ffdkit::app::scene_view_shapes
