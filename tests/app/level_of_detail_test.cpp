// The view's level of detail (LevelOfDetail in scene_view.h, app/render/src/lod_proxy.h): the
// proxy is a vertex clustering whose vertices are some of the mesh's, it is what a drag or
// playback draws of a large surface, during a drag the deformer evaluates its vertices only (the
// view's EvaluationRequest), and the full mesh drawn after the motion is bit for bit the one a view
// without level of detail draws.
// No GL draw: the renderers have no window.
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <tuple>

#include <gtest/gtest.h>

#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkMapper.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>

#include "arrow_ray.h"
#include "drag_sphere.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/meshio/mesh_io.h"
#include "ffdkit/render/scene_view.h"
#include "ffdkit/scenes/scene_file.h"
#include "lod_proxy.h"

namespace ffdkit::app {
namespace {

meshio::MeshData sphereMesh(int resolution) {
  scenes::PrimitiveOptions sphere;
  sphere.resolution = resolution;
  return scenes::buildObjectMesh(sphere, ".");
}

TEST(LodProxy, IsAClusteringOfSomeOfTheMeshsVertices) {
  const meshio::MeshData mesh = sphereMesh(200);
  const Eigen::Index n = mesh.points.rows();
  ASSERT_GT(n, 15000);
  const Eigen::Index target = 1000;
  const ProxyMesh proxy = clusterVertices(mesh.points, mesh.triangles, target);
  const auto count = static_cast<Eigen::Index>(proxy.vertices.size());
  // About the target: a cell per sqrt(area / target) of surface.
  EXPECT_GT(count, target / 3);
  EXPECT_LT(count, 3 * target);
  EXPECT_TRUE(std::is_sorted(proxy.vertices.begin(), proxy.vertices.end()));
  EXPECT_TRUE(std::adjacent_find(proxy.vertices.begin(), proxy.vertices.end()) == proxy.vertices.end());
  EXPECT_GE(proxy.vertices.front(), 0);
  EXPECT_LT(proxy.vertices.back(), n);
  // Triangles over three distinct proxy vertices, each once, every vertex used.
  std::set<std::tuple<int, int, int>> seen;
  std::vector<bool> used(proxy.vertices.size(), false);
  ASSERT_GT(proxy.triangles.rows(), count);  // a closed surface has about twice as many
  for (Eigen::Index t = 0; t < proxy.triangles.rows(); ++t) {
    int c[3] = {proxy.triangles(t, 0), proxy.triangles(t, 1), proxy.triangles(t, 2)};
    for (int v : c) {
      ASSERT_GE(v, 0);
      ASSERT_LT(v, count);
      used[static_cast<std::size_t>(v)] = true;
    }
    ASSERT_TRUE(c[0] != c[1] && c[1] != c[2] && c[0] != c[2]) << "triangle " << t;
    std::sort(c, c + 3);
    EXPECT_TRUE(seen.emplace(c[0], c[1], c[2]).second) << "triangle " << t << " repeats";
  }
  EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; }));
  // The proxy covers the surface: every vertex of the mesh lies within two cells (sqrt(3) cell
  // diagonals and a neighbour) of a proxy vertex.
  const double area = 4.0 * std::numbers::pi * std::pow(mesh.points.row(0).norm(), 2);
  const double cell = std::sqrt(area / double(target));
  double farthest = 0.0;
  for (Eigen::Index v = 0; v < n; v += 7) {
    double nearest = INFINITY;
    for (Eigen::Index p : proxy.vertices) nearest = std::min(nearest, (mesh.points.row(v) - mesh.points.row(p)).norm());
    farthest = std::max(farthest, nearest);
  }
  EXPECT_LT(farthest, 2.0 * cell);
  // Deterministic.
  const ProxyMesh again = clusterVertices(mesh.points, mesh.triangles, target);
  EXPECT_EQ(again.vertices, proxy.vertices);
  EXPECT_EQ(again.triangles, proxy.triangles);
}

