// MainWindow's state shared by its source files: main_window.cpp (the window, the model -> view
// wiring, the view's events), main_window_menus.cpp (the menus, actions and toolbar),
// main_window_document.cpp (the document's files: open, save, the unsaved-changes prompt, recent
// files, recovery) and main_window_embed.cpp (a large attach's background embedding).
#pragma once

#include <algorithm>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <QAction>
#include <QLabel>
#include <QMenu>
#include <QPoint>
#include <QString>
#include <QTimer>

#include "ffdkit/interaction/edit_controller.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/gui/main_window.h"
#include "ffdkit/gui/recovery_file.h"
#include "ffdkit/render/scene_view.h"
#include "ffdkit/viewhost/vtk_view_widget.h"
#include "ffdkit/scenes/command_stack.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "edit_mode.h"
#include "outliner.h"
#include "property_panel.h"
#include "status_line.h"
#include "timeline_widget.h"
#include "view_navigation.h"

namespace ffdkit::app {
namespace window_detail {

constexpr int kMaxRecent = 8;
constexpr int kDefaultAutosaveMinutes = 2;
constexpr double kPickPixels = 7.0;  // pick tolerance on screen

inline QString qs(const std::string& s) { return QString::fromStdString(s); }

/// A mesh file by its extension (.obj .ply .stl .vtp .vtk .gltf .glb .xyz, any case).
bool isMeshFile(const std::filesystem::path& path);
/// A widget file says "format": "ffdkit-widgets" near its top; a scene says "ffdkit-scene".
bool isWidgetFile(const std::filesystem::path& path);
/// What openAny does with `path`: a scene replaces the document (so first ask to save it).
bool opensAsScene(const std::filesystem::path& path);

}  // namespace window_detail

struct MainWindow::Impl {
  VtkViewWidget* view = nullptr;
  std::unique_ptr<SceneView> sceneView;
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  std::unique_ptr<InteractionController> controller;
  std::unique_ptr<EditController> edit;  ///< a lattice's edit mode, group transforms
  EditModeInput* editInput = nullptr;    ///< their actions, keys and pointer (edit_mode.h)
  Outliner* outliner = nullptr;
  PropertyPanel* properties = nullptr;
  TimelineWidget* timeline = nullptr;  ///< under the view (timeline_widget.h)
  QLabel* deformStatus = nullptr;
  StatusLine* status = nullptr;
  QMenu* recentMenu = nullptr;
  RecoveryFile recovery;
  QTimer autosaveTimer;
  /// A document restored from a recovery file differs from its file with nothing to undo.
  bool restoredUnsaved = false;
  bool rememberLayout = true;  ///< closeEvent saves the layout (not after a screenshot run hid the docks)
  /// The command-stack position last autosaved (an autosave per change, not per timer tick).
  std::optional<std::size_t> autosavedAt;
  QAction* undo = nullptr;
  QAction* redo = nullptr;
  QAction* zebra = nullptr;
  QAction* comb = nullptr;
  std::filesystem::path scenePath;
  std::vector<scenes::ObjectId> selectedObjects;  ///< by id: a rename keeps the selection
  /// The names of the selected objects that exist, in selection order.
  std::vector<std::string> selectedObjectNames() const {
    std::vector<std::string> names;
    for (const scenes::ObjectId id : selectedObjects)
      if (const scenes::SceneObject* object = scene.findObject(id)) names.push_back(object->name);
    return names;
  }
  std::optional<widgets::BindingId> selectedBinding;
  /// Drops the selected binding when the model no longer has it (an undo or a widget file took
  /// it away), before anything shows the selection: the panel would ask the model for it.
  void forgetRemovedBinding() {
    if (!selectedBinding) return;
    const auto all = scene.widgets.bindings();
    if (std::find(all.begin(), all.end(), *selectedBinding) == all.end()) selectedBinding.reset();
  }
  // Pointer state of the 3D view.
  QPoint pressAt;
  bool pressOnEmpty = false;
  QAction* directManipulation = nullptr;  ///< checked: a drag on an object moves its point
  ViewNavigation* navigation = nullptr;   ///< orbit, framing, axis views (owned by the window)
  bool showingScene = false;
  /// A change waits for the next frame: drawFrame() evaluates the scene once and redraws.
  bool frameDue = false;
  /// Frames that evaluated the scene (MainWindow::evaluations).
  std::uint64_t evaluations = 0;
  /// What a frame draws of the document and the controllers (the view's own looks and camera ask
  /// for their frames themselves): the scene and its widget model by revision, whether a gesture
  /// runs (its objects drawn as proxies) and the highlights.
  struct FrameInputs {
    std::uint64_t sceneRevision = 0;
    std::uint64_t widgetsInstance = 0;
    std::uint64_t widgetsRevision = 0;
    bool gesture = false;
    ViewHighlights highlights;
    friend bool operator==(const FrameInputs&, const FrameInputs&) = default;
  };
  FrameInputs frameInputs() const {
    return {scene.revision(), scene.widgets.instance(), scene.widgets.revision(), deformer.inGesture(),
            edit->highlights(controller->highlights())};
  }
  /// The inputs of the frame a change asked for last (none: the next change asks for one).
  std::optional<FrameInputs> askedInputs;
  /// A change of the model or of a controller's state (onChanged, requestEvaluation) asks for a
  /// frame, which evaluates the scene and draws it (drawFrame), unless it left everything a
  /// frame draws as the frame asked for last: a frame of the timeline that no key moves anything
  /// at, a selection made again, a hover over what was hovered. The view shows that frame already.
  void requestFrame() {
    if (!showingScene) return;
    FrameInputs inputs = frameInputs();
    if (askedInputs == inputs) return;
    askedInputs = std::move(inputs);
    frameDue = true;
    view->requestRender();
  }
  /// Brings the deformer and the view up to date when a change waits (frameDue): the scene
  /// evaluated once for every event since the last frame, then highlights, actors and the
  /// deform status refreshed. The view calls it before each repaint (VtkViewWidget::aboutToRender);
  /// readers of deformed points call it first (deformed()).
  void drawFrame();
  /// The deformer with every change evaluated (drawFrame first) and every object in full (a
  /// gesture's frame may have evaluated a proxied object at its proxy's points only): what
  /// exports, bounds and scripts read.
  const scenes::SceneDeformer& deformed() {
    drawFrame();
    try {
      deformer.evaluate(scene);  // nothing to do unless a frame left an object at a subset
    } catch (const std::exception& e) {
      sayError(e.what());
    }
    return deformer;
  }

