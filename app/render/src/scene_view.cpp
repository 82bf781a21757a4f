#include "ffdkit/render/scene_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <vtkActor.h>
#include <vtkAppendPolyData.h>
#include <vtkArrowSource.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCubeSource.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkPointData.h>
#include <vtkNew.h>
#include <vtkParametricFunctionSource.h>
#include <vtkParametricTorus.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTexture.h>
#include <vtkTransform.h>
#include <vtkTubeFilter.h>

#include "ffdkit/render/curvature_comb.h"
#include "ffdkit/parts/parts.h"
#include "gesture_normals.h"
#include "object_arrays.h"
#include "object_proxy.h"
#include "ffdkit/widgets/widget_model.h"
#include "ffdkit/widgets/widget_redraw.h"
#include "scene_view_shapes.h"
#include "surface_mapper.h"

namespace ffdkit::app {
namespace {

using namespace scene_view_shapes;
using widgets::AffineKind;
using widgets::WidgetId;

const Eigen::Vector3d kSelected{1.0, 0.9, 0.2};
const Eigen::Vector3d kVisited{1.0, 0.45, 1.0};

bool contains(const std::vector<WidgetId>& ids, WidgetId id) { return std::find(ids.begin(), ids.end(), id) != ids.end(); }

}  // namespace

struct SceneView::Impl {
  struct ObjectActor {
    scenes::ObjectId id;                      ///< the object drawn (a rename keeps the actor)
    std::string name;                         ///< its name at the last refresh (objectNormals)
    Eigen::Index pointCount = 0;
    std::uint64_t pointsRevision = 0;         ///< SceneDeformer::revision of the points drawn
    scenes::DisplaySettings display;          ///< as drawn; a change rebuilds the actor
    double combFactor = 0.0;                  ///< tooth length per unit curvature
    std::vector<std::vector<int>> chains;     ///< curves: the segments in curve order (comb)
    vtkSmartPointer<vtkActor> comb;           ///< the curvature comb, or null
    VertexFaces vertexFaces;                  ///< of the triangles, for the normals
    Eigen::Vector3d restLo, restHi;           ///< bounding box of the object's own points
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
    WidgetId id;
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

  void updatePins() {
    if (pins && highlights.pins == pinsShown) return;
    pinsShown = highlights.pins;
    Eigen::MatrixX3d points(static_cast<Eigen::Index>(pinsShown.size()), 3);
    for (std::size_t i = 0; i < pinsShown.size(); ++i) points.row(static_cast<Eigen::Index>(i)) = pinsShown[i].transpose();
    if (!pins) {
      pins = vtkSmartPointer<vtkActor>::New();
      pins->SetMapper(vtkSmartPointer<vtkPolyDataMapper>::New());
      pins->GetProperty()->SetColor(kPinColour.x(), kPinColour.y(), kPinColour.z());
      pins->GetProperty()->SetPointSize(14.0);
      pins->GetProperty()->SetRenderPointsAsSpheres(true);
      pins->GetProperty()->SetLighting(false);
      renderer->AddActor(pins);
    }
    vtkPolyDataMapper::SafeDownCast(pins->GetMapper())->SetInputData(pointsPolyData(points));
    pins->SetVisibility(!pinsShown.empty());
  }

  // The fold-over tint of lattice cells (red: folds, amber: unknown), rebuilt when the tints or
  // the model changed; and the soft selection's radius as three circles round the pivot.
  vtkSmartPointer<vtkActor> foldTint, softSphere;
  std::vector<FoldTint> foldTintShown;
  std::uint64_t foldTintRevision = 0;
  std::optional<SoftRadius> softRadiusShown;

  vtkSmartPointer<vtkActor> addPlainActor() {
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(vtkSmartPointer<vtkPolyDataMapper>::New());
    renderer->AddActor(actor);
    return actor;
  }

