#include "scene_view_shapes.h"

#include "ffdkit/render/scene_view.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <vtkArrowSource.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCubeSource.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkParametricFunctionSource.h>
#include <vtkParametricTorus.h>
#include <vtkPointData.h>
#include <vtkTransform.h>
#include <vtkUnsignedCharArray.h>

#include "ffdkit/ffd/lattice.h"
#include "ffdkit/render/curvature_comb.h"
#include "ffdkit/parts/parts.h"
#include "ffdkit/widgets/glyph_shape.h"

namespace ffdkit::app::scene_view_shapes {

using widgets::AffineKind;
using widgets::GlyphShape;

void setPoints(vtkPoints* vtkPts, const Eigen::MatrixX3d& points) {
  vtkPts->SetNumberOfPoints(points.rows());
  auto* data = static_cast<double*>(vtkPts->GetVoidPointer(0));
  // Memory bound (a drag step rewrites every point of a large mesh): both cores' bandwidth.
#pragma omp parallel for schedule(static) if (points.rows() >= 65536)
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    data[3 * i] = points(i, 0);
    data[3 * i + 1] = points(i, 1);
    data[3 * i + 2] = points(i, 2);
  }
  vtkPts->Modified();
}

VertexFaces vertexFaces(const Eigen::MatrixX3i& triangles, Eigen::Index pointCount) {
  VertexFaces vf;
  vf.start.assign(static_cast<std::size_t>(pointCount) + 1, 0);
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int c = 0; c < 3; ++c) ++vf.start[static_cast<std::size_t>(triangles(t, c)) + 1];
  for (std::size_t i = 1; i < vf.start.size(); ++i) vf.start[i] += vf.start[i - 1];
  vf.faces.resize(static_cast<std::size_t>(vf.start.back()));
  std::vector<int> fill(vf.start.begin(), vf.start.end() - 1);
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int c = 0; c < 3; ++c) vf.faces[static_cast<std::size_t>(fill[static_cast<std::size_t>(triangles(t, c))]++)] = static_cast<int>(t);
  return vf;
}

void faceAreaVectors(const Eigen::MatrixX3i& triangles, const Eigen::MatrixX3d& points,
                     std::vector<Eigen::Vector3f>& faceNormals) {
  perFace(triangles, points, faceNormals,
          [](int, int, int, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) -> Eigen::Vector3d { return e1.cross(e2); });
}

void gatherNormals(const VertexFaces& vf, const std::vector<Eigen::Vector3f>& faceNormals, Eigen::Index n, float* out,
                   Eigen::MatrixX3f* sums) {
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3f sum = vertexSum(vf, faceNormals, i);
    if (sums) sums->row(i) = sum.transpose();
    const float length = sum.norm();
    const Eigen::Vector3f v = length > 0.0f ? Eigen::Vector3f(sum / length) : Eigen::Vector3f::UnitZ();
    out[3 * i] = v.x();
    out[3 * i + 1] = v.y();
    out[3 * i + 2] = v.z();
  }
}

// Area-weighted vertex normals of a triangle mesh into `normals` (#points x 3 floats).
// Done here rather than with vtkPolyDataNormals, which costs ~0.4 s per frame on 1M vertices
// (it rebuilds cell links every time); a drag step has to stay within the engine's budget.
void updateNormals(vtkFloatArray* normals, const Eigen::MatrixX3i& triangles, const VertexFaces& vf,
                   const Eigen::MatrixX3d& points, std::vector<Eigen::Vector3f>& faceNormals) {
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(points.rows());
  faceAreaVectors(triangles, points, faceNormals);
  gatherNormals(vf, faceNormals, points.rows(), normals->GetPointer(0), nullptr);
  normals->Modified();
}