  bool modified() const { return commands.isDirty() || restoredUnsaved; }

  // A refusal or error as the user reads it: widgets by name, the whole text (on one line, whole
  // in its tooltip).
  void sayError(const std::string& what) { status->say(window_detail::qs(readableMessage(scene.widgets, what))); }

  // The open document to the recovery file when it has unsaved changes; none when it has not.
  void autosave() {
    if (!modified()) {
      recovery.remove();
      autosavedAt.reset();
      return;
    }
    if (autosavedAt == commands.position() && !restoredUnsaved) return;
    try {
      recovery.write(scene, sceneView->camera(), scenePath);
      autosavedAt = commands.position();
    } catch (const std::exception& e) {
      status->say(QObject::tr("Autosave failed: %1").arg(window_detail::qs(e.what())));
    }
  }

  // The objects the View menu's looks apply to: the selected ones, else all.
  std::vector<std::string> lookTargets() const {
    if (std::vector<std::string> selected = selectedObjectNames(); !selected.empty()) return selected;
    std::vector<std::string> names;
    for (const auto& o : scene.objects()) names.push_back(o.name);
    return names;
  }

  // Checks the look actions when every target surface is zebra / every target curve has a comb.
  void syncLookActions() {
    if (!zebra) return;
    bool anySurface = false, allZebra = true, anyCurve = false, allComb = true;
    for (const auto& name : lookTargets()) {
      const scenes::SceneObject* o = scene.findObject(name);
      if (!o) continue;
      if (o->mesh.triangles.rows() > 0) {
        anySurface = true;
        allZebra = allZebra && o->display.surfaceStyle == scenes::SurfaceStyle::Zebra;
      } else if (o->mesh.segments.rows() > 0) {
        anyCurve = true;
        allComb = allComb && o->display.curvatureComb;
      }
    }
    zebra->setChecked(anySurface && allZebra);
    comb->setChecked(anyCurve && allComb);
  }

  // Changes the look of the target objects through the controller (one undoable command).
  void changeLook(const std::string& description, const std::function<void(const scenes::SceneObject&,
                                                                             scenes::DisplaySettings&)>& change) {
    const std::vector<std::string> names = lookTargets();
    std::vector<scenes::DisplaySettings> looks;
    for (const auto& name : names) {
      const scenes::SceneObject& o = *scene.findObject(name);
      looks.push_back(o.display);
      change(o, looks.back());
    }
    controller->setDisplay(names, looks, description);
    syncLookActions();
  }

  widgets::Ray rayAt(const QPoint& p) const {
    const double ratio = view->devicePixelRatioF();
    const double h = view->height() * ratio;
    return sceneView->rayAt(p.x() * ratio, h - p.y() * ratio - 1.0);
  }
  double tolerance() const { return window_detail::kPickPixels * view->devicePixelRatioF() * sceneView->pixelSize(); }

  std::vector<OutlinerEntry> entries() const {
    std::vector<OutlinerEntry> out;
    for (const scenes::ObjectId o : selectedObjects)
      if (scene.findObject(o) != nullptr) out.push_back({OutlinerEntry::Kind::Object, o, {}, {}});
    for (widgets::WidgetId w : controller->selection()) out.push_back({OutlinerEntry::Kind::Widget, {}, w, {}});
    if (selectedBinding) out.push_back({OutlinerEntry::Kind::Binding, {}, {}, *selectedBinding});
    return out;
  }
};

}  // namespace ffdkit::app
