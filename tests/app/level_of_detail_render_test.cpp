// The level of detail's release as VTK draws it, off screen (Mesa's GL under Xvfb): the full mesh's
// actor and its GPU buffers stay alive, hidden, while a drag draws the proxy, so the release
// uploads the full mesh's moved points and normals in one build and keeps its triangles' index
// buffer (surface_mapper.h); the proxy's buffers are built once and refreshed at each step; and
// the released frame is pixel for pixel the frame of the same drag without the level of detail.
#include <vector>

#include <gtest/gtest.h>

#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include "arrow_ray.h"
#include "drag_sphere.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/render/scene_view.h"
#include "surface_mapper.h"

namespace ffdkit::app {
namespace {

// A sphere in a cubic lattice with a translate widget, in an off-screen window of 200 x 160
// pixels, drawn a frame at a time as the window draws it (MainWindow::drawFrame): the changes of
// the events before it evaluated once, with the view's request, then the view refreshed and
// rendered.
struct RenderedDocument {
  static constexpr int kWidth = 200, kHeight = 160;
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  InteractionController controller{scene, deformer, commands};
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  SceneView view{renderer};
  testing::DragSphere made;
  bool frameDue = false;

  explicit RenderedDocument(bool lod) {
    window->SetOffScreenRendering(true);
    window->SetSize(kWidth, kHeight);
    window->AddRenderer(renderer);
    LevelOfDetail options;
    options.enabled = lod;
    options.minVertices = 500;
    options.proxyVertices = 300;
    view.setLevelOfDetail(options);
    made = testing::addDragSphere(controller, 60);
    controller.requestEvaluation = [this] { frameDue = true; };
    controller.onChanged = [this] { frameDue = true; };
    view.setHighlights(controller.highlights());
    view.show(scene, deformer);
    renderer->ResetCamera();
    frame();
  }
  void frame() {
    deformer.evaluate(scene, view.evaluationRequest(scene, deformer));
    view.setHighlights(controller.highlights());
    view.refresh(scene, deformer);
    window->Render();
    frameDue = false;
  }
  widgets::Ray ray(double along) const { return test::arrowRay(scene.widgets, made.widget, along); }
  double tolerance() const { return test::arrowTolerance(scene.widgets, made.widget); }
  // The surface mapper (the objects' and their proxies') drawing `vertices` points, or with
  // `fewer`, fewer than that: the sphere's, or its proxy's; null when there is none.
  SurfaceMapper* mapperOf(vtkIdType vertices, bool fewer = false) {
    vtkActorCollection* actors = renderer->GetActors();
    actors->InitTraversal();
    while (vtkActor* actor = actors->GetNextActor()) {
      auto* mapper = SurfaceMapper::SafeDownCast(actor->GetMapper());
      auto* data = mapper != nullptr ? vtkPolyData::SafeDownCast(mapper->GetInput()) : nullptr;
      if (data == nullptr) continue;
      if (fewer ? data->GetNumberOfPoints() < vertices : data->GetNumberOfPoints() == vertices) return mapper;
    }
    return nullptr;
  }
  // The sphere's surface mapper, or with `proxy`, its proxy's; null when there is none.
  SurfaceMapper* sphereMapper(bool proxy = false) {
    return mapperOf(scene.findObject(made.sphere)->mesh.points.rows(), proxy);
  }
  std::vector<unsigned char> pixels() {
    vtkNew<vtkUnsignedCharArray> rgb;
    window->GetPixelData(0, 0, kWidth - 1, kHeight - 1, 0, rgb);
    return {rgb->GetPointer(0), rgb->GetPointer(0) + rgb->GetNumberOfValues()};
  }
};

TEST(LevelOfDetailRender, TheReleaseUploadsTheFullMeshsPointsOnceAndKeepsItsIndexBuffer) {
  RenderedDocument on(true), off(false);
  const vtkIdType n = on.scene.findObject(on.made.sphere)->mesh.points.rows();
  SurfaceMapper* full = on.mapperOf(n);
  ASSERT_NE(full, nullptr);
  ASSERT_EQ(full->bufferBuilds(), 1);  // the first frame drew the full mesh
  ASSERT_EQ(full->indexBuilds(), 1);
  for (RenderedDocument* d : {&on, &off})
    ASSERT_EQ(d->controller.press(d->ray(0.5), d->tolerance()), InteractionController::PressResult::Widget);
  constexpr int kSteps = 6;
  SurfaceMapper* proxy = on.mapperOf(n, true);  // built with the scene, not drawn yet
  ASSERT_NE(proxy, nullptr);
  EXPECT_EQ(proxy->bufferBuilds(), 0);
  for (int step = 1; step <= kSteps; ++step) {
    for (RenderedDocument* d : {&on, &off}) {
      d->controller.drag(d->ray(0.5 + 0.15 * step));
      ASSERT_TRUE(d->frameDue);
      d->frame();
    }
    ASSERT_TRUE(on.view.showsProxy(on.made.sphere));
  }
  EXPECT_EQ(on.mapperOf(n, true), proxy);
  EXPECT_EQ(proxy->bufferBuilds(), kSteps);  // its points and normals at each step
  EXPECT_EQ(proxy->indexBuilds(), 1);        // its triangles once
  // The full mesh, hidden during the drag, built nothing.
  EXPECT_EQ(full->bufferBuilds(), 1);
  EXPECT_EQ(full->indexBuilds(), 1);

  for (RenderedDocument* d : {&on, &off}) {
    d->controller.release();
    ASSERT_TRUE(d->frameDue);
    d->frame();
  }
  EXPECT_FALSE(on.view.showsProxy(on.made.sphere));
  EXPECT_EQ(on.mapperOf(n), full);     // the same mapper, kept through the gesture
  EXPECT_EQ(full->bufferBuilds(), 2);  // the moved points and normals, once
  EXPECT_EQ(full->indexBuilds(), 1);   // the triangles did not change: not built again
  EXPECT_EQ(proxy->bufferBuilds(), kSteps);  // hidden again: nothing more
  // What the release draws is what the same drag draws without the level of detail.
  const std::vector<unsigned char> released = on.pixels(), reference = off.pixels();
  ASSERT_EQ(released.size(), std::size_t(3 * RenderedDocument::kWidth * RenderedDocument::kHeight));
  EXPECT_TRUE(released == reference);
  // And the drag moved the sphere on screen: the first frame's pixels differ.
  RenderedDocument still(true);
  EXPECT_FALSE(still.pixels() == released);
}

TEST(LevelOfDetailRender, TheClosedSphereIsDrawnWithItsBackFacesCulledUnlessALatticeMayFold) {
  // The sphere is closed and faces out, the camera outside it: its full mesh is drawn with its
  // back faces culled (surface_mapper.h), its proxy (not known to be closed) never.
  RenderedDocument doc(true);
  SurfaceMapper* full = doc.sphereMapper();
  ASSERT_NE(full, nullptr);
  EXPECT_EQ(full->culledDraws(), 1);
  ASSERT_EQ(doc.controller.press(doc.ray(0.5), doc.tolerance()), InteractionController::PressResult::Widget);
  doc.controller.drag(doc.ray(0.8));
  doc.frame();
  SurfaceMapper* proxy = doc.sphereMapper(true);
  ASSERT_NE(proxy, nullptr);
  EXPECT_EQ(proxy->bufferBuilds(), 1);  // drawn
  EXPECT_EQ(proxy->culledDraws(), 0);
  doc.controller.release();
  doc.frame();
  EXPECT_EQ(full->culledDraws(), 2);
  // A lattice whose cells may fold (the fold-over tint): no culling until it is certified again.
  ViewHighlights folding = doc.controller.highlights();
  folding.foldTints.push_back({doc.made.lattice, {1, 1, 1}, {ffd::CellFolding::Folds}});
  doc.view.setHighlights(folding);
  doc.window->Render();
  EXPECT_EQ(full->culledDraws(), 2);
  doc.view.setHighlights(doc.controller.highlights());
  doc.window->Render();
  EXPECT_EQ(full->culledDraws(), 3);
}

TEST(LevelOfDetailRender, ASurfaceIsNotCulledWhileALatticeFoldsItWithoutATintOrTearsItAcrossItsBoundary) {
  // Changes no drag made, so no fold-over tint: control points set in the model (as a scene read
  // from a file, a playback key or a script sets them) and a lattice moved across the sphere.
  RenderedDocument doc(true);
  SurfaceMapper* full = doc.sphereMapper();
  ASSERT_NE(full, nullptr);
  EXPECT_EQ(full->culledDraws(), 1);
  auto& model = doc.scene.widgets;
  const widgets::WidgetId lattice = doc.made.lattice;
  const Eigen::MatrixX3d rest = model.restPoints(lattice);

  // Mirrored through the lattice's centre along x: det J < 0 everywhere, every face of the sphere
  // turned inward; what is seen is its inside, which culling would hide.
  Eigen::MatrixX3d mirrored = rest;
  const double centreX = 0.5 * (rest.col(0).minCoeff() + rest.col(0).maxCoeff());
  mirrored.col(0) = (2.0 * centreX) - rest.col(0).array();
  model.setControlPoints(lattice, mirrored);
  doc.frame();
  EXPECT_TRUE(doc.controller.highlights().foldTints.empty());  // no drag: nothing tinted
  EXPECT_EQ(full->culledDraws(), 1);
  model.setControlPoints(lattice, rest);
  doc.frame();
  EXPECT_EQ(full->culledDraws(), 2);

  // The lattice moved half its width along x, one control point of the half inside the sphere
  // pulled: the points inside move and the others stay (OutsidePolicy::Identity), so the surface
  // is torn open where it crosses the lattice's face. Not culled; moved wholly off the sphere,
  // culled again (the lattice leaves it alone).
  const double width = rest.col(0).maxCoeff() - rest.col(0).minCoeff();
  const Eigen::Affine3d frame = model.latticeFrame(lattice);
  model.setLatticeFrame(lattice, Eigen::Translation3d(0.5 * width, 0.0, 0.0) * frame);
  Eigen::MatrixX3d pulled = rest;
  pulled(0, 2) -= 0.3 * width;
  model.setControlPoints(lattice, pulled);
  doc.frame();
  EXPECT_EQ(full->culledDraws(), 2);
  model.setLatticeFrame(lattice, Eigen::Translation3d(3.0 * width, 0.0, 0.0) * frame);
  doc.frame();
  EXPECT_EQ(full->culledDraws(), 3);
}

TEST(LevelOfDetailRender, ADragsLatticeIsCheckedForFoldsOnceAStepByTheControllerNotAgainByTheView) {
  // Without the level of detail every step of a drag draws the full mesh, culled only over
  // lattices certified free of fold-over. The controller checks the lattice the drag moves at every
  // step (its fold-over tint) and hands its verdicts on (ViewHighlights::certified): the view culls
  // on them without a check of its own.
  RenderedDocument doc(false);
  SurfaceMapper* full = doc.sphereMapper();
  ASSERT_NE(full, nullptr);
  EXPECT_EQ(doc.view.stats().foldChecks, 1);  // the lattice at rest, when the actor was built
  EXPECT_EQ(full->culledDraws(), 1);
  ASSERT_EQ(doc.controller.press(doc.ray(0.5), doc.tolerance()), InteractionController::PressResult::Widget);
  for (double along : {0.6, 0.7, 0.8}) {
    doc.controller.drag(doc.ray(along));
    doc.frame();
    EXPECT_FALSE(doc.controller.highlights().certified.empty());
  }
  doc.controller.release();
  doc.frame();
  EXPECT_EQ(doc.view.stats().foldChecks, 1);
  EXPECT_EQ(full->culledDraws(), 5);  // every frame, the drag's three and the release's too
}

}  // namespace
}  // namespace ffdkit::app
