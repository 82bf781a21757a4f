// The view is change-driven (scene_view.h): hover and selection build no geometry and touch no
// point or normal array; a drag step rewrites the points and normals of the objects that moved,
// and only theirs. No GL draw: the renderer has no window.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include <vtkNew.h>
#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkMapper.h>
#include <vtkPolyData.h>
#include <vtkPoints.h>
#include <vtkMatrix4x4.h>
#include <vtkRenderWindow.h>
#include <vtkRendererCollection.h>
#include <vtkRenderer.h>

#include "arrow_ray.h"
#include "drag_sphere.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/render/scene_view.h"

namespace ffdkit::app {
namespace {

// A document edited through the controller and drawn by a view (no window: no GL draw).
struct ViewedDocument {
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  InteractionController controller{scene, deformer, commands};
  vtkNew<vtkRenderer> renderer;
  SceneView view{renderer};
  widgets::WidgetId lattice, widget;
};

struct Session : ViewedDocument {
  std::string moved, still;

  Session() {
    scenes::PrimitiveOptions sphere;
    sphere.resolution = 12;
    moved = controller.addPrimitive(sphere);
    sphere.placement = Eigen::Translation3d(3, 0, 0);
    still = controller.addPrimitive(sphere);
    lattice = controller.newLattice({});
    controller.attachLattice(lattice, moved);
    widget = controller.addAffineAtPoint({lattice, 1 + 3 * (1 + 3 * 2)}, widgets::AffineKind::Translate);
    controller.clearSelection();
    view.setHighlights(controller.highlights());
    view.show(scene, deformer);
    controller.onChanged = [this] {
      view.setHighlights(controller.highlights());
      view.refresh(scene, deformer);
    };
  }
  widgets::Ray ray(double along, double aside = 0.0) const {
    const widgets::WidgetFrame f = scene.widgets.affineFrame(widget);
    widgets::Ray r;
    r.origin = f.frame.translation() + f.size * (along * f.frame.linear().col(0) + aside * f.frame.linear().col(1)) +
               5.0 * f.frame.linear().col(2);
    r.direction = -f.frame.linear().col(2);
    return r;
  }
  double tolerance() const { return 0.05 * scene.widgets.affineFrame(widget).size; }
};

void expectNoGeometryWork(const SceneViewStats& before, const SceneViewStats& after) {
  EXPECT_EQ(after.objectBuilds, before.objectBuilds);
  EXPECT_EQ(after.pointUpdates, before.pointUpdates);
  EXPECT_EQ(after.normalUpdates, before.normalUpdates);
  EXPECT_EQ(after.widgetBuilds, before.widgetBuilds);
}

TEST(SceneViewUpdates, HoverAndSelectionBuildNoGeometry) {
  Session s;
  const SceneViewStats start = s.view.stats();
  EXPECT_EQ(start.objectBuilds, 2);
  EXPECT_EQ(start.widgetBuilds, 1);
  for (int i = 0; i < 5; ++i) {
    EXPECT_TRUE(s.controller.hover(s.ray(0.5), s.tolerance()));
    EXPECT_EQ(s.controller.hovered(), s.widget);
    EXPECT_TRUE(s.controller.hover(s.ray(0.5, 4.0), s.tolerance()));
  }
  s.controller.setSelection({s.lattice});
  s.controller.setPickedPoint(LatticePointRef{s.lattice, 4});
  s.controller.clearSelection();
  expectNoGeometryWork(start, s.view.stats());
}

TEST(SceneViewUpdates, ADragStepUpdatesThePointsOfTheObjectsThatMovedOnly) {
  Session s;
  ASSERT_EQ(s.controller.press(s.ray(0.5), s.tolerance()), InteractionController::PressResult::Widget);
  const SceneViewStats pressed = s.view.stats();
  s.controller.drag(s.ray(0.8));
  const SceneViewStats dragged = s.view.stats();
  EXPECT_EQ(dragged.pointUpdates, pressed.pointUpdates + 1);  // the attached sphere, not the other
  EXPECT_EQ(dragged.normalUpdates, pressed.normalUpdates + 1);
  EXPECT_EQ(dragged.objectBuilds, pressed.objectBuilds);
  EXPECT_EQ(dragged.widgetBuilds, pressed.widgetBuilds + 1);  // the lattice and glyphs moved
  // A hover during nothing-changed refreshes does no geometry work either.
  s.controller.release();
  const SceneViewStats released = s.view.stats();
  s.controller.hover(s.ray(0.5, 4.0), s.tolerance());
  expectNoGeometryWork(released, s.view.stats());
}

// Undo and redo of a structural edit go through the model in place (WidgetModel::assignData):
// in a scene of three lattices, undoing the addition of one widget embeds nothing, builds no
// lattice and no actor of any other widget, and leaves the actors a fresh view would draw.
TEST(SceneViewUpdates, UndoAndRedoOfAddingAWidgetRedrawOnlyThatWidget) {
  Session s;
  for (const std::string& object : {s.moved, s.still}) {
    NewLatticeOptions options;
    options.counts = Eigen::Vector3i(3, 2, 2);
    const widgets::WidgetId lattice = s.controller.newLattice(options);
    s.controller.attachLattice(lattice, object);
    s.controller.addAffineAtPoint({lattice, 1}, widgets::AffineKind::Translate);
  }
  s.controller.clearSelection();
  ASSERT_EQ(s.scene.widgets.widgets(widgets::WidgetType::Lattice).size(), 3u);
  auto actorsOfAFreshView = [&s] {
    vtkNew<vtkRenderer> renderer;
    SceneView fresh{renderer};
    fresh.setHighlights(s.controller.highlights());
    fresh.show(s.scene, s.deformer);
    return renderer->GetActors()->GetNumberOfItems();
  };
  const std::size_t widgetsBefore = s.scene.widgets.widgets().size();
  const int actorsBefore = s.renderer->GetActors()->GetNumberOfItems();
  EXPECT_EQ(actorsBefore, actorsOfAFreshView());
  s.controller.addAffineAtPoint({s.lattice, 2}, widgets::AffineKind::Translate);  // a cell and its widget
  const std::size_t added = s.scene.widgets.widgets().size() - widgetsBefore;
  ASSERT_EQ(added, 2u);
  s.controller.clearSelection();
  const int actorsAdded = s.renderer->GetActors()->GetNumberOfItems();
  const std::uint64_t instance = s.scene.widgets.instance();

  const SceneViewStats done = s.view.stats();
  s.commands.undo();
  EXPECT_EQ(s.scene.widgets.instance(), instance);
  EXPECT_EQ(s.scene.widgets.widgets().size(), widgetsBefore);
  EXPECT_EQ(s.deformer.lastStats().reembeddedStages, 0);
  EXPECT_EQ(s.deformer.lastStats().latticesBuilt, 0);
  const SceneViewStats undone = s.view.stats();
  EXPECT_EQ(undone.widgetActorBuilds, done.widgetActorBuilds) << "no other widget is redrawn";
  EXPECT_EQ(undone.objectBuilds, done.objectBuilds);
  EXPECT_EQ(undone.pointUpdates, done.pointUpdates);
  EXPECT_EQ(s.renderer->GetActors()->GetNumberOfItems(), actorsBefore);
  EXPECT_EQ(s.renderer->GetActors()->GetNumberOfItems(), actorsOfAFreshView());

  s.commands.redo();
  EXPECT_EQ(s.deformer.lastStats().reembeddedStages, 0);
  EXPECT_EQ(s.deformer.lastStats().latticesBuilt, 0);
  const SceneViewStats redone = s.view.stats();
  EXPECT_EQ(redone.widgetActorBuilds, undone.widgetActorBuilds + static_cast<int>(added)) << "just the two widgets back";
  EXPECT_EQ(redone.objectBuilds, undone.objectBuilds);
  EXPECT_EQ(s.renderer->GetActors()->GetNumberOfItems(), actorsAdded);
  EXPECT_EQ(s.renderer->GetActors()->GetNumberOfItems(), actorsOfAFreshView());
}

// The visible actors' bounds, sorted: what a view draws, compared between views.
std::vector<std::array<double, 6>> drawnBounds(vtkRenderer* renderer) {
  std::vector<std::array<double, 6>> all;
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor()) {
    if (!actor->GetVisibility()) continue;
    std::array<double, 6> b{};
    actor->GetBounds(b.data());
    all.push_back(b);
  }
  std::sort(all.begin(), all.end());
  return all;
}

// Redrawing only what a change concerns draws what a view built from scratch draws, through
// random edits, drags, undos and redos (structural ones included).
TEST(SceneViewUpdates, RedrawingWhatChangedDrawsWhatAFreshViewDraws) {
  Session s;
  std::mt19937 random(16);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto pick = [&random](const auto& from) { return from[std::uniform_int_distribution<std::size_t>(0, from.size() - 1)(random)]; };
  for (int step = 0; step < 80; ++step) {
    const auto& m = s.scene.widgets;
    const std::vector<widgets::WidgetId> affines = m.widgets(widgets::WidgetType::Affine);
    const std::vector<widgets::WidgetId> lattices = m.widgets(widgets::WidgetType::Lattice);
    try {
      switch (std::uniform_int_distribution<int>(0, 8)(random)) {
        case 0: {
          const widgets::WidgetId l = pick(lattices);
          s.controller.addAffineAtPoint({l, std::uniform_int_distribution<Eigen::Index>(0, m.counts(l).prod() - 1)(random)},
                                        widgets::AffineKind::Translate);
          break;
        }
        case 1:
          if (affines.size() > 1) s.controller.removeWidget(pick(affines));
          break;
        case 2:
          if (affines.size() > 1) s.controller.bind(pick(affines), pick(affines));
          break;
        case 3:
          s.controller.setVariation(pick(affines), 0.2 * unit(random));
          break;
        case 4:
          s.controller.setLatticeCounts(pick(lattices), Eigen::Vector3i(3 + step % 2, 3, 3));
          break;
        case 5: {
          const widgets::WidgetId fresh = s.controller.newLattice({});
          s.controller.attachLattice(fresh, s.still);
          break;
        }
        case 6:
        case 7:
          if (s.commands.canUndo()) s.commands.undo();
          break;
        case 8:
          if (s.commands.canRedo()) s.commands.redo();
          break;
      }
    } catch (const std::exception&) {
      // a refused edit (a bind that closes a bad loop, ...) leaves no trace
    }
    s.controller.clearSelection();
    vtkNew<vtkRenderer> renderer;
    SceneView fresh{renderer};
    fresh.setHighlights(s.controller.highlights());
    fresh.show(s.scene, s.deformer);
    ASSERT_EQ(drawnBounds(s.renderer), drawnBounds(renderer)) << "step " << step;
  }
  EXPECT_GT(s.view.stats().widgetBuilds, 40);
  EXPECT_EQ(s.view.stats().objectBuilds, 2) << "no object was rebuilt";
}

// Area-weighted vertex normals in double, written here from the definition (sum of the
// triangles' (b - a) x (c - a) at each vertex, normalised): the exact normals of `points`.
Eigen::MatrixX3d exactNormals(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles) {
  Eigen::MatrixX3d sums = Eigen::MatrixX3d::Zero(points.rows(), 3);
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const Eigen::Vector3d a = points.row(triangles(t, 0)), b = points.row(triangles(t, 1)), c = points.row(triangles(t, 2));
    const Eigen::RowVector3d area = (b - a).cross(c - a).transpose();
    for (int k = 0; k < 3; ++k) sums.row(triangles(t, k)) += area;
  }
  return sums.rowwise().normalized();
}