  void updateFoldTintAndRadius(const widgets::WidgetModel& model) {
    if (!foldTint) {
      foldTint = addPlainActor();
      foldTint->GetProperty()->SetOpacity(0.45);
      softSphere = addPlainActor();
      softSphere->GetProperty()->SetColor(0.95, 0.95, 0.95);
      softSphere->GetProperty()->SetLighting(false);
      softSphere->GetProperty()->SetLineWidth(1.5);
    }
    if (highlights.foldTints != foldTintShown || (!foldTintShown.empty() && foldTintRevision != model.revision())) {
      foldTintShown = highlights.foldTints;
      foldTintRevision = model.revision();
      vtkNew<vtkAppendPolyData> all;
      for (const FoldTint& tint : foldTintShown) {
        if (!model.contains(tint.lattice) || model.type(tint.lattice) != widgets::WidgetType::Lattice) continue;
        // A tint of another lattice under that id (the scene before an Open) or of its older cells
        // is not drawn: its verdicts would be indexed past the lattice's cells.
        const ffd::Lattice lattice = model.ffdLattice(tint.lattice);
        const std::array<int, 3> cells{lattice.axis(0).cellCount(), lattice.axis(1).cellCount(), lattice.axis(2).cellCount()};
        if (cells == tint.cellCounts) all->AddInputData(foldTintPolyData(lattice, tint.cellCounts, tint.cells));
      }
      if (all->GetNumberOfInputConnections(0) > 0) {
        all->Update();
        vtkPolyDataMapper::SafeDownCast(foldTint->GetMapper())->SetInputData(all->GetOutput());
      }
      foldTint->SetVisibility(all->GetNumberOfInputConnections(0) > 0);
    }
    if (highlights.softRadius != softRadiusShown) {
      softRadiusShown = highlights.softRadius;
      if (softRadiusShown)
        vtkPolyDataMapper::SafeDownCast(softSphere->GetMapper())
            ->SetInputData(sphereCirclesPolyData(softRadiusShown->centre, softRadiusShown->radius));
      softSphere->SetVisibility(softRadiusShown.has_value());
    }
  }

  Eigen::Vector3d emphasis(WidgetId id, const Eigen::Vector3d& base) const {
    if (contains(highlights.selected, id)) return kSelected;
    if (contains(highlights.visited, id)) return kVisited;
    if (highlights.hovered == id) return 0.45 * base + 0.55 * Eigen::Vector3d::Ones();
    return base;
  }

  vtkSmartPointer<vtkActor> addWidgetActor(vtkPolyData* polyData, const Eigen::Vector3d& colour) {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(polyData);
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(colour.x(), colour.y(), colour.z());
    renderer->AddActor(actor);
    widgetActors.push_back(actor);
    return actor;
  }
  vtkSmartPointer<vtkActor> addWidgetActor(vtkPolyData* polyData, WidgetId id, Role role, const Eigen::Vector3d& base) {
    auto actor = addWidgetActor(polyData, base);
    widgets.push_back({actor, id, role, base});
    return actor;
  }

  vtkPolyData* cachedGlyph(const widgets::Glyph& glyph, AffineKind kind) {
    std::string key = glyph.shape + "|" + std::string(widgets::affineKindName(kind));
    if (partMesh(glyph.shape)) {
      const Eigen::Matrix4d& m = glyph.partPlacement.matrix();
      key.append(reinterpret_cast<const char*>(m.data()), sizeof(double) * 16);
    }
    auto& shape = glyphShapes[key];
    if (!shape) shape = glyphShape(glyph, kind);
    return shape;
  }

  // Colours, line widths, the selected lattices' faces and the point marker from the highlights.
  void applyHighlights(const widgets::WidgetModel& model) {
    for (const WidgetActor& w : widgets) {
      const bool selected = contains(highlights.selected, w.id);
      vtkProperty* property = w.actor->GetProperty();
      if (w.role == Role::LatticeFaces) {
        w.actor->SetVisibility(selected);
        continue;
      }
      const Eigen::Vector3d colour = emphasis(w.id, w.base);
      property->SetColor(colour.x(), colour.y(), colour.z());
      if (w.role == Role::Lattice) property->SetLineWidth(selected ? 3.0 : 1.5);
    }
    const bool marked = highlights.point && model.contains(highlights.point->lattice) &&
                        model.type(highlights.point->lattice) == widgets::WidgetType::Lattice &&
                        highlights.point->index < model.controlPoints(highlights.point->lattice).rows();
    pointMarker->SetVisibility(marked);
    // The edit mode's selection: its few points again when it or the model changed.
    if (highlights.selectedPoints != selectedShown || selectedRevision != model.revision()) {
      selectedShown = highlights.selectedPoints;
      selectedRevision = model.revision();
      Eigen::MatrixX3d points(static_cast<Eigen::Index>(selectedShown.size()), 3);
      Eigen::Index row = 0;
      for (const LatticePointRef& p : selectedShown)
        if (model.contains(p.lattice) && model.type(p.lattice) == widgets::WidgetType::Lattice &&
            p.index < model.controlPoints(p.lattice).rows())
          points.row(row++) = (model.latticeFrame(p.lattice) * Eigen::Vector3d(model.controlPoints(p.lattice).row(p.index).transpose())).transpose();
      vtkPolyDataMapper::SafeDownCast(selectedPoints->GetMapper())->SetInputData(pointsPolyData(points.topRows(row)));
    }
    selectedPoints->SetVisibility(!selectedShown.empty());
    if (marked) {
      const Eigen::Vector3d p =
          model.latticeFrame(highlights.point->lattice) *
          Eigen::Vector3d(model.controlPoints(highlights.point->lattice).row(highlights.point->index).transpose());
      pointMarker->SetPosition(p.x(), p.y(), p.z());
    }
  }