// Zebra stripes: texture coordinate s = stripes * angle(n, d) / pi per vertex from the vertex
// normals, over a repeated two-texel (dark, light) texture without interpolation, so the stripe
// edges stay sharp between vertices.
void updateZebraCoordinates(vtkFloatArray* tcoords, vtkFloatArray* normals, const Eigen::Vector3d& direction,
                            int stripes) {
  const Eigen::Index n = normals->GetNumberOfTuples();
  tcoords->SetNumberOfComponents(2);
  tcoords->SetNumberOfTuples(n);
  const float* in = normals->GetPointer(0);
  float* out = tcoords->GetPointer(0);
  const Eigen::Vector3f d = direction.normalized().cast<float>();
  const float perRadian = static_cast<float>(stripes / std::numbers::pi);
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) {
    const float c = std::clamp(in[3 * i] * d.x() + in[3 * i + 1] * d.y() + in[3 * i + 2] * d.z(), -1.0f, 1.0f);
    out[2 * i] = perRadian * std::acos(c);
    out[2 * i + 1] = 0.5f;
  }
  tcoords->Modified();
}

vtkSmartPointer<vtkTexture> zebraTexture() {
  vtkNew<vtkImageData> image;
  image->SetDimensions(2, 1, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* texel = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int c = 0; c < 3; ++c) {
    texel[c] = static_cast<unsigned char>(std::lround(255.0 * kZebraDark[c]));
    texel[3 + c] = static_cast<unsigned char>(std::lround(255.0 * kZebraLight[c]));
  }
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetInputData(image);
  texture->InterpolateOff();
  texture->RepeatOn();
  texture->EdgeClampOff();
  return texture;
}

namespace {

std::vector<Eigen::MatrixX3d> chainCurves(const std::vector<std::vector<int>>& chains, const Eigen::MatrixX3d& points,
                                          std::vector<bool>& closed) {
  std::vector<Eigen::MatrixX3d> curves;
  closed.clear();
  for (const auto& chain : chains) {
    closed.push_back(chain.size() > 2 && chain.front() == chain.back());
    const std::size_t count = closed.back() ? chain.size() - 1 : chain.size();
    Eigen::MatrixX3d curve(static_cast<Eigen::Index>(count), 3);
    for (std::size_t k = 0; k < count; ++k) curve.row(static_cast<Eigen::Index>(k)) = points.row(chain[k]);
    curves.push_back(std::move(curve));
  }
  return curves;
}

}  // namespace

// Tooth length per unit curvature: the longest tooth of the undeformed curve is `scale` times
// its bounding-box diagonal (a straight curve: scale * diagonal^2), so that any curve shows a
// readable comb and a deformation shows as a change of it.
double combFactor(const std::vector<std::vector<int>>& chains, const Eigen::MatrixX3d& restPoints, double scale,
                  double diagonal) {
  std::vector<bool> closed;
  const auto curves = chainCurves(chains, restPoints, closed);
  double maxCurvature = 0.0;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const CurvatureComb comb = curvatureComb(curves[c], closed[c], 0.0);
    if (comb.curvature.size() > 0) maxCurvature = std::max(maxCurvature, comb.curvature.maxCoeff());
  }
  return maxCurvature * diagonal > 1e-9 ? scale * diagonal / maxCurvature : scale * diagonal * diagonal;
}