// The largest angle, in degrees, between corresponding rows.
double maxAngleDegrees(const Eigen::MatrixX3f& drawn, const Eigen::MatrixX3d& exact) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < exact.rows(); ++i) {
    const Eigen::Vector3d a = drawn.row(i).cast<double>().normalized();
    const Eigen::Vector3d b = exact.row(i);
    worst = std::max(worst, std::atan2(a.cross(b).norm(), a.dot(b)));
  }
  return worst * 180.0 / std::numbers::pi;
}

// A sphere in a 4x4x4 cubic B-spline lattice with a translate widget on an inner point of its
// top layer (the BM_DragStep scene, smaller), drawn by a view that follows the controller.
struct DragSession : ViewedDocument {
  std::string sphere;

  explicit DragSession(int resolution) {
    const testing::DragSphere made = testing::addDragSphere(controller, resolution);
    sphere = made.sphere;
    lattice = made.lattice;
    widget = made.widget;
    view.show(scene, deformer);
    controller.onChanged = [this] { view.refresh(scene, deformer); };
  }
  widgets::Ray ray(double along) const { return test::arrowRay(scene.widgets, widget, along); }
  double tolerance() const { return test::arrowTolerance(scene.widgets, widget); }
  const Eigen::MatrixX3i& triangles() const { return scene.findObject(sphere)->mesh.triangles; }
  // What a view built from scratch on the present state draws.
  Eigen::MatrixX3f freshNormals() const {
    vtkNew<vtkRenderer> other;
    SceneView fresh(other);
    fresh.show(scene, deformer);
    return fresh.objectNormals(sphere);
  }
};