  // --- Level of detail (LevelOfDetail, object_proxy.h): while things move, a large shaded surface
  // draws its proxy and its own arrays are left as they are until the motion stops.
  LevelOfDetail lod;
  bool moving = false;  // setMoving (playback)
  // The proxy built with the actor and at each refresh, not at the first gesture (object_proxy.h).
  void prepareProxy(ObjectActor& entry, const scenes::SceneObject* object) {
    if (prepareObjectProxy(entry.proxy, lod, renderer, entry.actor, object, entry.pointCount, entry.display))
      ++stats.proxyBuilds;
  }
  // Draws `entry` as its proxy when things move and it is large enough; returns whether it did.
  // Otherwise the object's own actor is shown.
  bool drawProxy(ObjectActor& entry, const scenes::Scene& scene, const scenes::SceneDeformer& deformed) {
    prepareProxy(entry, scene.findObject(entry.id));
    if (!(moving || deformed.inGesture()) || !entry.proxy) {
      if (entry.proxy && entry.proxy->shown()) entry.proxy->show(false);
      return false;
    }
    entry.proxy->show(true);
    if (entry.proxy->update(deformed, entry.id)) ++stats.proxyUpdates;
    return true;
  }
  // --- end of level of detail

  void clearObjects() {
    for (auto& o : objects) {
      renderer->RemoveActor(o.actor);
      if (o.comb) renderer->RemoveActor(o.comb);
    }
    objects.clear();
  }

  void buildObjects(const scenes::Scene& scene, const scenes::SceneDeformer& deformed) {
    clearObjects();
    for (const auto& object : scene.objects()) {
      if (!object.display.visible) continue;
      ObjectActor entry;
      entry.id = object.id;
      entry.name = object.name;
      const Eigen::MatrixX3d& points = deformed.points(object.id);
      entry.pointCount = points.rows();
      entry.pointsRevision = deformed.revision(object.id);
      entry.restLo = object.mesh.points.rows() > 0 ? Eigen::Vector3d(object.mesh.points.colwise().minCoeff().transpose())
                                                   : Eigen::Vector3d::Zero();
      entry.restHi = object.mesh.points.rows() > 0 ? Eigen::Vector3d(object.mesh.points.colwise().maxCoeff().transpose())
                                                   : Eigen::Vector3d::Zero();
      entry.display = object.display;
      entry.origin = 0.5 * (entry.restLo + entry.restHi);  // of its own points: the same in every view
      entry.polyData = object_arrays::objectPolyData(object.mesh, points, entry.origin);  // float32, 32-bit cells
      const bool zebra = object.display.surfaceStyle == scenes::SurfaceStyle::Zebra && object.mesh.triangles.rows() > 0;
      constexpr double kCurveLineWidth = 2.0;  // pixels, DisplaySettings::curveStyle
      const bool curveLine = object.display.curveStyle == scenes::CurveStyle::Line && object.mesh.triangles.rows() == 0 &&
                             object.mesh.segments.rows() > 0;
      vtkNew<SurfaceMapper> mapper;  // surface_mapper.h: no index buffer or cell bounds per frame
      if (object.mesh.triangles.rows() > 0) {
        vtkNew<vtkFloatArray> normals;  // smooth shading of the deformed surface
        entry.vertexFaces = vertexFaces(object.mesh.triangles, points.rows());
        entry.gestureNormals.update(deformed, object.id, object.mesh.triangles, entry.vertexFaces, points, entry.origin,
                                    entry.faceNormals, entry.polyData->GetPoints(), normals);
        entry.polyData->GetPointData()->SetNormals(normals);
        if (zebra) {
          vtkNew<vtkFloatArray> tcoords;
          updateZebraCoordinates(tcoords, normals, object.display.zebraDirection, object.display.zebraStripes);
          entry.polyData->GetPointData()->SetTCoords(tcoords);
        }
        mapper->SetInputData(entry.polyData);
      } else if (object.mesh.segments.rows() > 0) {
        if (curveLine) {
          // Curves as lines: the polyline itself (unlit, set below), the exact points drawn.
          mapper->SetInputData(entry.polyData);
        } else {
          // Curves as shaded tubes, thick enough to read at any zoom of the object.
          const double diagonal = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
          vtkNew<vtkTubeFilter> tubes;
          tubes->SetInputData(entry.polyData);
          tubes->SetRadius(std::max(1e-6, 0.006 * diagonal));
          tubes->SetNumberOfSides(10);
          tubes->CappingOn();
          mapper->SetInputConnection(tubes->GetOutputPort());
        }
        if (object.display.curvatureComb) {
          entry.chains = segmentChains(object.mesh.segments, points.rows());
          entry.combFactor = combFactor(entry.chains, object.mesh.points, object.display.combScale,
                                        (entry.restHi - entry.restLo).norm());
          vtkNew<vtkPolyDataMapper> combMapper;
          combMapper->SetInputData(combPolyData(entry.chains, points, entry.combFactor));
          entry.comb = vtkSmartPointer<vtkActor>::New();
          entry.comb->SetMapper(combMapper);
          entry.comb->GetProperty()->SetColor(kCombColour.x(), kCombColour.y(), kCombColour.z());
          entry.comb->GetProperty()->SetLighting(false);
          entry.comb->GetProperty()->SetLineWidth(1.5);
          renderer->AddActor(entry.comb);
        }
      } else {
        mapper->SetInputData(entry.polyData);
      }
      entry.actor = vtkSmartPointer<vtkActor>::New();
      entry.actor->SetPosition(entry.origin.data());  // where the float points are relative to
      entry.actor->GetProperty()->SetLineWidth(3.0);
      entry.actor->GetProperty()->SetPointSize(4.0);
      entry.actor->SetMapper(mapper);
      entry.actor->GetProperty()->SetColor(object.display.color.x(), object.display.color.y(), object.display.color.z());
      entry.actor->GetProperty()->SetOpacity(object.display.opacity);
      entry.actor->GetProperty()->SetSpecular(0.2);
      entry.actor->GetProperty()->SetSpecularPower(30);
      if (zebra) {  // unlit stripes: the texture's colours exactly
        entry.actor->SetTexture(zebraTexture());
        entry.actor->GetProperty()->SetColor(1.0, 1.0, 1.0);
        entry.actor->GetProperty()->SetLighting(false);
      }
      if (curveLine) {  // unlit: the object's colour exactly, at any orientation of the line
        entry.actor->GetProperty()->SetLighting(false);
        entry.actor->GetProperty()->SetLineWidth(kCurveLineWidth);
      }
      renderer->AddActor(entry.actor);
      prepareProxy(entry, &object);  // level of detail: the proxy at load, not at the first gesture
      objects.push_back(std::move(entry));
      ++stats.objectBuilds;
    }
  }

