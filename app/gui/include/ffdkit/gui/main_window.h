#pragma once

#include <filesystem>
#include <functional>
#include <memory>

#include <QMainWindow>

#include "ffdkit/scenes/command_stack.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/widgets/affine_kind.h"
#include "ffdkit/widgets/widget_id.h"

class QAction;
class QDockWidget;
class QMenu;
class QTreeWidget;

namespace ffdkit::app {

class VtkViewWidget;
class InteractionController;
class EditController;
class SceneView;

/// The application window: the 3D view, an outliner of objects / widget tree / bindings, a
/// property panel for the selection, menus, toolbar, status bar (last deform time) and undo.
/// Every model change goes through the InteractionController and so the command stack.
/// Actions have object names ("actionNewLattice", "actionBind", ...) for tests and scripting.
class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  /// Loads a scene file (or a sample-scene folder) and shows it.
  /// @throws scenes::SceneFileError if the file cannot be read; the current scene stays.
  void openScene(const std::filesystem::path& path);
  /// Writes the scene (inline widgets). @throws scenes::SceneFileError.
  void saveScene(const std::filesystem::path& path);
  /// Replaces the widget model by a widget file's (undoable). @throws scenes::WidgetFileError.
  void openWidgetFile(const std::filesystem::path& path);
  /// @throws scenes::WidgetFileError.
  void saveWidgetFile(const std::filesystem::path& path);
  /// Adds a mesh file as an object (undoable). @throws scenes::MeshIoError.
  void importMesh(const std::filesystem::path& path);
  /// Writes the selected (else the first) object at its deformed points. @throws scenes::MeshIoError.
  void exportMesh(const std::filesystem::path& path);
  /// Attaches `lattice` to `object` (undoable). An object of at least backgroundEmbedPoints()
  /// points is embedded in a worker thread first, behind a progress dialog (the fraction of the
  /// points embedded) whose Cancel stops the embedding at its next chunk and leaves the scene as
  /// it was. @return false if cancelled. @throws what the model throws.
  bool attachLattice(widgets::WidgetId lattice, const std::string& object);
  static void setBackgroundEmbedPoints(long points);
  static long backgroundEmbedPoints();

  /// Selects the widget named `name` (as a click would: outliner, property panel, and the
  /// transformer of an affine or lattice widget). @throws widgets::WidgetError naming the known widgets.
  void selectWidget(const std::string& name);

  /// Opens whatever `path` is: scene, widget file (by its "format"), or mesh.
  void openAny(const std::filesystem::path& path);

  /// File > New Scene: an empty, untitled scene (asks nothing; the action asks first).
  void newScene();
  /// True when the document differs from its file (the title shows `*`).
  bool isModified() const;
  /// The document's file; empty for a scene never saved.
  std::filesystem::path documentPath() const;
  /// The status line's whole message (the line shows what fits, its tooltip all of it; it is
  /// cleared when it stops being true).
  QString statusMessage() const;
  /// After a crash: offers to restore the newest recovery file another ffdkit process left
  /// (Restore / Discard) and removes those files. main() calls it at start.
  /// @return true if a document was restored.
  bool offerRecovery();

  /// Whether closing saves the dock layout and window geometry for the next session (on by
  /// default; off for a screenshot run, which hides the docks).
  void setLayoutRemembered(bool remembered);

  /// Shows `scene` (replacing the current one; clears undo).
  void setScene(scenes::Scene scene);
  const scenes::Scene& scene() const;
  /// The deformer, with every change evaluated: the window evaluates once per event-loop tick,
  /// at its next frame; reading it here evaluates what waits first.
  const scenes::SceneDeformer& deformer() const;
  /// How many frames evaluated the scene (SceneDeformer::evaluate found a change): one per
  /// event-loop tick that changed something, however many events the tick held.
  std::uint64_t evaluations() const;
  scenes::CommandStack& commands() const;
  InteractionController& controller() const;
  /// A lattice's edit mode and group transforms (Tab; edit_mode.h).
  EditController& editController() const;
  /// The view, brought up to date first (as the next frame draws it).
  SceneView& sceneView() const;
  QTreeWidget* outliner() const;

  VtkViewWidget* view() const;

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;
  void closeEvent(QCloseEvent* event) override;

 private:
  /// The menus, their actions, the toolbar, the edit mode's input and the timeline dock
  /// (main_window_menus.cpp); `refreshPanel` shows the selection in the property panel.
  void createMenus(QDockWidget* outlinerDock, QDockWidget* propertiesDock, const std::function<void()>& refreshPanel);
  void createFileMenu();
  void createEditMenu();
  /// The thesis operations (Kuriyama 1996, sec. 6.4): lattices, affine widgets, bindings,
  /// attachment, direct manipulation, primitives.
  QMenu* createWidgetsMenu();
  QMenu* createViewMenu(QDockWidget* outlinerDock, QDockWidget* propertiesDock);
  /// The operations toolbar, the edit mode's actions on it, and View > Toolbar Text Under Icons.
  void createOperationsToolbar(QMenu* widgetsMenu, QMenu* viewMenu);
  /// A menu action named `name` whose slot's exceptions are shown in the status line.
  QAction* addMenuAction(QMenu* menu, const QString& text, const char* name, std::function<void()> slot);
  /// A menu action that asks for a file (to save or to open) and applies `apply` to it; a
  /// failure is shown in a message box.
  QAction* addFileAction(QMenu* menu, const QString& text, const char* name, bool save, const QString& filter,
                         std::function<void(const std::filesystem::path&)> apply);
  /// Widgets > New Lattice: its dialog, then the lattice.
  void newLatticeInteractively();
  /// Widgets > Add Primitive: its dialog, then the object.
  void addPrimitiveInteractively();
  /// Widgets > Add Translate/Rotate/Scale Widget at the picked lattice point or selected cell.
  void addAffineWidget(widgets::AffineKind kind);
  /// Asks Save / Discard / Cancel when the document has unsaved changes.
  /// @return false if the user cancelled (or a save failed): keep everything.
  bool maybeSave();
  /// Save (to the document's file) or Save As (asks where). @return false if not saved.
  bool saveInteractively(bool askForPath);
  /// The document's file: the title, the recent files.
  void setDocumentPath(const std::filesystem::path& path);
  void rebuildRecentMenu();
  void startAutosaveTimer();
  void deleteSelectedObjects();
  void renameSelection();

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ffdkit::app
