// Back-face culling of closed surfaces (SurfaceMapper::cullsBackFaces, closed_surface.h), drawn off
// screen (Mesa's GL under Xvfb): where the mapper culls, every pixel is the one VTK draws without
// culling except a few at silhouettes, where the surface is seen edge-on (0 to 3 of 76,800 in the
// eight views below): there a back face and the front face it meets at the silhouette are closer
// than the rasteriser's rounding, and VTK's own image shows the back face (a shade of the grazing
// surface) that the geometry hides; culled, the front face is drawn. Where a back face can be seen
// (an open surface, a surface facing inwards, the eye inside, a near plane cutting the surface, a
// lattice that may fold) the mapper does not cull, and every pixel is the same.
#include <cmath>
#include <numbers>
#include <string>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include "closed_surface.h"
#include "scene_view_shapes.h"
#include "surface_mapper.h"

namespace ffdkit::app {
namespace {

struct Surface {
  Eigen::MatrixX3d points, normals;
  Eigen::MatrixX3i triangles;
};

// A torus round the z axis (radii `major`, `minor`), or with major = 0 a sphere of radius `minor`
// (its poles single points), its triangles counter-clockwise seen from outside, `rings` x
// `segments` quads; with `open`, only the triangles of the upper half (z > 0 at their centre).
Surface ringOrSphere(double major, double minor, int rings, int segments, bool open = false) {
  const bool sphere = major == 0.0;
  Surface s;
  std::vector<Eigen::Vector3d> points, normals;
  auto at = [&](int i, int j) {  // i round the tube (or pole to pole), j round the z axis
    const double phi = 2.0 * std::numbers::pi * j / segments;
    const double theta = sphere ? std::numbers::pi * i / rings : 2.0 * std::numbers::pi * i / rings;
    const Eigen::Vector3d n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    const Eigen::Vector3d centre = major * Eigen::Vector3d(std::cos(phi), std::sin(phi), 0.0);
    return std::pair{Eigen::Vector3d(centre + minor * n), n};
  };
  std::vector<std::vector<int>> index(std::size_t(rings + 1), std::vector<int>(std::size_t(segments)));
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j < segments; ++j) {
      if ((sphere && (i == 0 || i == rings) && j > 0) || (!sphere && i == rings)) {
        index[std::size_t(i)][std::size_t(j)] = index[std::size_t(sphere ? i : 0)][std::size_t(sphere ? 0 : j)];
        continue;
      }
      const auto [p, n] = at(i, j);
      index[std::size_t(i)][std::size_t(j)] = static_cast<int>(points.size());
      points.push_back(p);
      normals.push_back(n);
    }
  std::vector<Eigen::Vector3i> triangles;
  auto add = [&](int a, int b, int c) {
    if (a == b || b == c || c == a) return;
    if (open && (points[std::size_t(a)] + points[std::size_t(b)] + points[std::size_t(c)]).z() <= 0.0) return;
    triangles.emplace_back(a, b, c);
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const int jn = (j + 1) % segments;
      const int a = index[std::size_t(i)][std::size_t(j)], b = index[std::size_t(i + 1)][std::size_t(j)];
      const int c = index[std::size_t(i + 1)][std::size_t(jn)], d = index[std::size_t(i)][std::size_t(jn)];
      add(a, b, c);  // theta grows along a -> b, phi along b -> c: outward for both shapes
      add(a, c, d);
    }
  s.points.resize(Eigen::Index(points.size()), 3);
  s.normals.resize(Eigen::Index(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    s.points.row(Eigen::Index(i)) = points[i];
    s.normals.row(Eigen::Index(i)) = normals[i];
  }
  s.triangles.resize(Eigen::Index(triangles.size()), 3);
  for (std::size_t t = 0; t < triangles.size(); ++t) s.triangles.row(Eigen::Index(t)) = triangles[t];
  return s;
}

Surface flipped(Surface s) {
  s.triangles.col(1).swap(s.triangles.col(2));
  s.normals = -s.normals;
  return s;
}

bool closed(const Surface& s) {
  return closedOutwardSurface(s.points, s.triangles, scene_view_shapes::vertexFaces(s.triangles, s.points.rows()));
}

vtkSmartPointer<vtkPolyData> polyData(const Surface& s) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  for (Eigen::Index i = 0; i < s.points.rows(); ++i) {
    points->InsertNextPoint(s.points(i, 0), s.points(i, 1), s.points(i, 2));
    normals->InsertNextTuple3(s.normals(i, 0), s.normals(i, 1), s.normals(i, 2));
  }
  vtkNew<vtkCellArray> cells;
  for (Eigen::Index t = 0; t < s.triangles.rows(); ++t) {
    const vtkIdType ids[3] = {s.triangles(t, 0), s.triangles(t, 1), s.triangles(t, 2)};
    cells->InsertNextCell(3, ids);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);
  poly->GetPointData()->SetNormals(normals);
  return poly;
}

// Where the camera is: outside looking at the origin from `eye` (clipping range fitted to the
// surface, perspective or parallel), or at the origin looking along +x (inside a sphere).
struct Camera {
  Eigen::Vector3d eye{2.5, -4.0, 3.0};
  bool parallel = false;
  bool inside = false;
};

// The surface drawn in an off-screen window of 320 x 240 pixels with two SurfaceMappers, one told
// the surface is closed (closedOutwardSurface) and one not (never culls).
struct Drawn {
  std::vector<unsigned char> culled, reference;
  int culledDraws = 0;
};

std::vector<unsigned char> draw(vtkPolyData* poly, SurfaceMapper* mapper, const Camera& where, bool sphereInside,
                                double nearPlane = 0.0) {
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(true);
  window->SetSize(320, 240);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  mapper->SetInputData(poly);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.8, 0.6, 0.3);
  actor->GetProperty()->SetSpecular(0.2);
  actor->GetProperty()->SetSpecularPower(30);
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.2, 0.3);
  vtkCamera* camera = renderer->GetActiveCamera();
  if (sphereInside) {
    camera->SetPosition(0.0, 0.0, 0.0);
    camera->SetFocalPoint(1.0, 0.2, 0.1);
  } else {
    camera->SetPosition(where.eye.data());
    camera->SetFocalPoint(0.0, 0.0, 0.0);
  }
  camera->SetViewUp(0.0, 0.0, 1.0);
  camera->SetParallelProjection(where.parallel);
  camera->SetParallelScale(1.6);
  renderer->ResetCameraClippingRange();
  if (nearPlane > 0.0) camera->SetClippingRange(nearPlane, 100.0);
  window->Render();
  vtkNew<vtkUnsignedCharArray> rgb;
  window->GetPixelData(0, 0, 319, 239, 0, rgb);
  return {rgb->GetPointer(0), rgb->GetPointer(0) + rgb->GetNumberOfValues()};
}