  // True when the drawn objects are the scene's visible objects with the same point counts.
  bool sameObjects(const scenes::Scene& scene) const {
    std::size_t n = 0;
    for (const auto& object : scene.objects()) {
      if (!object.display.visible) continue;
      if (n >= objects.size() || objects[n].id != object.id ||
          objects[n].pointCount != object.mesh.points.rows() || !(objects[n].display == object.display))
        return false;
      ++n;
    }
    return n == objects.size();
  }

  void removeOverlay() {
    if (!overlay) return;
    if (vtkRenderWindow* window = overlay->GetRenderWindow()) window->RemoveRenderer(overlay);
    overlay = nullptr;
    overlayActors.clear();
    overlayHandles.clear();
    overlayPlaces.clear();
  }

  vtkRenderer* overlayRenderer() {
    vtkRenderWindow* window = renderer->GetRenderWindow();
    if (window == nullptr) return nullptr;
    if (overlay && overlay->GetRenderWindow() == window) return overlay;
    removeOverlay();
    overlay = vtkSmartPointer<vtkRenderer>::New();
    overlay->SetLayer(renderer->GetLayer() + 1);
    overlay->SetInteractive(false);
    overlay->SetActiveCamera(renderer->GetActiveCamera());
    overlay->SetViewport(renderer->GetViewport());
    if (window->GetNumberOfLayers() < overlay->GetLayer() + 1) window->SetNumberOfLayers(overlay->GetLayer() + 1);
    window->AddRenderer(overlay);
    return overlay;
  }

  // The handles of TransformerLayout, red / green / blue per axis, the hovered or dragged one
  // in the selection colour.
  static bool sameShapes(const std::optional<Transformer>& a, const std::optional<Transformer>& b) {
    if (a.has_value() != b.has_value()) return false;
    return !a || (a->size == b->size && a->uniformSize == b->uniformSize);
  }

  // The overlay actors are built once per transformer's size; a transformer that moved (it
  // follows a dragged widget every frame) moves them; the hovered or dragged handle recolours.
  void updateTransformer() {
    const bool placed = overlay && overlay->GetRenderWindow() == renderer->GetRenderWindow();
    if (!placed || !sameShapes(overlayBuiltFor, highlights.transformer)) {
      buildTransformer();
    } else if (highlights.transformer && overlayBuiltFor->frame.matrix() != highlights.transformer->frame.matrix()) {
      overlayBuiltFor = highlights.transformer;
      for (std::size_t k = 0; k < overlayActors.size(); ++k)
        placeOverlayActor(overlayActors[k], Eigen::Affine3d(highlights.transformer->frame) * overlayPlaces[k]);
    }
    const Eigen::Vector3d axisColour[3] = {{0.95, 0.25, 0.25}, {0.3, 0.9, 0.3}, {0.3, 0.5, 1.0}};
    for (std::size_t k = 0; k < overlayActors.size(); ++k) {
      const TransformerHandle handle = overlayHandles[k];
      const Eigen::Vector3d colour =
          highlights.transformerHandle == handle ? kSelected : axisColour[transformerAxis(handle)];
      overlayActors[k]->GetProperty()->SetColor(colour.x(), colour.y(), colour.z());
    }
  }