// The curvature comb of every chain of a curve object's segments, as lines: the teeth and the
// polyline through their tips.
vtkSmartPointer<vtkPolyData> combPolyData(const std::vector<std::vector<int>>& chains, const Eigen::MatrixX3d& points,
                                          double scale) {
  vtkNew<vtkPoints> vtkPts;
  vtkPts->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  std::vector<bool> closedChains;
  const auto curves = chainCurves(chains, points, closedChains);
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const bool closed = closedChains[c];
    const CurvatureComb comb = curvatureComb(curves[c], closed, scale);
    const vtkIdType first = vtkPts->GetNumberOfPoints();
    const vtkIdType teeth = comb.bases.rows();
    for (vtkIdType k = 0; k < teeth; ++k) vtkPts->InsertNextPoint(comb.bases(k, 0), comb.bases(k, 1), comb.bases(k, 2));
    for (vtkIdType k = 0; k < teeth; ++k) vtkPts->InsertNextPoint(comb.tips(k, 0), comb.tips(k, 1), comb.tips(k, 2));
    // At most ~120 teeth drawn per curve (a dense polyline would fill the comb in); the tip
    // polyline goes through every sample.
    const vtkIdType stride = std::max<vtkIdType>(1, (teeth + 119) / 120);
    for (vtkIdType k = 0; k < teeth; k += stride) {
      const vtkIdType tooth[2] = {first + k, first + teeth + k};
      lines->InsertNextCell(2, tooth);
    }
    if (teeth >= 2) {
      lines->InsertNextCell(teeth + (closed ? 1 : 0));
      for (vtkIdType k = 0; k < teeth; ++k) lines->InsertCellPoint(first + teeth + k);
      if (closed) lines->InsertCellPoint(first + teeth);
    }
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(vtkPts);
  polyData->SetLines(lines);
  return polyData;
}

vtkSmartPointer<vtkPolyData> toPolyData(const meshio::MeshData& mesh, const Eigen::MatrixX3d& points) {
  vtkNew<vtkPoints> vtkPts;
  vtkPts->SetDataTypeToDouble();
  setPoints(vtkPts, points);
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(vtkPts);
  vtkNew<vtkCellArray> triangles;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const vtkIdType ids[3] = {mesh.triangles(t, 0), mesh.triangles(t, 1), mesh.triangles(t, 2)};
    triangles->InsertNextCell(3, ids);
  }
  polyData->SetPolys(triangles);
  vtkNew<vtkCellArray> lines;
  for (Eigen::Index s = 0; s < mesh.segments.rows(); ++s) {
    const vtkIdType ids[2] = {mesh.segments(s, 0), mesh.segments(s, 1)};
    lines->InsertNextCell(2, ids);
  }
  polyData->SetLines(lines);
  if (mesh.triangles.rows() == 0 && mesh.segments.rows() == 0) {
    vtkNew<vtkCellArray> vertices;  // a point cloud
    for (vtkIdType i = 0; i < points.rows(); ++i) vertices->InsertNextCell(1, &i);
    polyData->SetVerts(vertices);
  }
  return polyData;
}

// Lattice points as vertices and the grid lines between neighbours as lines.
vtkSmartPointer<vtkPolyData> latticePolyData(const Eigen::MatrixX3d& points, const Eigen::Vector3i& n) {
  vtkNew<vtkPoints> vtkPts;
  vtkPts->SetDataTypeToDouble();
  setPoints(vtkPts, points);
  vtkNew<vtkCellArray> vertices;
  for (vtkIdType i = 0; i < points.rows(); ++i) vertices->InsertNextCell(1, &i);
  vtkNew<vtkCellArray> lines;
  auto id = [&](int i, int j, int k) -> vtkIdType { return i + n.x() * (j + n.y() * k); };
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const Eigen::Vector3i here(i, j, k);
        for (int axis = 0; axis < 3; ++axis) {
          Eigen::Vector3i next = here;
          next[axis] += 1;
          if (next[axis] >= n[axis]) continue;
          const vtkIdType ends[2] = {id(i, j, k), id(next.x(), next.y(), next.z())};
          lines->InsertNextCell(2, ends);
        }
      }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(vtkPts);
  polyData->SetVerts(vertices);
  polyData->SetLines(lines);
  return polyData;
}

// The six boundary sides of a lattice as quads between neighbouring grid points (drawn
// translucent for a selected lattice).
Eigen::Vector3d foldColour(ffd::CellFolding verdict) {
  return verdict == ffd::CellFolding::Folds ? Eigen::Vector3d(0.95, 0.12, 0.10) : Eigen::Vector3d(1.0, 0.70, 0.05);
}