Drawn drawBothWays(const Surface& s, const Camera& where = {}, double nearPlane = 0.0, bool foldFree = true) {
  const auto poly = polyData(s);
  Drawn d;
  vtkNew<SurfaceMapper> culling, plain;
  culling->setClosedSurface(closed(s));
  culling->setFoldFree(foldFree);
  d.culled = draw(poly, culling, where, where.inside, nearPlane);
  d.reference = draw(poly, plain, where, where.inside, nearPlane);
  d.culledDraws = culling->culledDraws();
  return d;
}

// Pixels of `a` and `b` (RGB, 3 bytes a pixel) that differ.
int differences(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
  EXPECT_EQ(a.size(), b.size());
  int pixels = 0;
  for (std::size_t i = 0; i + 2 < a.size() && i + 2 < b.size(); i += 3)
    if (a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2]) ++pixels;
  return pixels;
}

// Pixels that are not the background.
int covered(const std::vector<unsigned char>& rgb) {
  int n = 0;
  for (std::size_t i = 0; i + 2 < rgb.size(); i += 3)
    if (!(rgb[i] == 26 && rgb[i + 1] == 51 && rgb[i + 2] == 77)) ++n;
  return n;
}

TEST(ClosedSurface, TellsAClosedOutwardSurfaceFromOpenInwardAndNonManifoldOnes) {
  EXPECT_TRUE(closed(ringOrSphere(0.0, 1.0, 40, 64)));
  EXPECT_TRUE(closed(ringOrSphere(1.0, 0.4, 48, 96)));
  EXPECT_FALSE(closed(ringOrSphere(0.0, 1.0, 40, 64, true)));  // open: a rim of single edges
  EXPECT_FALSE(closed(flipped(ringOrSphere(0.0, 1.0, 40, 64))));  // closed, facing inwards
  EXPECT_FALSE(closed(flipped(ringOrSphere(1.0, 0.4, 48, 96))));
  Surface inconsistent = ringOrSphere(0.0, 1.0, 40, 64);  // one triangle turned over
  inconsistent.triangles.row(100) = Eigen::Vector3i(inconsistent.triangles(100, 0), inconsistent.triangles(100, 2),
                                                    inconsistent.triangles(100, 1));
  EXPECT_FALSE(closed(inconsistent));
  Surface doubled = ringOrSphere(0.0, 1.0, 40, 64);  // a triangle twice: three triangles at its edges
  doubled.triangles.conservativeResize(doubled.triangles.rows() + 1, 3);
  doubled.triangles.row(doubled.triangles.rows() - 1) = doubled.triangles.row(7);
  EXPECT_FALSE(closed(doubled));
}