  static void placeOverlayActor(vtkActor* actor, const Eigen::Affine3d& place) {
    const Eigen::Matrix<double, 4, 4, Eigen::RowMajor> m = place.matrix();
    static_cast<vtkTransform*>(actor->GetUserTransform())->SetMatrix(m.data());
  }

  void buildTransformer() {
    if (overlay) {
      for (auto& actor : overlayActors) overlay->RemoveActor(actor);
      overlayActors.clear();
    }
    overlayHandles.clear();
    overlayPlaces.clear();
    overlayBuiltFor = highlights.transformer;
    if (!highlights.transformer) return;
    ++stats.overlayBuilds;
    vtkRenderer* target = overlayRenderer();
    if (target == nullptr) return;
    using L = TransformerLayout;
    const Transformer& t = *highlights.transformer;
    const double s = t.size;
    auto add = [&](vtkPolyData* shape, const Eigen::Affine3d& place, TransformerHandle handle) {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(shape);
      auto actor = vtkSmartPointer<vtkActor>::New();
      actor->SetMapper(mapper);
      actor->GetProperty()->SetAmbient(0.35);  // colours: updateTransformer
      actor->SetUserTransform(vtkNew<vtkTransform>());
      placeOverlayActor(actor, Eigen::Affine3d(t.frame) * place);
      target->AddActor(actor);
      overlayActors.push_back(actor);
      overlayHandles.push_back(handle);
      overlayPlaces.push_back(place);
    };
    const double length = L::moveTip - L::moveFrom;
    if (!transformerArrow) {
      vtkNew<vtkArrowSource> arrow;  // along +x, length 1
      arrow->SetShaftRadius(0.025 / length);
      arrow->SetTipRadius(0.07 / length);
      arrow->SetTipLength((L::moveTip - L::moveTo) / length);
      arrow->SetShaftResolution(12);
      arrow->SetTipResolution(20);
      arrow->Update();
      transformerArrow = arrow->GetOutput();
      vtkNew<vtkParametricTorus> torus;  // about z
      torus->SetRingRadius(L::turnRadius);
      torus->SetCrossSectionRadius(0.018);
      vtkNew<vtkParametricFunctionSource> ring;
      ring->SetParametricFunction(torus);
      ring->SetUResolution(64);
      ring->SetVResolution(6);
      ring->Update();
      transformerRing = ring->GetOutput();
      vtkNew<vtkCubeSource> cube;
      cube->SetXLength(2.0 * L::sizeHalf);
      cube->SetYLength(2.0 * L::sizeHalf);
      cube->SetZLength(2.0 * L::sizeHalf);
      cube->Update();
      transformerCube = cube->GetOutput();
    }
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d a = Eigen::Vector3d::Unit(i);
      // Rotations taking +x (arrow) and +z (ring) onto axis i.
      const Eigen::Matrix3d xToAxis = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), a).toRotationMatrix();
      const Eigen::Matrix3d zToAxis = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), a).toRotationMatrix();
      add(transformerArrow,
          Eigen::Affine3d(Eigen::Scaling(s)) * Eigen::Affine3d(xToAxis) * Eigen::Translation3d(L::moveFrom, 0, 0) *
              Eigen::Scaling(length),
          static_cast<TransformerHandle>(i));
      add(transformerRing, Eigen::Affine3d(Eigen::Scaling(s)) * Eigen::Affine3d(zToAxis),
          static_cast<TransformerHandle>(3 + i));
      add(transformerCube, Eigen::Affine3d(Eigen::Scaling(s)) * Eigen::Translation3d(L::sizeAt * a),
          static_cast<TransformerHandle>(6 + i));
    }
  }

  // The actors of one widget: a lattice's points and edges and its faces, a cell's points, an
  // affine widget's glyph at its frame.
  void addWidgetActors(const widgets::WidgetModel& model, WidgetId id) {
    ++stats.widgetActorBuilds;
    switch (model.type(id)) {
      case widgets::WidgetType::Lattice: {
        const Eigen::MatrixX3d points = model.worldControlPoints(id);
        const Eigen::Vector3d base{0.55, 0.8, 1.0};
        auto actor = addWidgetActor(latticePolyData(points, model.counts(id)), id, Role::Lattice, base);
        actor->GetProperty()->SetPointSize(9.0);
        actor->GetProperty()->SetRenderPointsAsSpheres(true);
        actor->GetProperty()->SetLighting(false);
        auto faces = addWidgetActor(latticeFacesPolyData(points, model.counts(id)), id, Role::LatticeFaces, base);
        faces->GetProperty()->SetOpacity(0.18);
        faces->GetProperty()->SetLighting(false);
        return;
      }
      case widgets::WidgetType::Cell: {
        auto actor = addWidgetActor(pointsPolyData(model.cellWorldPoints(id)), id, Role::Cell, {1.0, 0.65, 0.2});
        actor->GetProperty()->SetPointSize(14.0);
        actor->GetProperty()->SetRenderPointsAsSpheres(true);
        actor->GetProperty()->SetLighting(false);
        return;
      }
      case widgets::WidgetType::Affine: {
        const widgets::WidgetFrame frame = model.affineFrame(id);
        vtkNew<vtkTransform> transform;
        const AffineKind kind = model.affineKind(id);
        Eigen::Matrix4d m = frame.frame.matrix();
        m.topLeftCorner<3, 3>() *= frame.size;
        // A free rotate widget (a handle) turns its glyph by its variation about its axis, so a
        // crank follows the pointer; an attached one already turns with its cell.
        if (kind == AffineKind::Rotate && !model.attachedCell(id))
          m.topLeftCorner<3, 3>() *= Eigen::AngleAxisd(model.variation(id), Eigen::Vector3d::UnitZ()).toRotationMatrix();
        Eigen::Matrix<double, 4, 4, Eigen::RowMajor> rowMajor = m;
        transform->SetMatrix(rowMajor.data());
        auto actor = addWidgetActor(cachedGlyph(model.glyph(id), kind), id, Role::Glyph, kindColour(kind));
        actor->SetUserTransform(transform);
        actor->GetProperty()->SetSpecular(0.4);
        actor->GetProperty()->SetSpecularPower(40);
        return;
      }
    }
  }

  void buildWidgets(const widgets::WidgetModel& model) {
    for (auto& actor : widgetActors) renderer->RemoveActor(actor);
    widgetActors.clear();
    widgets.clear();
    widgetInstance = model.instance();
    widgetRevision = model.revision();
    ++stats.widgetBuilds;
    for (widgets::WidgetType type : {widgets::WidgetType::Lattice, widgets::WidgetType::Cell, widgets::WidgetType::Affine})
      for (WidgetId id : model.widgets(type)) addWidgetActors(model, id);
    // The picked-point marker: one point at the origin, placed by the actor's position.
    pointMarker = addWidgetActor(pointsPolyData(Eigen::RowVector3d::Zero()), kSelected);
    pointMarker->GetProperty()->SetPointSize(18.0);
    pointMarker->GetProperty()->SetRenderPointsAsSpheres(true);
    pointMarker->GetProperty()->SetLighting(false);
    selectedPoints = addWidgetActor(pointsPolyData(Eigen::MatrixX3d(0, 3)), kSelected);
    selectedPoints->GetProperty()->SetPointSize(17.0);  // over a cell's points (14)
    selectedPoints->GetProperty()->SetRenderPointsAsSpheres(true);
    selectedPoints->GetProperty()->SetLighting(false);
    selectedShown.clear();
    selectedRevision = 0;
  }

  // The actors of the widgets a change concerns (widgets::widgetsToRedraw) anew, and those of the
  // widgets the model no longer has gone; every other actor stays as it is.
  void redrawWidgets(const widgets::WidgetModel& model, const std::vector<WidgetId>& redraw) {
    widgetRevision = model.revision();
    ++stats.widgetBuilds;
    auto stale = [&](WidgetId id) { return !model.contains(id) || std::binary_search(redraw.begin(), redraw.end(), id); };
    std::erase_if(widgets, [&](const WidgetActor& w) {
      if (!stale(w.id)) return false;
      renderer->RemoveActor(w.actor);
      std::erase(widgetActors, w.actor);
      return true;
    });
    for (WidgetId id : redraw) addWidgetActors(model, id);
  }

  // Widget actors from the model when it changed; highlights always (no geometry).
  void updateWidgets(const widgets::WidgetModel& model) {
    updateTransformer();
    if (!pointMarker || widgetInstance != model.instance()) {
      buildWidgets(model);
    } else if (widgetRevision != model.revision()) {
      redrawWidgets(model, widgets::widgetsToRedraw(model, model.changesSince(widgetRevision)));
    }
    applyHighlights(model);
    updatePins();
    updateFoldTintAndRadius(model);
  }
};