TEST(LodProxy, AMeshNoLargerThanTheTargetIsItsOwnProxy) {
  const meshio::MeshData mesh = sphereMesh(20);
  const ProxyMesh proxy = clusterVertices(mesh.points, mesh.triangles, mesh.points.rows());
  ASSERT_EQ(static_cast<Eigen::Index>(proxy.vertices.size()), mesh.points.rows());
  for (std::size_t i = 0; i < proxy.vertices.size(); ++i) EXPECT_EQ(proxy.vertices[i], static_cast<Eigen::Index>(i));
  EXPECT_EQ(proxy.triangles, mesh.triangles);
}

// A sphere in a cubic lattice with a translate widget, drawn by a view whose level of detail is
// on (proxies from 500 vertices) or off. `perFrame`: evaluation as the window runs it
// (MainWindow::drawFrame), with the view's request (SceneView::evaluationRequest); otherwise the
// controller evaluates every object in full at each change.
struct Document {
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  InteractionController controller{scene, deformer, commands};
  vtkNew<vtkRenderer> renderer;
  SceneView view{renderer};
  testing::DragSphere made;
  static constexpr Eigen::Index kProxyVertices = 300;

  explicit Document(bool lod, bool perFrame = false) {
    LevelOfDetail options;
    options.enabled = lod;
    options.minVertices = 500;
    options.proxyVertices = kProxyVertices;
    view.setLevelOfDetail(options);
    made = testing::addDragSphere(controller, 60);
    view.setHighlights(controller.highlights());
    view.show(scene, deformer);
    if (perFrame) controller.requestEvaluation = [this] { deformer.evaluate(scene, view.evaluationRequest(scene, deformer)); };
    controller.onChanged = [this] {
      view.setHighlights(controller.highlights());
      view.refresh(scene, deformer);
    };
  }
  widgets::Ray ray(double along) const { return test::arrowRay(scene.widgets, made.widget, along); }
  double tolerance() const { return test::arrowTolerance(scene.widgets, made.widget); }
  const meshio::MeshData& mesh() const { return scene.findObject(made.sphere)->mesh; }
  scenes::ObjectId sphereId() const { return scene.findObject(made.sphere)->id; }
  // The points of the visible actor drawing `vertices` points (the proxy), #vertices x 3.
  Eigen::MatrixX3d visibleActorPoints(Eigen::Index vertices) {
    vtkActorCollection* actors = renderer->GetActors();
    actors->InitTraversal();
    while (vtkActor* actor = actors->GetNextActor()) {
      auto* data = vtkPolyData::SafeDownCast(actor->GetMapper()->GetInput());
      if (!actor->GetVisibility() || data == nullptr || data->GetNumberOfPoints() != vertices) continue;
      Eigen::MatrixX3d out(vertices, 3);
      for (Eigen::Index i = 0; i < vertices; ++i) {
        double p[3];
        data->GetPoint(i, p);
        out.row(i) = Eigen::RowVector3d(p[0], p[1], p[2]);
      }
      return out;
    }
    return {};
  }
};