vtkSmartPointer<vtkPolyData> foldTintPolyData(const ffd::Lattice& lattice, const std::array<int, 3>& cellCounts,
                                              const std::vector<ffd::CellFolding>& cells, int samples) {
  vtkNew<vtkPoints> vtkPts;
  vtkPts->SetDataTypeToDouble();
  vtkNew<vtkCellArray> quads;
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("Colors");
  colours->SetNumberOfComponents(3);
  const int n = std::max(samples, 1);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    if (cells[c] == ffd::CellFolding::Positive) continue;
    const int cell[3] = {static_cast<int>(c % std::size_t(cellCounts[0])),
                         static_cast<int>(c / std::size_t(cellCounts[0]) % std::size_t(cellCounts[1])),
                         static_cast<int>(c / std::size_t(cellCounts[0]) / std::size_t(cellCounts[1]))};
    Eigen::Vector3d lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = lattice.axis(a).cellMin(cell[a]);
      hi[a] = lattice.axis(a).cellMax(cell[a]);
    }
    const Eigen::Vector3d rgb = 255.0 * foldColour(cells[c]);
    // Each side of the cell's parameter box, sampled on an (n+1) x (n+1) grid and mapped.
    for (int normal = 0; normal < 3; ++normal) {
      const int a = (normal + 1) % 3, b = (normal + 2) % 3;
      for (double side : {lo[normal], hi[normal]}) {
        const vtkIdType first = vtkPts->GetNumberOfPoints();
        for (int j = 0; j <= n; ++j)
          for (int i = 0; i <= n; ++i) {
            Eigen::Vector3d uvw;
            uvw[normal] = side;
            uvw[a] = lo[a] + (hi[a] - lo[a]) * i / n;
            uvw[b] = lo[b] + (hi[b] - lo[b]) * j / n;
            const Eigen::Vector3d world = lattice.frame() * lattice.evaluate(uvw);
            vtkPts->InsertNextPoint(world.x(), world.y(), world.z());
          }
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            const vtkIdType q = first + j * (n + 1) + i;
            const vtkIdType ids[4] = {q, q + 1, q + n + 2, q + n + 1};
            quads->InsertNextCell(4, ids);
            colours->InsertNextTuple3(rgb.x(), rgb.y(), rgb.z());
          }
      }
    }
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(vtkPts);
  polyData->SetPolys(quads);
  polyData->GetCellData()->SetScalars(colours);
  return polyData;
}