TEST(SceneViewUpdates, DragNormalsFollowTheExactNormalsAndAreTheExactOnesAtRelease) {
  // During a drag of one control point the view follows the normals along the motion
  // (gesture_normals.h: N(t) = N(t0) + (D(t) - D(t0)) x W, exact up to float rounding) instead
  // of recomputing them; at release it recomputes them. Two resolutions: the agreement is float
  // rounding at both, it does not depend on the mesh. The follow step runs four vertices at a
  // time and the last n % 4 one by one: one of the spheres has such a tail.
  int tails = 0;
  for (const int resolution : {40, 120}) {
    DragSession s(resolution);
    tails += s.deformer.pointCount(s.sphere) % 4 != 0;
    const Eigen::MatrixX3d start = exactNormals(s.deformer.points(s.sphere), s.triangles());
    ASSERT_EQ(s.controller.press(s.ray(0.5), s.tolerance()), InteractionController::PressResult::Widget);
    const SceneViewStats pressed = s.view.stats();
    double turned = 0.0;
    for (int step = 1; step <= 8; ++step) {
      s.controller.drag(s.ray(0.5 + 0.25 * step));  // up to two glyph sizes along the arrow
      ASSERT_EQ(s.deformer.lastStats().deltaStages, 1);
      const SceneViewStats now = s.view.stats();
      EXPECT_EQ(now.normalUpdates, pressed.normalUpdates + step);
      // The first step computes them (and what follows them), the next ones follow.
      EXPECT_EQ(now.followedNormals, pressed.followedNormals + step - 1) << "step " << step;
      const Eigen::MatrixX3d exact = exactNormals(s.deformer.points(s.sphere), s.triangles());
      EXPECT_LT(maxAngleDegrees(s.view.objectNormals(s.sphere), exact), 1e-3)
          << "resolution " << resolution << " step " << step;
      turned = maxAngleDegrees(start.cast<float>(), exact);
    }
    EXPECT_GT(turned, 5.0) << "the drag should turn some normals visibly";
    s.controller.release();
    EXPECT_EQ(s.view.stats().followedNormals, pressed.followedNormals + 7);  // release recomputes
    const Eigen::MatrixX3f released = s.view.objectNormals(s.sphere);
    const Eigen::MatrixX3f fresh = s.freshNormals();
    ASSERT_EQ(released.rows(), fresh.rows());
    EXPECT_TRUE((released.array() == fresh.array()).all()) << "released normals are not bit for bit the exact ones";
    EXPECT_LT(maxAngleDegrees(released, exactNormals(s.deformer.points(s.sphere), s.triangles())), 1e-3);
  }
  EXPECT_GT(tails, 0);
}

