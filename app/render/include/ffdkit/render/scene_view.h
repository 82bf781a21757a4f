#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/interaction/camera_navigation.h"
#include "ffdkit/interaction/transformer.h"
#include "ffdkit/interaction/view_highlights.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/widgets/ray.h"
#include "ffdkit/widgets/widget_id.h"

class vtkRenderer;

namespace ffdkit::app {

/// The two (unlit) colours of a surface drawn in zebra style (scenes::SurfaceStyle::Zebra).
inline const Eigen::Vector3d kZebraDark{0.08, 0.08, 0.10};
inline const Eigen::Vector3d kZebraLight{0.96, 0.96, 0.96};
/// The colour of curvature combs.
inline const Eigen::Vector3d kCombColour{1.0, 0.35, 0.75};
/// The colour of pinned object points (direct manipulation).
inline const Eigen::Vector3d kPinColour{0.95, 0.15, 0.15};

/// What a SceneView has built and updated since it was made (how tests see that hover and
/// selection build no geometry and that a drag step touches only the objects that moved).
struct SceneViewStats {
  int objectBuilds = 0;   ///< object actors made (show(), or a refresh after the objects changed)
  int pointUpdates = 0;   ///< object point arrays rewritten in place
  int normalUpdates = 0;  ///< object normal arrays recomputed in place
  /// Of normalUpdates, those that followed a drag of one control point (one cross product per
  /// vertex, exact to float rounding) instead of a pass over the triangles (app/render/src/gesture_normals.h).
  int followedNormals = 0;
  /// Of normalUpdates, first steps of a one-control-point drag that started from the normals the
  /// view drew last: N(base) + D x W, without computing the triangles' area vectors again.
  int normalsFromBase = 0;
  /// Updates of the widget actors (the model changed): all of them for a new model instance, those
  /// of the widgets the change concerns otherwise (widgets::widgetsToRedraw).
  int widgetBuilds = 0;
  int widgetActorBuilds = 0;  ///< widgets whose actors were built, one per widget (a lattice's two count once)
  int overlayBuilds = 0;  ///< builds of the transformer's actors (another size; a moved transformer moves them)
  int proxyBuilds = 0;    ///< level-of-detail proxies built (LevelOfDetail; once per object actor)
  int proxyUpdates = 0;   ///< proxy point arrays rewritten (a gesture step or a played frame)
  /// Fold-over checks the view made itself to decide whether a closed surface's back faces may be
  /// culled (app/render/src/outward_faces.h): one per lattice and change of it that no controller's
  /// verdict (ViewHighlights::certified) already covered.
  int foldChecks = 0;
};

/// How a SceneView draws large objects while things move (SceneView::setLevelOfDetail), as VTK's
/// LOD actors and Blender's Simplify do: during a gesture (SceneDeformer::inGesture) and while
/// SceneView::setMoving(true) (playback), a shaded surface of at least `minVertices` vertices is
/// drawn as its proxy, a decimation of the mesh built once per object when its actor is built
/// (show(), or the refresh() after the level of detail changed), so the first gesture does not pay
/// for it (vertex clustering: the proxy's vertices are a subset of the mesh's, so its deformed
/// points are the object's deformed points at those indices and a step costs the proxy's size). The next refresh() after the motion
/// draws the full mesh, exact. Widgets, lattices, curves and zebra-striped surfaces are always
/// drawn in full; what is picked and exported never depends on what is drawn.
struct LevelOfDetail {
  bool enabled = true;                ///< false: every object is always drawn in full
  Eigen::Index minVertices = 250000;  ///< objects with fewer vertices are always drawn in full
  /// About this many vertices in a proxy: what a frame draws of the object while things move (its
  /// cost under a software rasteriser grows with it: docs/app.md, "Large meshes: level of detail").
  Eigen::Index proxyVertices = 10000;
};

/// What a SceneView holds in memory for the objects it draws (SceneView::objectMemory).
struct SceneViewMemory {
  /// Heap bytes: the VTK data of each object (points, cells, normals, texture coordinates), the
  /// triangles around each vertex and the per-triangle scratch of the normals, and what the
  /// normals keep to follow a drag (gesture_normals.h).
  std::size_t bytes = 0;
  Eigen::Index vertices = 0;  ///< vertices drawn, over all objects
  /// bytes / vertices (0 for no vertex): the view's memory per vertex.
  double bytesPerVertex() const { return vertices > 0 ? double(bytes) / double(vertices) : 0.0; }
};

/// Draws a scene into a VTK renderer: shaded (or zebra-striped, DisplaySettings::surfaceStyle)
/// objects at their deformed points, curves as tubes (with a curvature comb of the deformed
/// polyline when DisplaySettings::curvatureComb is set), lattice points and edges, cells as
/// points, affine widgets as glyphs at their frames (arrow = translate, ring = rotate, cube =
/// scale, or a part of the parts library), coloured by kind, with hover / selection / gesture
/// highlights. Change-driven: refresh() rewrites the point array (and normals) of an object only
/// when its deformed points moved (SceneDeformer::revision), rebuilds the actors of just the widgets
/// a model change concerns (WidgetModel::changesSince, widgets::widgetsToRedraw; all of them for
/// another model instance), and applies highlights by recolouring
/// and showing or hiding actors, so hover and selection build no geometry.
class SceneView {
 public:
  /// Draws into `renderer` (not owned; must outlive the view).
  explicit SceneView(vtkRenderer* renderer);
  ~SceneView();
  SceneView(const SceneView&) = delete;
  SceneView& operator=(const SceneView&) = delete;

