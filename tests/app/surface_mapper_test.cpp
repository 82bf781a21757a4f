// The view's surface mapper (app/render/src/surface_mapper.h), rendered off screen (Xvfb): moving
// a surface's points does not build its index buffer again (VTK 9.1's own mapper does, every
// time), what it draws after the move is pixel for pixel what a fresh VTK mapper draws of the
// same data, new triangles are drawn, and its bounds are the points' bounds.
#include <gtest/gtest.h>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include "surface_mapper.h"

namespace ffdkit::app {
namespace {

// Counts the renders whose index buffer was built again (its cache key changed).
class IndexBufferProbe : public SurfaceMapper {
 public:
  static IndexBufferProbe* New();
  vtkTypeMacro(IndexBufferProbe, SurfaceMapper)
  int indexBuilds = 0;

 protected:
  void BuildIBO(vtkRenderer* renderer, vtkActor* actor, vtkPolyData* poly) override {
    vtkStateStorage before;
    before = IBOBuildState;
    SurfaceMapper::BuildIBO(renderer, actor, poly);
    if (before != IBOBuildState) ++indexBuilds;
  }
};
vtkStandardNewMacro(IndexBufferProbe);

// An n x n grid of squares in z = 0 over [-1, 1]^2, two triangles each.
vtkSmartPointer<vtkPolyData> grid(int n) {
  vtkNew<vtkPoints> points;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) points->InsertNextPoint(-1.0 + 2.0 * i / n, -1.0 + 2.0 * j / n, 0.0);
  vtkNew<vtkCellArray> cells;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const vtkIdType a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      const vtkIdType t0[3] = {a, b, d}, t1[3] = {a, d, c};
      cells->InsertNextCell(3, t0);
      cells->InsertNextCell(3, t1);
    }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);
  return poly;
}

// Bends the grid: z = amount * x * y at every point.
void bend(vtkPolyData* poly, double amount) {
  vtkPoints* points = poly->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i) {
    double p[3];
    points->GetPoint(i, p);
    points->SetPoint(i, p[0], p[1], amount * p[0] * p[1]);
  }
  points->Modified();
  poly->Modified();
}

// An off-screen window of 120 x 100 pixels looking at the grid obliquely.
struct OffscreenView {
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkActor> actor;
  explicit OffscreenView(vtkPolyDataMapper* mapper) {
    window->SetOffScreenRendering(true);
    window->SetSize(120, 100);
    window->AddRenderer(renderer);
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(2.0, -3.0, 2.5);
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetViewUp(0.0, 0.0, 1.0);
    renderer->ResetCameraClippingRange(-2, 2, -2, 2, -2, 2);
  }
  std::vector<unsigned char> pixels() {
    window->Render();
    vtkNew<vtkUnsignedCharArray> rgb;
    window->GetPixelData(0, 0, 119, 99, 0, rgb);
    return {rgb->GetPointer(0), rgb->GetPointer(0) + rgb->GetNumberOfValues()};
  }
};

TEST(SurfaceMapper, MovingThePointsKeepsTheIndexBufferAndDrawsWhatAFreshMapperDraws) {
  const auto poly = grid(40);
  vtkNew<IndexBufferProbe> mapper;
  mapper->SetInputData(poly);
  OffscreenView view(mapper);
  const std::vector<unsigned char> flat = view.pixels();
  ASSERT_EQ(mapper->indexBuilds, 1);
  for (double amount : {0.3, -0.5, 0.8}) {
    bend(poly, amount);
    const std::vector<unsigned char> drawn = view.pixels();
    EXPECT_EQ(mapper->indexBuilds, 1) << "bent by " << amount;
    // What VTK's own mapper draws of the same data from scratch, pixel for pixel.
    vtkNew<vtkPolyDataMapper> fresh;
    fresh->SetInputData(poly);
    OffscreenView reference(fresh);
    EXPECT_EQ(drawn, reference.pixels()) << "bent by " << amount;
  }
  EXPECT_NE(view.pixels(), flat);  // the bends are drawn
}

TEST(SurfaceMapper, NewTrianglesBuildTheIndexBufferAgain) {
  const auto poly = grid(20);
  vtkNew<IndexBufferProbe> mapper;
  mapper->SetInputData(poly);
  OffscreenView view(mapper);
  const std::vector<unsigned char> whole = view.pixels();
  // The first half of the triangles only.
  vtkCellArray* all = poly->GetPolys();
  vtkNew<vtkCellArray> half;
  for (vtkIdType t = 0; t < all->GetNumberOfCells() / 2; ++t) {
    vtkNew<vtkIdList> ids;
    all->GetCellAtId(t, ids);
    half->InsertNextCell(ids);
  }
  poly->SetPolys(half);
  const std::vector<unsigned char> drawn = view.pixels();
  EXPECT_EQ(mapper->indexBuilds, 2);
  EXPECT_NE(drawn, whole);
  vtkNew<vtkPolyDataMapper> fresh;
  fresh->SetInputData(poly);
  OffscreenView reference(fresh);
  EXPECT_EQ(drawn, reference.pixels());
}

TEST(SurfaceMapper, BoundsAreThePointsBoundsAndHoldTheCells) {
  const auto poly = grid(4);
  poly->GetPoints()->InsertNextPoint(5.0, -7.0, 3.0);  // used by no triangle
  poly->Modified();
  vtkNew<SurfaceMapper> mapper;
  mapper->SetInputData(poly);
  const double* bounds = mapper->GetBounds();
  const double expected[6] = {-1.0, 5.0, -7.0, 1.0, 0.0, 3.0};
  for (int k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(bounds[k], expected[k]) << k;
  double cells[6];
  poly->GetCellsBounds(cells);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_LE(bounds[2 * axis], cells[2 * axis]);
    EXPECT_GE(bounds[2 * axis + 1], cells[2 * axis + 1]);
  }
  bend(poly, 2.0);  // z = 2 x y: the unused point goes to z = -70, and the bounds follow it
  EXPECT_DOUBLE_EQ(mapper->GetBounds()[4], -70.0);
  EXPECT_DOUBLE_EQ(mapper->GetBounds()[5], 2.0);
}

}  // namespace
}  // namespace ffdkit::app