TEST(SceneViewUpdates, ObjectMemoryCountsTheDrawnDataAndTheDragStateWhileADragLasts) {
  // The view holds at least each vertex's float point and float normal (12 bytes each), each
  // triangle's three indices (4 bytes each) and the float sums of the normals (12 per vertex:
  // a drag's first step starts from them); following a drag adds beta and W in float and beta in
  // double (24 bytes per vertex of the dragged object), kept at release for the next drag's first
  // step (no fresh pages to fault in) and reused by it: the next drag holds no more.
  DragSession s(60);
  const Eigen::Index n = s.deformer.pointCount(s.sphere);
  const SceneViewMemory before = s.view.objectMemory();
  EXPECT_EQ(before.vertices, n);
  EXPECT_GE(before.bytes, std::size_t(n) * (12 + 12 + 12) + std::size_t(s.triangles().rows()) * 3 * 4);
  EXPECT_DOUBLE_EQ(before.bytesPerVertex(), double(before.bytes) / double(n));
  ASSERT_EQ(s.controller.press(s.ray(0.5), s.tolerance()), InteractionController::PressResult::Widget);
  s.controller.drag(s.ray(0.75));
  s.controller.drag(s.ray(1.0));
  const SceneViewMemory dragging = s.view.objectMemory();
  EXPECT_GE(dragging.bytes, before.bytes + std::size_t(n) * 24);
  s.controller.release();
  EXPECT_EQ(s.view.objectMemory().bytes, dragging.bytes);
  ASSERT_EQ(s.controller.press(s.ray(0.5), s.tolerance()), InteractionController::PressResult::Widget);
  s.controller.drag(s.ray(0.75));
  s.controller.drag(s.ray(1.0));
  EXPECT_EQ(s.view.objectMemory().bytes, dragging.bytes);
  s.controller.release();
  EXPECT_EQ(SceneViewMemory{}.bytesPerVertex(), 0.0);
}