SceneView::SceneView(vtkRenderer* renderer) : impl_(std::make_unique<Impl>()) { impl_->renderer = renderer; }

SceneView::~SceneView() {
  impl_->removeOverlay();
  impl_->clearObjects();
  for (auto& actor : impl_->widgetActors) impl_->renderer->RemoveActor(actor);
  if (impl_->pins) impl_->renderer->RemoveActor(impl_->pins);
}

void SceneView::show(const scenes::Scene& scene, const scenes::SceneDeformer& deformed) {
  impl_->buildObjects(scene, deformed);
  impl_->buildTransformer();
  impl_->buildWidgets(scene.widgets);
  impl_->updateWidgets(scene.widgets);
  impl_->renderer->SetBackground(scene.background().x(), scene.background().y(), scene.background().z());
  applyCamera(scene.camera());
}

void SceneView::refresh(const scenes::Scene& scene, const scenes::SceneDeformer& deformed) {
  if (impl_->sameObjects(scene)) {
    if (scene.structureRevision() != impl_->namesSeen) {  // a rename: the labels only
      auto entry = impl_->objects.begin();
      for (const auto& object : scene.objects())
        if (object.display.visible) (entry++)->name = object.name;
    }
    for (auto& entry : impl_->objects) {
      if (impl_->drawProxy(entry, scene, deformed)) continue;  // level of detail: the proxy only
      // Only objects whose deformed points moved: their point array, normals and comb, in place.
      const std::uint64_t revision = deformed.revision(entry.id);
      if (revision == entry.pointsRevision) continue;
      entry.pointsRevision = revision;
      auto* normals = vtkFloatArray::SafeDownCast(entry.polyData->GetPointData()->GetNormals());
      // A later step of a one-control-point drag: points and normals follow the motion in one pass.
      const bool followed = normals && entry.gestureNormals.follow(deformed, entry.id, entry.polyData->GetPoints(), normals);
      if (!normals) object_arrays::setFloatPoints(entry.polyData->GetPoints(), deformed.points(entry.id), entry.origin);
      ++impl_->stats.pointUpdates;
      if (normals) {
        ++impl_->stats.normalUpdates;
        // Otherwise the points and normals together (the first step of a drag from the normals
        // drawn last: gesture_normals.h).
        if (followed)
          ++impl_->stats.followedNormals;
        else if (entry.gestureNormals.update(deformed, entry.id, scene.findObject(entry.id)->mesh.triangles,
                                             entry.vertexFaces, deformed.points(entry.id), entry.origin,
                                             entry.faceNormals, entry.polyData->GetPoints(), normals))
          ++impl_->stats.normalsFromBase;
        if (auto* tcoords = vtkFloatArray::SafeDownCast(entry.polyData->GetPointData()->GetTCoords()))
          updateZebraCoordinates(tcoords, normals, entry.display.zebraDirection, entry.display.zebraStripes);
      }
      if (entry.comb)
        vtkPolyDataMapper::SafeDownCast(entry.comb->GetMapper())
            ->SetInputData(combPolyData(entry.chains, deformed.points(entry.id), entry.combFactor));
      entry.polyData->Modified();
    }
  } else {
    impl_->buildObjects(scene, deformed);
  }
  impl_->namesSeen = scene.structureRevision();
  impl_->updateWidgets(scene.widgets);
  impl_->renderer->SetBackground(scene.background().x(), scene.background().y(), scene.background().z());
  // The clipping range from our own bounds: VTK's would visit every cell of a large mesh
  // (~40 ms per frame at 1M vertices).
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  auto grow = [&](const Eigen::MatrixX3d& points) {
    if (points.rows() == 0) return;
    lo = lo.cwiseMin(points.colwise().minCoeff().transpose());
    hi = hi.cwiseMax(points.colwise().maxCoeff().transpose());
  };
  // Deformed points lie in their lattices' control hull (FFD's convex hull property) or stay
  // near their own points (outside policies): the own box and the lattices bound the scene
  // without visiting a million points per frame.
  for (const auto& entry : impl_->objects) {
    lo = lo.cwiseMin(entry.restLo);
    hi = hi.cwiseMax(entry.restHi);
  }
  for (widgets::WidgetId lattice : scene.widgets.widgets(widgets::WidgetType::Lattice))
    grow(scene.widgets.worldControlPoints(lattice));
  if (lo.x() <= hi.x()) {
    const Eigen::Vector3d margin = Eigen::Vector3d::Constant(0.5 * (hi - lo).norm() + 1e-6);  // glyphs stick out
    lo -= margin;
    hi += margin;
    double bounds[6] = {lo.x(), hi.x(), lo.y(), hi.y(), lo.z(), hi.z()};
    impl_->renderer->ResetCameraClippingRange(bounds);
  } else {
    impl_->renderer->ResetCameraClippingRange();
  }
}

