#pragma once

// SceneView's state (private to ffdkit::render): the actors it draws and what they were built
// for. Its work is split by concept, one file each:
//   scene_view.cpp                  show, refresh and the camera (SceneView's own members)
//   scene_view_objects.cpp          the object actors: built from the scene, normals, memory
//   scene_view_level_of_detail.cpp  the objects' proxies while things move, the evaluation request
//   scene_view_widgets.cpp          the widget actors: built for a model, redrawn per change
//   scene_view_highlights.cpp       colours, pins, fold tints, the soft radius: no widget geometry
//   scene_view_transformer.cpp      the transformer manipulator in the overlay renderer
// scene_view_shapes.h builds the VTK data they draw.

#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vtkActor.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include "ffdkit/render/scene_view.h"
#include "ffdkit/widgets/widget_model.h"
#include "gesture_normals.h"
#include "object_proxy.h"
#include "outward_faces.h"
#include "scene_view_shapes.h"

namespace ffdkit::app {

struct SceneView::Impl {
  static inline const Eigen::Vector3d kSelected{1.0, 0.9, 0.2};
  static inline const Eigen::Vector3d kVisited{1.0, 0.45, 1.0};

  static bool contains(const std::vector<widgets::WidgetId>& ids, widgets::WidgetId id) {
    return std::find(ids.begin(), ids.end(), id) != ids.end();
  }

  struct ObjectActor {
    scenes::ObjectId id;                      ///< the object drawn (a rename keeps the actor)
    std::string name;                         ///< its name at the last refresh (objectNormals)
    Eigen::Index pointCount = 0;
    std::uint64_t pointsRevision = 0;         ///< SceneDeformer::revision of the points drawn
    scenes::DisplaySettings display;          ///< as drawn; a change rebuilds the actor
    double combFactor = 0.0;                  ///< tooth length per unit curvature
    std::vector<std::vector<int>> chains;     ///< curves: the segments in curve order (comb)
    vtkSmartPointer<vtkActor> comb;           ///< the curvature comb, or null
    scene_view_shapes::VertexFaces vertexFaces;  ///< of the triangles, for the normals
    Eigen::Vector3d restLo, restHi;           ///< bounding box of the object's own points
    bool keepsOutward = false;                ///< the lattices keep its faces outward (outward_faces.h)
    Eigen::Vector3d origin;                   ///< the float points are relative to it (object_arrays.h)
    std::vector<Eigen::Vector3f> faceNormals; ///< scratch
    GestureNormals gestureNormals;            ///< the normals followed along a drag
    vtkSmartPointer<vtkPolyData> polyData;
    vtkSmartPointer<vtkActor> actor;
    std::unique_ptr<ObjectProxy> proxy;       ///< level of detail (object_proxy.h), or null
  };
  vtkRenderer* renderer = nullptr;
  std::vector<ObjectActor> objects;
  std::uint64_t namesSeen = 0;  // Scene::structureRevision when the actors' names were last set
  // Widget actors are built for a new model instance, and for the widgets a change concerns when
  // the model's revision moved (widgets::widgetsToRedraw); a change of the highlights only
  // recolours them, shows or hides the selected lattices' faces and moves the point marker:
  // hover and selection build no geometry.
  enum class Role { Lattice, LatticeFaces, Cell, Glyph };
  struct WidgetActor {
    vtkSmartPointer<vtkActor> actor;
    widgets::WidgetId id;
    Role role = Role::Lattice;
    Eigen::Vector3d base = Eigen::Vector3d::Ones();
  };
  std::vector<WidgetActor> widgets;
  std::vector<vtkSmartPointer<vtkActor>> widgetActors;  // every widget actor, for removal
  vtkSmartPointer<vtkActor> pointMarker;                // the picked lattice point, moved by a transform
  vtkSmartPointer<vtkActor> selectedPoints;             // the edit mode's selected points
  std::vector<LatticePointRef> selectedShown;           // ... as drawn
  std::uint64_t selectedRevision = 0;                   // of the model they were drawn for
  std::uint64_t widgetInstance = 0, widgetRevision = 0;  // of the model the widget actors show
  // Glyph shapes at size 1 by shape, kind and part placement: built once, shared by the actors.
  std::map<std::string, vtkSmartPointer<vtkPolyData>> glyphShapes;
  std::optional<Transformer> overlayBuiltFor;  // the transformer the overlay actors show
  SceneViewStats stats;
  // The transformer manipulator is drawn by a second renderer in the layer above, sharing the
  // camera, so that it stays visible inside the object it moves (a lattice's centre usually is).
  vtkSmartPointer<vtkRenderer> overlay;
  std::vector<vtkSmartPointer<vtkActor>> overlayActors;
  std::vector<TransformerHandle> overlayHandles;  // of overlayActors, in order
  std::vector<Eigen::Affine3d> overlayPlaces;      // of overlayActors: each shape's place in the frame
  // The transformer's three shapes at size 1 (built once; the actors place them per frame).
  vtkSmartPointer<vtkPolyData> transformerArrow, transformerRing, transformerCube;
  ViewHighlights highlights;
  // Pinned object points (direct manipulation): red dots, rebuilt only when the pins move.
  vtkSmartPointer<vtkActor> pins;
  std::vector<Eigen::Vector3d> pinsShown;
  // The fold-over tint of lattice cells (red: folds, amber: unknown), rebuilt when the tints or
  // the model changed; and the soft selection's radius as three circles round the pivot.
  vtkSmartPointer<vtkActor> foldTint, softSphere;
  std::vector<FoldTint> foldTintShown;
  std::uint64_t foldTintRevision = 0;
  std::optional<SoftRadius> softRadiusShown;
  // --- Level of detail (LevelOfDetail, object_proxy.h): while things move, a large shaded surface
  // draws its proxy and its own arrays are left as they are until the motion stops.
  LevelOfDetail lod;
  bool moving = false;  // setMoving (playback)