TEST(SceneViewUpdates, TheViewHoldsFloatPointsAnd32BitCells) {
  // Per vertex of a closed sphere (two triangles a vertex) during a drag: points and normals
  // 12 + 12, cells 8 + 24 (32-bit offsets and indices), the triangles of each vertex 4 + 24, the
  // per-triangle scratch 24, the sums of the normals 12, beta and W 16 and beta in double 8: 144
  // bytes and VTK's object headers. Double points and 64-bit cells held 196.
  DragSession s(120);
  ASSERT_EQ(s.controller.press(s.ray(0.5), s.tolerance()), InteractionController::PressResult::Widget);
  s.controller.drag(s.ray(0.75));
  s.controller.drag(s.ray(1.0));
  const SceneViewMemory dragging = s.view.objectMemory();
  EXPECT_GT(dragging.bytesPerVertex(), 144.0);
  EXPECT_LT(dragging.bytesPerVertex(), 148.0);
  s.controller.release();
}

TEST(SceneViewUpdates, AGestureOfTwoControlPointsRecomputesTheNormalsAtEveryStep) {
  // The followed form covers one control point; two (pairwise D x D' terms) are recomputed.
  DragSession s(40);
  const Eigen::Index f = 1 + 4 * (1 + 4 * 3), g = 2 + 4 * (2 + 4 * 3);
  Eigen::MatrixX3d control = s.scene.widgets.controlPoints(s.lattice);
  const SceneViewStats before = s.view.stats();
  for (int step = 1; step <= 3; ++step) {
    control(f, 2) += 0.05;
    control(g, 0) += 0.04;
    s.scene.widgets.setControlPoints(s.lattice, control);
    s.deformer.updateGesture(s.scene, s.lattice);
    ASSERT_TRUE(s.deformer.gestureMotion(s.sphere));
    ASSERT_EQ(s.deformer.gestureMotion(s.sphere)->controlPoints.size(), 2u);
    s.view.refresh(s.scene, s.deformer);
    EXPECT_TRUE((s.view.objectNormals(s.sphere).array() == s.freshNormals().array()).all()) << "step " << step;
  }
  EXPECT_EQ(s.view.stats().normalUpdates, before.normalUpdates + 3);
  EXPECT_EQ(s.view.stats().followedNormals, before.followedNormals);
}

// The float points the view draws for the shaded object of `n` points, relative to its actor's
// position (null for none).
struct Drawn {
  vtkPoints* points = nullptr;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
};
Drawn drawnPoints(vtkRenderer* renderer, Eigen::Index n) {
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor()) {
    auto* polyData = vtkPolyData::SafeDownCast(actor->GetMapper() ? actor->GetMapper()->GetInput() : nullptr);
    if (polyData && polyData->GetNumberOfPoints() == n && polyData->GetNumberOfPolys() > 0)
      return {polyData->GetPoints(), Eigen::Vector3d(actor->GetPosition())};
  }
  return {};
}