void SceneView::setHighlights(const ViewHighlights& highlights) { impl_->highlights = highlights; }

Eigen::MatrixX3f SceneView::objectNormals(const std::string& object) const {
  for (const auto& entry : impl_->objects) {
    if (entry.name != object) continue;
    auto* normals = vtkFloatArray::SafeDownCast(entry.polyData->GetPointData()->GetNormals());
    if (!normals) break;
    Eigen::MatrixX3f out(normals->GetNumberOfTuples(), 3);
    for (Eigen::Index i = 0; i < out.rows(); ++i)
      for (int c = 0; c < 3; ++c) out(i, c) = normals->GetPointer(0)[3 * i + c];
    return out;
  }
  return {};
}

const SceneViewStats& SceneView::stats() const { return impl_->stats; }

SceneViewMemory SceneView::objectMemory() const {
  SceneViewMemory memory;
  for (const auto& entry : impl_->objects) {
    memory.vertices += entry.pointCount;
    memory.bytes += std::size_t(entry.polyData->GetActualMemorySize()) * 1024;  // VTK reports KiB
    memory.bytes += sizeof(int) * (entry.vertexFaces.start.capacity() + entry.vertexFaces.faces.capacity());
    memory.bytes += sizeof(Eigen::Vector3f) * entry.faceNormals.capacity();
    memory.bytes += entry.gestureNormals.memoryBytes();
    if (entry.proxy) memory.bytes += entry.proxy->memoryBytes();
  }
  return memory;
}