  // The object actors (scene_view_objects.cpp).
  void clearObjects();
  void buildObjects(const scenes::Scene& scene, const scenes::SceneDeformer& deformed);
  bool sameObjects(const scenes::Scene& scene) const;
  // Tells the objects' mappers whether a lattice may fold or tear them (SurfaceMapper::setFoldFree):
  // no back faces culled while the highlights tint a lattice's cells as folding or unknown, nor
  // unless the lattices keep the object's faces outward (ObjectActor::keepsOutward).
  void updateFoldFree();
  void updateFoldFree(ObjectActor& entry);  // ... of one object
  // Asks the lattices again whether they keep a closed surface's faces outward (when its full mesh
  // is drawn: a proxy is never culled), then tells its mapper.
  void updateKeepsOutward(ObjectActor& entry, const widgets::WidgetModel& model);
  OutwardFacesGuard outwardFaces;

  // Level of detail (scene_view_level_of_detail.cpp).
  void prepareProxy(ObjectActor& entry, const scenes::SceneObject* object);
  bool drawProxy(ObjectActor& entry, const scenes::Scene& scene, const scenes::SceneDeformer& deformed);

  // The widget actors (scene_view_widgets.cpp).
  vtkSmartPointer<vtkActor> addWidgetActor(vtkPolyData* polyData, const Eigen::Vector3d& colour);
  vtkSmartPointer<vtkActor> addWidgetActor(vtkPolyData* polyData, widgets::WidgetId id, Role role,
                                           const Eigen::Vector3d& base);
  vtkPolyData* cachedGlyph(const widgets::Glyph& glyph, widgets::AffineKind kind);
  void addWidgetActors(const widgets::WidgetModel& model, widgets::WidgetId id);
  void buildWidgets(const widgets::WidgetModel& model);
  void redrawWidgets(const widgets::WidgetModel& model, const std::vector<widgets::WidgetId>& redraw);
  void updateWidgets(const widgets::WidgetModel& model);

  // The highlights (scene_view_highlights.cpp).
  void updatePins();
  vtkSmartPointer<vtkActor> addPlainActor();
  void updateFoldTintAndRadius(const widgets::WidgetModel& model);
  Eigen::Vector3d emphasis(widgets::WidgetId id, const Eigen::Vector3d& base) const;
  void applyHighlights(const widgets::WidgetModel& model);

  // The transformer manipulator (scene_view_transformer.cpp).
  void removeOverlay();
  vtkRenderer* overlayRenderer();
  static bool sameShapes(const std::optional<Transformer>& a, const std::optional<Transformer>& b);
  void updateTransformer();
  static void placeOverlayActor(vtkActor* actor, const Eigen::Affine3d& place);
  void buildTransformer();
};

}  // namespace ffdkit::app