// The largest |drawn - float(exact - origin)| over the coordinates (the drawn points are the
// deformer's relative to the actor's position, rounded to float); infinity when `drawn` is not n
// float points.
double largestDifference(const Drawn& drawn, const Eigen::MatrixX3d& exact) {
  if (drawn.points == nullptr || drawn.points->GetDataType() != VTK_FLOAT ||
      drawn.points->GetNumberOfPoints() != exact.rows())
    return std::numeric_limits<double>::infinity();
  const float* p = static_cast<const float*>(drawn.points->GetVoidPointer(0));
  double worst = 0.0;
  for (Eigen::Index i = 0; i < exact.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(double(p[3 * i + c]) - double(float(exact(i, c) - drawn.origin[c]))));
  return worst;
}

TEST(SceneViewUpdates, AnObjectFarFromTheOriginIsDrawnToFloatRoundingOfItsOwnSize) {
  // A unit sphere placed as in map coordinates (x = 500 km, y = 4000 km): float points relative to
  // the object's centre keep its shape to ~1e-7; absolute float coordinates would round to 0.03
  // (ulp(4e6) / 2 = 0.25, ulp(5e5) / 2 = 0.03).
  ViewedDocument d;
  scenes::PrimitiveOptions sphere;
  sphere.resolution = 30;
  sphere.placement = Eigen::Translation3d(5.0e5, 4.0e6, 120.0);
  const std::string name = d.controller.addPrimitive(sphere);
  d.view.show(d.scene, d.deformer);
  const Eigen::MatrixX3d& exact = d.deformer.points(name);
  const Drawn drawn = drawnPoints(d.renderer, exact.rows());
  ASSERT_NE(drawn.points, nullptr);
  EXPECT_EQ(largestDifference(drawn, exact), 0.0);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < exact.rows(); ++i) {
    double p[3];
    drawn.points->GetPoint(i, p);
    worst = std::max(worst, (Eigen::Vector3d(p[0], p[1], p[2]) + drawn.origin - exact.row(i).transpose()).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 2e-7);
}

TEST(SceneViewUpdates, TheViewDrawsTheDeformersPointsRoundedToFloatAndExactlyThemAtRelease) {
  // The view's points are float32 relative to the actor's position o: float(x - o) for every
  // point it copies from the deformer (show, the first step of a drag, release), and while a drag
  // is followed the float points moved by beta (D(t) - D(t')), off float(x - o) by float rounding.
  DragSession s(80);
  const Eigen::Index n = s.deformer.pointCount(s.sphere);
  EXPECT_EQ(largestDifference(drawnPoints(s.renderer, n), s.deformer.points(s.sphere)), 0.0) << "shown";
  ASSERT_EQ(s.controller.press(s.ray(0.5), s.tolerance()), InteractionController::PressResult::Widget);
  for (int step = 1; step <= 12; ++step) {
    s.controller.drag(s.ray(0.5 + 0.15 * step));
    const double off = largestDifference(drawnPoints(s.renderer, n), s.deformer.points(s.sphere));
    if (step == 1)
      EXPECT_EQ(off, 0.0) << "the first step copies the deformer's points";
    else
      EXPECT_LT(off, 2e-6) << "step " << step;  // a unit sphere: ulp(1) = 1.2e-7 a step at most
  }
  s.controller.release();
  EXPECT_EQ(largestDifference(drawnPoints(s.renderer, n), s.deformer.points(s.sphere)), 0.0) << "released";
  // Undo: the exact points again.
  s.commands.undo();
  EXPECT_EQ(largestDifference(drawnPoints(s.renderer, n), s.deformer.points(s.sphere)), 0.0) << "undone";
}