  /// Replaces what is drawn with `scene`, its objects at the points `deformed` computed, and
  /// sets background and camera from it.
  void show(const scenes::Scene& scene, const scenes::SceneDeformer& deformed);

  /// Like show() but keeps the camera; when the objects are the same as last time only their
  /// points are replaced (a drag step).
  void refresh(const scenes::Scene& scene, const scenes::SceneDeformer& deformed);

  /// Highlights used by the next show() / refresh().
  void setHighlights(const ViewHighlights& highlights);

  /// Sets how large objects are drawn while things move; a change of the proxies' size or
  /// threshold builds them again at the next refresh().
  void setLevelOfDetail(const LevelOfDetail& lod);
  /// The level of detail set (the default LevelOfDetail unless set).
  const LevelOfDetail& levelOfDetail() const;
  /// Marks a stream of changes outside a gesture (playback): until setMoving(false), refresh()
  /// draws large objects as their proxies. The refresh() after setMoving(false) draws them in full.
  void setMoving(bool moving);
  /// What the next refresh() reads of the deformer, for SceneDeformer::evaluate: during a gesture
  /// an object drawn as its proxy is read at the proxy's vertices only (EvaluationRequest::subsets),
  /// so its evaluation costs the proxy's size and its full mesh waits for the gesture's end; an
  /// object drawn in full whose normals follow a one-control-point drag (the steps after its
  /// first) is named as followed (EvaluationRequest::followed: the view reads its motion only, and
  /// the deformer's delta passes over its points wait); every other object in full. Builds the proxies the level of detail asks for first (as refresh()
  /// would). Asks for no subset when the drawn objects changed (refresh() then builds every actor
  /// from full points). The spans point into the view's proxies: valid until the next refresh().
  scenes::EvaluationRequest evaluationRequest(const scenes::Scene& scene, const scenes::SceneDeformer& deformed);
  /// True when `object` is drawn as its level-of-detail proxy now.
  bool showsProxy(const std::string& object) const;
  /// The points of `object`'s full mesh as the view holds them, #points x 3 (empty when it is not
  /// drawn). For tests.
  Eigen::MatrixX3d objectPoints(const std::string& object) const;

  const SceneViewStats& stats() const;
  /// The memory the view holds for the objects it draws now.
  SceneViewMemory objectMemory() const;
  /// The vertex normals drawn for `object`, #points x 3 (empty when it is not drawn or has no
  /// triangles). For tests.
  Eigen::MatrixX3f objectNormals(const std::string& object) const;

  /// Sets the renderer's camera from `camera` (clipping range reset to the scene).
  void applyCamera(const scenes::Camera& camera);
  /// The renderer's current camera.
  scenes::Camera camera() const;
  /// The camera with its projection (orthographic or not) as navigation changes it.
  ViewCamera viewCamera() const;
  /// Sets the renderer's camera and projection (clipping range reset to the scene).
  void setViewCamera(const ViewCamera& view);

  /// World ray from the camera through display pixel (x, y) (VTK display coordinates: device
  /// pixels, origin at the bottom left). Needs the renderer to be in a sized render window.
  widgets::Ray rayAt(double x, double y) const;
  /// Display pixel (VTK display coordinates, as rayAt) where the world point `p` is drawn.
  Eigen::Vector2d displayPoint(const Eigen::Vector3d& p) const;
  /// World length of one pixel at the camera's focal distance (for pick tolerances).
  double pixelSize() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ffdkit::app