// --- Level of detail (LevelOfDetail, object_proxy.h).
void SceneView::setLevelOfDetail(const LevelOfDetail& lod) { impl_->lod = lod; }
const LevelOfDetail& SceneView::levelOfDetail() const { return impl_->lod; }
void SceneView::setMoving(bool moving) { impl_->moving = moving; }
scenes::EvaluationRequest SceneView::evaluationRequest(const scenes::Scene& scene, const scenes::SceneDeformer& deformed) {
  scenes::EvaluationRequest request;  // during a gesture, the objects drawn as proxies at their vertices only
  if (!deformed.inGesture() || !impl_->sameObjects(scene)) return request;  // refresh() builds actors from full points
  for (auto& entry : impl_->objects) {
    impl_->prepareProxy(entry, scene.findObject(entry.id));
    if (entry.proxy) request.subsets[entry.id] = entry.proxy->vertices();
  }
  return request;
}
bool SceneView::showsProxy(const std::string& object) const {
  for (const auto& entry : impl_->objects)
    if (entry.name == object) return entry.proxy && entry.proxy->shown();
  return false;
}
Eigen::MatrixX3d SceneView::objectPoints(const std::string& object) const {
  for (const auto& entry : impl_->objects)
    if (entry.name == object) return object_arrays::worldPoints(entry.polyData->GetPoints(), entry.origin);
  return {};
}
// --- end of level of detail

void SceneView::applyCamera(const scenes::Camera& camera) {
  vtkCamera* c = impl_->renderer->GetActiveCamera();
  c->SetPosition(camera.position.data());
  c->SetFocalPoint(camera.focalPoint.data());
  c->SetViewUp(camera.viewUp.data());
  c->SetViewAngle(camera.viewAngleDegrees);
  c->OrthogonalizeViewUp();
  impl_->renderer->ResetCameraClippingRange();
}

scenes::Camera SceneView::camera() const {
  vtkCamera* c = impl_->renderer->GetActiveCamera();
  scenes::Camera camera;
  c->GetPosition(camera.position.data());
  c->GetFocalPoint(camera.focalPoint.data());
  c->GetViewUp(camera.viewUp.data());
  camera.viewAngleDegrees = c->GetViewAngle();
  return camera;
}

ViewCamera SceneView::viewCamera() const {
  vtkCamera* c = impl_->renderer->GetActiveCamera();
  return ViewCamera{camera(), c->GetParallelProjection() != 0, c->GetParallelScale()};
}

void SceneView::setViewCamera(const ViewCamera& view) {
  vtkCamera* c = impl_->renderer->GetActiveCamera();
  c->SetParallelProjection(view.parallel);
  c->SetParallelScale(view.parallelScale);
  applyCamera(view.camera);
}

widgets::Ray SceneView::rayAt(double x, double y) const {
  vtkRenderer* r = impl_->renderer;
  auto world = [&](double z) {
    r->SetDisplayPoint(x, y, z);
    r->DisplayToWorld();
    double p[4];
    r->GetWorldPoint(p);
    return Eigen::Vector3d(p[0] / p[3], p[1] / p[3], p[2] / p[3]);
  };
  widgets::Ray ray;
  ray.origin = world(0.0);
  ray.direction = (world(1.0) - ray.origin).normalized();
  return ray;
}

Eigen::Vector2d SceneView::displayPoint(const Eigen::Vector3d& p) const {
  vtkRenderer* r = impl_->renderer;
  r->SetWorldPoint(p.x(), p.y(), p.z(), 1.0);
  r->WorldToDisplay();
  double d[3];
  r->GetDisplayPoint(d);
  return {d[0], d[1]};
}

double SceneView::pixelSize() const {
  vtkCamera* c = impl_->renderer->GetActiveCamera();
  const int* size = impl_->renderer->GetSize();
  const double height = std::max(1, size[1]);
  if (c->GetParallelProjection()) return 2.0 * c->GetParallelScale() / height;
  return 2.0 * c->GetDistance() * std::tan(c->GetViewAngle() * std::numbers::pi / 360.0) / height;
}

}  // namespace ffdkit::app