vtkSmartPointer<vtkPolyData> sphereCirclesPolyData(const Eigen::Vector3d& centre, double radius, int segments) {
  vtkNew<vtkPoints> vtkPts;
  vtkPts->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  for (int normal = 0; normal < 3; ++normal) {
    const int a = (normal + 1) % 3, b = (normal + 2) % 3;
    const vtkIdType first = vtkPts->GetNumberOfPoints();
    for (int s = 0; s < segments; ++s) {
      const double t = 2.0 * std::numbers::pi * s / segments;
      Eigen::Vector3d p = centre;
      p[a] += radius * std::cos(t);
      p[b] += radius * std::sin(t);
      vtkPts->InsertNextPoint(p.x(), p.y(), p.z());
    }
    lines->InsertNextCell(segments + 1);
    for (int s = 0; s <= segments; ++s) lines->InsertCellPoint(first + s % segments);
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(vtkPts);
  polyData->SetLines(lines);
  return polyData;
}

vtkSmartPointer<vtkPolyData> latticeFacesPolyData(const Eigen::MatrixX3d& points, const Eigen::Vector3i& n) {
  vtkNew<vtkPoints> vtkPts;
  vtkPts->SetDataTypeToDouble();
  setPoints(vtkPts, points);
  vtkNew<vtkCellArray> quads;
  auto id = [&](const Eigen::Vector3i& g) -> vtkIdType { return g.x() + n.x() * (g.y() + n.y() * g.z()); };
  for (int normal = 0; normal < 3; ++normal) {
    const int a = (normal + 1) % 3, b = (normal + 2) % 3;
    for (int side : {0, n[normal] - 1})
      for (int i = 0; i + 1 < n[a]; ++i)
        for (int j = 0; j + 1 < n[b]; ++j) {
          Eigen::Vector3i g = Eigen::Vector3i::Zero();
          g[normal] = side;
          g[a] = i;
          g[b] = j;
          Eigen::Vector3i ga = g, gb = g, gab = g;
          ga[a] += 1;
          gb[b] += 1;
          gab[a] += 1;
          gab[b] += 1;
          const vtkIdType ids[4] = {id(g), id(ga), id(gab), id(gb)};
          quads->InsertNextCell(4, ids);
        }
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(vtkPts);
  polyData->SetPolys(quads);
  return polyData;
}

vtkSmartPointer<vtkPolyData> pointsPolyData(const Eigen::MatrixX3d& points) {
  vtkNew<vtkPoints> vtkPts;
  vtkPts->SetDataTypeToDouble();
  setPoints(vtkPts, points);
  vtkNew<vtkCellArray> vertices;
  for (vtkIdType i = 0; i < points.rows(); ++i) vertices->InsertNextCell(1, &i);
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(vtkPts);
  polyData->SetVerts(vertices);
  return polyData;
}

// The glyph shapes in the widget frame, at size 1, as widgets::GlyphShape gives them (what
// WidgetModel::pick hits).
static_assert(GlyphShape::arrowLength == 1.0, "vtkArrowSource makes arrows of length 1");
vtkSmartPointer<vtkPolyData> glyphShape(const widgets::Glyph& glyph, AffineKind kind) {
  if (auto part = partMesh(glyph.shape)) {
    meshio::MeshData mesh;
    mesh.triangles = part->triangles;
    Eigen::MatrixX3d points = part->vertices;
    for (Eigen::Index i = 0; i < points.rows(); ++i)
      points.row(i) = (glyph.partPlacement * Eigen::Vector3d(points.row(i).transpose())).transpose();
    return toPolyData(mesh, points);
  }
  const std::string shape = glyph.shape.empty() ? std::string(widgets::affineKindName(kind)) : glyph.shape;
  if (shape == "ring" || (shape == "rotate")) {
    vtkNew<vtkParametricTorus> torus;
    torus->SetRingRadius(GlyphShape::ringRadius);
    torus->SetCrossSectionRadius(GlyphShape::ringTubeRadius);
    vtkNew<vtkParametricFunctionSource> source;
    source->SetParametricFunction(torus);
    source->SetUResolution(48);
    source->SetVResolution(8);
    source->Update();
    return source->GetOutput();
  }
  if (shape == "cube" || shape == "scale") {
    vtkNew<vtkCubeSource> cube;
    cube->SetXLength(2.0 * GlyphShape::cubeHalfWidth);
    cube->SetYLength(2.0 * GlyphShape::cubeHalfWidth);
    cube->SetZLength(2.0 * GlyphShape::cubeHalfWidth);
    cube->Update();
    return cube->GetOutput();
  }
  vtkNew<vtkArrowSource> arrow;
  arrow->SetShaftRadius(GlyphShape::arrowShaftRadius);  // vtkArrowSource: length 1 along +x
  arrow->SetTipRadius(GlyphShape::arrowTipRadius);
  arrow->SetTipLength(GlyphShape::arrowTipLength);
  arrow->SetShaftResolution(16);
  arrow->SetTipResolution(24);
  arrow->Update();
  return arrow->GetOutput();
}

Eigen::Vector3d kindColour(AffineKind kind) {
  switch (kind) {
    case AffineKind::Translate: return {0.95, 0.30, 0.30};
    case AffineKind::Rotate: return {0.30, 0.85, 0.40};
    case AffineKind::Scale: return {0.35, 0.55, 1.00};
  }
  return {1.0, 1.0, 1.0};
}

}  // namespace ffdkit::app::scene_view_shapes