TEST(LevelOfDetail, ADragDrawsTheProxyFollowingTheMotionAndReleaseTheFullMeshBitForBit) {
  Document on(true), off(false);
  ASSERT_GT(on.mesh().points.rows(), 500);
  const ProxyMesh proxy = clusterVertices(on.mesh().points, on.mesh().triangles, Document::kProxyVertices);
  const auto proxyCount = static_cast<Eigen::Index>(proxy.vertices.size());
  for (Document* d : {&on, &off})
    ASSERT_EQ(d->controller.press(d->ray(0.5), d->tolerance()), InteractionController::PressResult::Widget);
  const SceneViewStats pressed = on.view.stats();
  const double scale = on.mesh().points.cwiseAbs().maxCoeff();
  for (int step = 1; step <= 6; ++step) {
    for (Document* d : {&on, &off}) d->controller.drag(d->ray(0.5 + 0.15 * step));
    EXPECT_TRUE(on.view.showsProxy(on.made.sphere));
    EXPECT_FALSE(off.view.showsProxy(off.made.sphere));
    // The proxy at the deformer's points of its vertices (this controller evaluates every object
    // in full at each change: the proxy gathers them).
    const Eigen::MatrixX3d drawn = on.visibleActorPoints(proxyCount);
    ASSERT_EQ(drawn.rows(), proxyCount);
    const Eigen::MatrixX3d& exact = on.deformer.points(on.made.sphere);
    double worst = 0.0;
    for (Eigen::Index i = 0; i < proxyCount; ++i)
      worst = std::max(worst, (drawn.row(i) - exact.row(proxy.vertices[static_cast<std::size_t>(i)])).cwiseAbs().maxCoeff());
    EXPECT_LT(worst, 1e-6 * scale) << "step " << step;  // float storage
  }
  const SceneViewStats dragged = on.view.stats();
  EXPECT_EQ(dragged.proxyBuilds, pressed.proxyBuilds + (pressed.proxyBuilds == 0 ? 1 : 0));
  EXPECT_GE(dragged.proxyUpdates, pressed.proxyUpdates + 6);
  EXPECT_EQ(dragged.pointUpdates, pressed.pointUpdates);  // the full mesh's arrays untouched
  EXPECT_EQ(dragged.normalUpdates, pressed.normalUpdates);

  for (Document* d : {&on, &off}) d->controller.release();
  EXPECT_FALSE(on.view.showsProxy(on.made.sphere));
  EXPECT_EQ(on.view.stats().pointUpdates, dragged.pointUpdates + 1);
  // The same document, the same exact points, and the same full mesh drawn, bit for bit.
  EXPECT_EQ(on.deformer.points(on.made.sphere), off.deformer.points(off.made.sphere));
  EXPECT_EQ(on.scene.widgets.variation(on.made.widget), off.scene.widgets.variation(off.made.widget));
  const Eigen::MatrixX3d onPoints = on.view.objectPoints(on.made.sphere);
  ASSERT_EQ(onPoints.rows(), on.mesh().points.rows());
  EXPECT_TRUE(onPoints == off.view.objectPoints(off.made.sphere));
  EXPECT_TRUE(on.view.objectNormals(on.made.sphere) == off.view.objectNormals(off.made.sphere));
  EXPECT_LT((onPoints - on.deformer.points(on.made.sphere)).cwiseAbs().maxCoeff(), 1e-6 * scale);
  EXPECT_GT((onPoints - on.mesh().points).cwiseAbs().maxCoeff(), 1e-3 * scale);  // it did move
}