TEST(SurfaceCulling, AClosedSurfaceSeenFromOutsideIsDrawnAsWithoutCullingButAFewSilhouettePixels) {
  // A sphere and a torus (whose far side shows through its hole, behind back faces of its near
  // side), fine enough that many triangles are under a pixel at the silhouettes; perspective and
  // parallel projections, from two sides.
  for (const Surface& s : {ringOrSphere(0.0, 1.0, 200, 400), ringOrSphere(1.0, 0.4, 240, 480)})
    for (bool parallel : {false, true})
      for (const Eigen::Vector3d& eye : {Eigen::Vector3d(2.5, -4.0, 3.0), Eigen::Vector3d(-0.5, 1.0, -5.0)}) {
        Camera where;
        where.eye = eye;
        where.parallel = parallel;
        const Drawn d = drawBothWays(s, where);
        EXPECT_EQ(d.culledDraws, 1) << s.points.rows() << " points, parallel " << parallel;
        EXPECT_GT(covered(d.reference), 10000);
        // Every pixel the same but a few of 76,800 at silhouettes, seen edge-on.
        const int differing = differences(d.culled, d.reference);
        EXPECT_LE(differing, 8) << s.points.rows() << " points, parallel " << parallel;
        std::printf("%ld points, parallel %d: %d of 76800 pixels differ\n", long(s.points.rows()), int(parallel),
                    differing);
      }
}

TEST(SurfaceCulling, AnOpenSurfaceOrOneFacingInwardsIsNotCulled) {
  // The open half sphere seen from below shows its inside, its back faces; so does a closed
  // sphere whose triangles face inwards, everywhere.
  Camera below;
  below.eye = Eigen::Vector3d(0.5, -1.0, -4.0);
  for (const Surface& s : {ringOrSphere(0.0, 1.0, 100, 200, true), flipped(ringOrSphere(0.0, 1.0, 100, 200))}) {
    const Drawn d = drawBothWays(s, below);
    EXPECT_EQ(d.culledDraws, 0);
    EXPECT_GT(covered(d.reference), 10000);
    EXPECT_TRUE(d.culled == d.reference);
  }
}

TEST(SurfaceCulling, AnEyeInsideOrANearPlaneCuttingTheSurfaceDrawsItsBackFaces) {
  const Surface sphere = ringOrSphere(0.0, 1.0, 100, 200);
  Camera inside;
  inside.inside = true;
  const Drawn fromInside = drawBothWays(sphere, inside);
  EXPECT_EQ(fromInside.culledDraws, 0);
  EXPECT_EQ(covered(fromInside.reference), 320 * 240);  // back faces everywhere
  EXPECT_TRUE(fromInside.culled == fromInside.reference);
  // The eye outside, the near plane through the sphere: the cut shows its inside.
  const double distance = Camera{}.eye.norm();
  const Drawn cut = drawBothWays(sphere, Camera{}, distance - 0.3);
  EXPECT_EQ(cut.culledDraws, 0);
  EXPECT_TRUE(cut.culled == cut.reference);
  // The same near plane in front of the sphere: culled again.
  EXPECT_EQ(drawBothWays(sphere, Camera{}, distance - 2.0).culledDraws, 1);
}

TEST(SurfaceCulling, NothingIsCulledWhileALatticeMayFold) {
  const Drawn d = drawBothWays(ringOrSphere(0.0, 1.0, 40, 80), Camera{}, 0.0, false);
  EXPECT_EQ(d.culledDraws, 0);
  EXPECT_TRUE(d.culled == d.reference);
}

}  // namespace
}  // namespace ffdkit::app