TEST(SceneViewUpdates, TheFirstStepOfADragStartsFromTheNormalsDrawnBeforeIt) {
  // The first step of a one-control-point drag whose motion starts from the points the view drew
  // last (after show, a release, an undo) adds D x W to the sums of their normals instead of
  // computing the triangles' area vectors again (gesture_normals.h); the normals are the exact
  // ones to float rounding, and at release the exact ones bit for bit.
  DragSession s(120);
  for (int drag = 0; drag < 3; ++drag) {
    const SceneViewStats before = s.view.stats();
    ASSERT_EQ(s.controller.press(s.ray(0.5), s.tolerance()), InteractionController::PressResult::Widget);
    s.controller.drag(s.ray(1.0 + 0.5 * drag));
    EXPECT_EQ(s.view.stats().normalsFromBase, before.normalsFromBase + 1) << "drag " << drag;
    EXPECT_EQ(s.view.stats().followedNormals, before.followedNormals) << "drag " << drag;
    const Eigen::MatrixX3d exact = exactNormals(s.deformer.points(s.sphere), s.triangles());
    EXPECT_LT(maxAngleDegrees(s.view.objectNormals(s.sphere), exact), 1e-3) << "drag " << drag;
    s.controller.drag(s.ray(1.2 + 0.5 * drag));
    EXPECT_EQ(s.view.stats().followedNormals, before.followedNormals + 1) << "drag " << drag;
    EXPECT_LT(maxAngleDegrees(s.view.objectNormals(s.sphere), exactNormals(s.deformer.points(s.sphere), s.triangles())),
              1e-3)
        << "drag " << drag;
    s.controller.release();
    EXPECT_TRUE((s.view.objectNormals(s.sphere).array() == s.freshNormals().array()).all()) << "drag " << drag;
    if (drag == 1) s.commands.undo();  // the next drag starts from the undone points
  }
}

// The transformer follows the widget it moves at every drag step: its actors are moved, not built
// again, and stand where the actors of a view that showed the moved transformer from the start do.
TEST(SceneViewUpdates, AMovedTransformerMovesItsActorsWithoutBuildingThem) {
  struct Viewed {  // a view in a render window (the transformer's overlay renderer needs one; no GL draw)
    vtkNew<vtkRenderWindow> window;
    vtkNew<vtkRenderer> renderer;
    std::unique_ptr<SceneView> view;
    scenes::Scene scene;
    scenes::SceneDeformer deformer;
    explicit Viewed(const Transformer& t) {
      window->AddRenderer(renderer);
      view = std::make_unique<SceneView>(renderer);
      ViewHighlights h;
      h.transformer = t;
      view->setHighlights(h);
      view->show(scene, deformer);
    }
    std::vector<Eigen::Matrix4d> overlayMatrices() const {  // the actors of the layer above, in order
      std::vector<Eigen::Matrix4d> out;
      vtkRendererCollection* renderers = window->GetRenderers();
      renderers->InitTraversal();
      while (vtkRenderer* r = renderers->GetNextItem()) {
        if (r == renderer.GetPointer()) continue;
        vtkActorCollection* actors = r->GetActors();
        actors->InitTraversal();
        while (vtkActor* actor = actors->GetNextActor()) {
          Eigen::Matrix4d m;
          for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) m(i, j) = actor->GetMatrix()->GetElement(i, j);
          out.push_back(m);
        }
      }
      return out;
    }
  };
  Transformer start;
  start.frame = Eigen::Translation3d(0.5, -1.0, 2.0) * Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized());
  start.size = 1.5;
  Transformer moved = start;
  moved.frame = Eigen::Translation3d(-2.0, 0.25, 1.0) * Eigen::AngleAxisd(1.1, Eigen::Vector3d(0, 1, 1).normalized());

  Viewed dragged(start);
  ASSERT_EQ(dragged.view->stats().overlayBuilds, 1);
  ASSERT_EQ(dragged.overlayMatrices().size(), 9u);  // three arrows, rings and cubes
  for (int step = 0; step < 3; ++step) {
    ViewHighlights h;
    h.transformer = step % 2 == 0 ? moved : start;
    dragged.view->setHighlights(h);
    dragged.view->refresh(dragged.scene, dragged.deformer);
  }
  EXPECT_EQ(dragged.view->stats().overlayBuilds, 1) << "moved, not built again";
  const Viewed fresh(moved);
  const std::vector<Eigen::Matrix4d> got = dragged.overlayMatrices(), expected = fresh.overlayMatrices();
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t k = 0; k < got.size(); ++k) EXPECT_LT((got[k] - expected[k]).cwiseAbs().maxCoeff(), 1e-12) << k;

  ViewHighlights resized;
  resized.transformer = moved;
  resized.transformer->size = 3.0;
  dragged.view->setHighlights(resized);
  dragged.view->refresh(dragged.scene, dragged.deformer);
  EXPECT_EQ(dragged.view->stats().overlayBuilds, 2) << "another size builds the shapes again";
}

}  // namespace
}  // namespace ffdkit::app