// The window's evaluation: during the drag the deformer evaluates the proxy's points only (the full
// mesh is not touched: counted), what an exact reader asks for is exact, and the release gives
// the document, the points, the drawn mesh and the files of a run without level of detail, bit
// for bit.
TEST(LevelOfDetail, ADragEvaluatesTheProxysPointsOnlyAndLeavesWhatARunWithoutItLeaves) {
  // `off` evaluates every object in full at each step: what this test compares the drawn proxy
  // with (the window's evaluation without level of detail lets the delta passes of a followed
  // drag wait: gesture_normals_test).
  Document on(true, true), off(false);
  const ProxyMesh proxy = clusterVertices(on.mesh().points, on.mesh().triangles, Document::kProxyVertices);
  const auto proxyCount = static_cast<Eigen::Index>(proxy.vertices.size());
  const scenes::ObjectId sphere = on.sphereId();
  for (Document* d : {&on, &off})
    ASSERT_EQ(d->controller.press(d->ray(0.5), d->tolerance()), InteractionController::PressResult::Widget);
  const scenes::SceneDeformer::Totals pressed = on.deformer.totals();
  const double scale = on.mesh().points.cwiseAbs().maxCoeff();
  constexpr int kSteps = 6;
  for (int step = 1; step <= kSteps; ++step) {
    for (Document* d : {&on, &off}) d->controller.drag(d->ray(0.5 + 0.15 * step));
    ASSERT_TRUE(on.view.showsProxy(on.made.sphere));
    ASSERT_EQ(on.deformer.coverage(sphere), scenes::PointCoverage::Subset);
    EXPECT_EQ(on.deformer.subsetIndices(sphere), proxy.vertices);
    EXPECT_THROW((void)on.deformer.points(sphere), scenes::PointsNotEvaluated);  // never stale, silently
    EXPECT_EQ(off.deformer.coverage(off.sphereId()), scenes::PointCoverage::Full);
    // The proxy drawn at the points a full evaluation gives at its vertices.
    const Eigen::MatrixX3d drawn = on.visibleActorPoints(proxyCount);
    ASSERT_EQ(drawn.rows(), proxyCount);
    const Eigen::MatrixX3d& full = off.deformer.points(off.made.sphere);
    double worst = 0.0;
    for (Eigen::Index i = 0; i < proxyCount; ++i)
      worst = std::max(worst, (drawn.row(i) - full.row(proxy.vertices[static_cast<std::size_t>(i)])).cwiseAbs().maxCoeff());
    EXPECT_LT(worst, 1e-6 * scale) << "step " << step;  // float storage
  }
  EXPECT_EQ(on.deformer.totals().deformedPoints, pressed.deformedPoints);  // the full mesh waited
  EXPECT_EQ(on.deformer.totals().subsetPoints - pressed.subsetPoints, std::uint64_t(kSteps * proxyCount));
  EXPECT_EQ(on.deformer.totals().evaluations - pressed.evaluations, std::uint64_t(kSteps));

  // An exact reader during the gesture (an export, a script): the full mesh, now.
  on.deformer.evaluate(on.scene);
  ASSERT_EQ(on.deformer.coverage(sphere), scenes::PointCoverage::Full);
  EXPECT_LT((on.deformer.points(sphere) - off.deformer.points(off.made.sphere)).cwiseAbs().maxCoeff(), 1e-13 * scale);
  on.controller.drag(on.ray(0.5 + 0.15 * (kSteps + 1)));  // the next frame: the proxy's points again
  off.controller.drag(off.ray(0.5 + 0.15 * (kSteps + 1)));
  EXPECT_EQ(on.deformer.coverage(sphere), scenes::PointCoverage::Subset);

  for (Document* d : {&on, &off}) d->controller.release();
  EXPECT_FALSE(on.view.showsProxy(on.made.sphere));
  ASSERT_EQ(on.deformer.coverage(sphere), scenes::PointCoverage::Full);
  // The same document, exact points and drawn mesh, bit for bit.
  EXPECT_TRUE(on.deformer.points(sphere) == off.deformer.points(off.made.sphere));
  EXPECT_TRUE(on.view.objectPoints(on.made.sphere) == off.view.objectPoints(off.made.sphere));
  EXPECT_TRUE(on.view.objectNormals(on.made.sphere) == off.view.objectNormals(off.made.sphere));
  EXPECT_GT((on.deformer.points(sphere) - on.mesh().points).cwiseAbs().maxCoeff(), 1e-3 * scale);  // it did move
  // The same files: the saved scene and the exported deformed mesh, byte for byte.
  EXPECT_EQ(scenes::sceneFileText(on.scene), scenes::sceneFileText(off.scene));
  std::string exported[2];
  for (int k = 0; k < 2; ++k) {
    const Document& d = k == 0 ? on : off;
    meshio::MeshData mesh = d.mesh();
    mesh.points = d.deformer.points(d.made.sphere);
    std::ostringstream out;
    meshio::writeMesh(out, mesh, meshio::MeshFormat::Ply);
    exported[k] = out.str();
  }
  EXPECT_GT(exported[0].size(), std::size_t(on.mesh().points.rows()) * 24);
  EXPECT_TRUE(exported[0] == exported[1]);
  // The proxy, drawn again (playback), is the full mesh at its vertices, bit for bit (as floats).
  on.view.setMoving(true);
  on.view.refresh(on.scene, on.deformer);
  const Eigen::MatrixX3d again = on.visibleActorPoints(proxyCount);
  ASSERT_EQ(again.rows(), proxyCount);
  const Eigen::MatrixX3d& full = off.deformer.points(off.made.sphere);
  for (Eigen::Index i = 0; i < proxyCount; ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(again(i, c), double(float(full(proxy.vertices[static_cast<std::size_t>(i)], c)))) << i;
}

TEST(LevelOfDetail, PlaybackDrawsTheProxyUntilItStops) {
  Document on(true);
  on.view.setMoving(true);
  for (int frame = 1; frame <= 3; ++frame) {
    on.controller.setVariation(on.made.widget, 0.1 * frame);
    EXPECT_TRUE(on.view.showsProxy(on.made.sphere));
  }
  const SceneViewStats playing = on.view.stats();
  on.view.setMoving(false);
  on.view.refresh(on.scene, on.deformer);
  EXPECT_FALSE(on.view.showsProxy(on.made.sphere));
  EXPECT_EQ(on.view.stats().pointUpdates, playing.pointUpdates + 1);
  const double scale = on.mesh().points.cwiseAbs().maxCoeff();
  EXPECT_LT((on.view.objectPoints(on.made.sphere) - on.deformer.points(on.made.sphere)).cwiseAbs().maxCoeff(), 1e-6 * scale);
}

TEST(LevelOfDetail, TheProxyIsBuiltWithTheSceneSoTheFirstGestureDoesNotBuildIt) {
  Document d(true);
  EXPECT_EQ(d.view.stats().proxyBuilds, 1);  // by show(), before anything moved
  EXPECT_FALSE(d.view.showsProxy(d.made.sphere));
  ASSERT_EQ(d.controller.press(d.ray(0.5), d.tolerance()), InteractionController::PressResult::Widget);
  d.controller.drag(d.ray(0.8));
  EXPECT_TRUE(d.view.showsProxy(d.made.sphere));
  EXPECT_EQ(d.view.stats().proxyBuilds, 1);
  EXPECT_GE(d.view.stats().proxyUpdates, 1);
  d.controller.release();
  EXPECT_FALSE(d.view.showsProxy(d.made.sphere));
  // Another size: built again at the next refresh, still before anything moves.
  LevelOfDetail options = d.view.levelOfDetail();
  options.proxyVertices = 2 * Document::kProxyVertices;
  d.view.setLevelOfDetail(options);
  d.view.refresh(d.scene, d.deformer);
  EXPECT_EQ(d.view.stats().proxyBuilds, 2);
  EXPECT_FALSE(d.view.showsProxy(d.made.sphere));
  ASSERT_EQ(d.controller.press(d.ray(0.8), d.tolerance()), InteractionController::PressResult::Widget);
  d.controller.drag(d.ray(0.6));
  EXPECT_TRUE(d.view.showsProxy(d.made.sphere));
  EXPECT_EQ(d.view.stats().proxyBuilds, 2);
  d.controller.release();
  // Turned off: no proxy is kept or drawn.
  options.enabled = false;
  d.view.setLevelOfDetail(options);
  d.view.refresh(d.scene, d.deformer);
  ASSERT_EQ(d.controller.press(d.ray(0.6), d.tolerance()), InteractionController::PressResult::Widget);
  d.controller.drag(d.ray(0.9));
  EXPECT_FALSE(d.view.showsProxy(d.made.sphere));
  EXPECT_EQ(d.view.stats().proxyBuilds, 2);
  d.controller.release();
}

TEST(LevelOfDetail, SmallObjectsAndAViewWithoutItDrawInFull) {
  for (const bool large : {false, true}) {
    Document d(true);
    LevelOfDetail options = d.view.levelOfDetail();
    options.enabled = large;  // off: no proxy at any size
    if (large) options.minVertices = d.mesh().points.rows() + 1;  // on, but the sphere is below it
    const int builtWithTheScene = d.view.stats().proxyBuilds;  // under the Document's options
    d.view.setLevelOfDetail(options);
    ASSERT_EQ(d.controller.press(d.ray(0.5), d.tolerance()), InteractionController::PressResult::Widget);
    d.controller.drag(d.ray(0.9));
    EXPECT_FALSE(d.view.showsProxy(d.made.sphere));
    EXPECT_EQ(d.view.stats().proxyBuilds, builtWithTheScene);
    d.controller.release();
  }
}

}  // namespace
}  // namespace ffdkit::app
