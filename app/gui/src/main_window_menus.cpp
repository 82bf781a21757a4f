// MainWindow, its menus and actions: File, Edit, Widgets (the thesis operations), View and
// Help, the operations toolbar (icons: toolbar_icons.h), the edit mode's input and the
// timeline dock, one function per menu. The window, the
// view's events and the model -> view wiring are in main_window.cpp; the document's files in
// main_window_document.cpp.
#include <algorithm>
#include <numbers>

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDockWidget>
#include <QFileDialog>
#include <QFormLayout>
#include <QMenuBar>
#include <QMessageBox>
#include <QSettings>
#include <QSpinBox>
#include <QToolBar>

#include "ffdkit/interaction/scene_bounds.h"
#include "cad_import.h"
#include "gltf_export_dialog.h"
#include "import_options.h"
#include "keyboard_shortcuts.h"
#include "main_window_impl.h"
#include "read_preferences.h"
#include "toolbar_icons.h"

namespace ffdkit::app {

/// QSettings key of View > Simplify While Moving (bool, default true).
constexpr const char* kSimplifyWhileMovingKey = "view/simplifyWhileMoving";

using namespace window_detail;

namespace {
/// Adds OK / Cancel to a form dialog and runs it. @return true if accepted.
bool acceptedForm(QDialog& dialog, QFormLayout* form) {
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
  QObject::connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
  QObject::connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
  form->addRow(buttons);
  return dialog.exec() == QDialog::Accepted;
}
}  // namespace

void MainWindow::createMenus(QDockWidget* outlinerDock, QDockWidget* propertiesDock,
                             const std::function<void()>& refreshPanel) {
  createFileMenu();
  createEditMenu();
  QMenu* widgetsMenu = createWidgetsMenu();
  QMenu* viewMenu = createViewMenu(outlinerDock, propertiesDock);
  createOperationsToolbar(widgetsMenu, viewMenu);

  Impl& d = *impl_;
  d.timeline = addTimelineDock(this, d.scene, d.commands, *d.controller);
  connect(d.timeline, &TimelineWidget::error, this, [this](const QString& m) { impl_->sayError(m.toStdString()); });
  connect(d.timeline, &TimelineWidget::frameChanged, this, refreshPanel);
  // Level of detail (SceneView::setMoving): playback draws large surfaces as their proxies, a pause
  // draws them in full at once. After the timeline's own handler: playing() is the new state.
  connect(findChild<QAction*>("actionPlayPause"), &QAction::triggered, this, [this] {
    Impl& s = *impl_;
    s.sceneView->setMoving(s.timeline->timeline().playing());
    if (!s.showingScene) return;
    s.sceneView->refresh(s.scene, s.deformer);
    s.view->requestRender();
  });
  QMenu* help = menuBar()->addMenu(tr("&Help"));
  addMenuAction(help, tr("&Keyboard Shortcuts"), "actionKeyboardShortcuts", [this] { showKeyboardShortcuts(this); });
  applyKeyboardShortcuts(this);  // every action's keys (and its tooltip's) from the one table (keyboard_shortcuts.h)
  applyActionIcons(this);        // the toolbar's icons (toolbar_icons.h)
}

QAction* MainWindow::addMenuAction(QMenu* menu, const QString& text, const char* name, std::function<void()> slot) {
  QAction* a = menu->addAction(text);
  a->setObjectName(name);
  connect(a, &QAction::triggered, this, [this, slot = std::move(slot)] {
    try {
      slot();
    } catch (const std::exception& e) {
      impl_->sayError(e.what());
      QApplication::beep();
    }
  });
  return a;
}

QAction* MainWindow::addFileAction(QMenu* menu, const QString& text, const char* name, bool save, const QString& filter,
                                   std::function<void(const std::filesystem::path&)> apply) {
  return addMenuAction(menu, text, name, [this, text, save, filter, apply = std::move(apply)] {
    const QString path = save ? QFileDialog::getSaveFileName(this, text, QString(), filter)
                              : QFileDialog::getOpenFileName(this, text, QString(), filter);
    if (path.isEmpty()) return;
    try {
      apply(std::filesystem::path(path.toStdString()));
    } catch (const std::exception& e) {
      QMessageBox::critical(this, text, qs(readErrorText(e.what())));
    }
  });
}

void MainWindow::createFileMenu() {
  Impl& d = *impl_;
  const QString sceneFilter = tr("ffdkit scenes (*.json);;All files (*)");
  const QString widgetFilter = tr("ffdkit widget files (*.json);;All files (*)");
  const QString meshFilter = tr("Meshes and CAD parts (*.obj *.ply *.stl *.vtp *.vtk *.gltf *.glb *.xyz *.npy *.step *.stp "
                                "*.iges *.igs);;All files (*)");
  const QString cadFilter = tr("STEP (*.step *.stp);;IGES (*.iges *.igs)");
  registerCadObjectReader();  // STEP and IGES objects (cad_import.h), in scenes and imports alike

  QMenu* file = menuBar()->addMenu(tr("&File"));
  addMenuAction(file, tr("&New Scene"), "actionNewScene", [this] {
    if (maybeSave()) newScene();
  });
  addMenuAction(file, tr("&Open Scene..."), "actionOpenScene", [this, sceneFilter] {
    if (!maybeSave()) return;
    const QString path = QFileDialog::getOpenFileName(this, tr("Open Scene"), QString(), sceneFilter);
    if (path.isEmpty()) return;
    try {
      openScene(path.toStdString());
    } catch (const std::exception& e) {
      QMessageBox::critical(this, tr("Open Scene"), qs(readErrorText(e.what())));
    }
  });
  d.recentMenu = file->addMenu(tr("Open &Recent"));
  addMenuAction(file, tr("&Save Scene"), "actionSaveScene", [this] { saveInteractively(false); });
  addMenuAction(file, tr("Save Scene &As..."), "actionSaveSceneAs", [this] { saveInteractively(true); });
  file->addSeparator();
  addFileAction(file, tr("Open &Widget File..."), "actionOpenWidgetFile", false, widgetFilter,
                [this](const std::filesystem::path& p) { openWidgetFile(p); });
  addFileAction(file, tr("Save W&idget File..."), "actionSaveWidgetFile", true, widgetFilter,
                [this](const std::filesystem::path& p) { saveWidgetFile(p); });
  file->addSeparator();
  addFileAction(file, tr("&Import Mesh..."), "actionImportMesh", false, meshFilter,
                [this](const std::filesystem::path& p) { importMesh(p); });
  addImportUpAxisMenu(file);
  // A scene's volume mesh is exported in its own format (.msh, .su2, ...; docs/volume-meshes.md).
  const QString exportFilter = tr("Meshes and volume meshes (*.obj *.ply *.stl *.vtp *.vtk *.xyz *.npy *.msh *.su2 *.unv "
                                  "*.nodes *.k *.key *.mdpa *.cgns);;All files (*)");
  addFileAction(file, tr("&Export Deformed Mesh..."), "actionExportMesh", true, exportFilter,
                [this](const std::filesystem::path& p) { exportMesh(p); });
  QAction* exportCad = addFileAction(file, tr("Export Deformed &CAD Model..."), "actionExportCad", true, cadFilter,
                                     [this](const std::filesystem::path& p) {
                                       const std::filesystem::path base =
                                           impl_->scenePath.empty() ? std::filesystem::path{} : impl_->scenePath.parent_path();
                                       impl_->status->say(exportDeformedCad(impl_->scene, impl_->selectedObjectNames(), base, p), 5000);
                                     });
  if (!hasCadModule()) exportCad->setToolTip(tr("This build has no CAD module (OpenCASCADE): it writes no STEP or IGES"));
  addCadTessellationAction(file, this);
  addMenuAction(file, tr("Export &glTF..."), "actionExportGltf", [this] { exportGltfInteractively(this, impl_->scene); });
  file->addSeparator();
  addReadPreferenceActions(file, this);  // the confinement opt-out and the read limits
  file->addSeparator();
  addMenuAction(file, tr("&Quit"), "actionQuit", [this] { close(); });
}

void MainWindow::createEditMenu() {
  Impl& d = *impl_;
  QMenu* edit = menuBar()->addMenu(tr("&Edit"));
  // Undo and redo first abandon a transform or drag in progress (the model back to before it,
  // nothing pushed): its cancel puts back the state it began from, which after an undo or redo
  // would be a state no step of the stack stands for.
  const auto endTransform = [this] {
    impl_->edit->cancel();
    impl_->controller->cancel();
  };
  d.undo = addMenuAction(edit, tr("&Undo"), "actionUndo", [this, endTransform] {
    endTransform();
    impl_->commands.undo();
  });
  d.redo = addMenuAction(edit, tr("&Redo"), "actionRedo", [this, endTransform] {
    endTransform();
    impl_->commands.redo();
  });
  d.undo->setEnabled(false);
  d.redo->setEnabled(false);
  edit->addSeparator();
  addMenuAction(edit, tr("&Delete Widget"), "actionRemove", [this] {
    const auto sel = impl_->controller->selection();
    if (!impl_->selectedObjectNames().empty() && sel.empty() && !impl_->selectedBinding) {
      deleteSelectedObjects();  // the Delete key deletes whatever is selected
    } else if (impl_->selectedBinding) {
      impl_->controller->unbind(*impl_->selectedBinding);
      impl_->selectedBinding.reset();
    } else if (!sel.empty()) {
      impl_->controller->removeWidget(sel.front());
    }
  });
  addMenuAction(edit, tr("Delete &Object"), "actionDeleteObject", [this] { deleteSelectedObjects(); });
  addMenuAction(edit, tr("Re&name..."), "actionRename", [this] { renameSelection(); });
  edit->addSeparator();
  addMenuAction(edit, tr("&Preferences..."), "actionPreferences", [this] {
    QDialog dialog(this);
    dialog.setObjectName("preferencesDialog");
    dialog.setWindowTitle(tr("Preferences"));
    auto* form = new QFormLayout(&dialog);
    auto* minutes = new QSpinBox;
    minutes->setObjectName("autosaveMinutes");
    minutes->setRange(0, 120);
    minutes->setSpecialValueText(tr("only on changes"));
    minutes->setSuffix(tr(" min"));
    minutes->setValue(QSettings().value("autosaveMinutes", kDefaultAutosaveMinutes).toInt());
    form->addRow(tr("Autosave for recovery every"), minutes);
    if (!acceptedForm(dialog, form)) return;
    QSettings().setValue("autosaveMinutes", minutes->value());
    startAutosaveTimer();
  });
}

QMenu* MainWindow::createWidgetsMenu() {
  Impl& d = *impl_;
  // The thesis operations (Kuriyama 1996, sec. 6.4).
  QMenu* widgetsMenu = menuBar()->addMenu(tr("&Widgets"));
  addMenuAction(widgetsMenu, tr("New &Lattice..."), "actionNewLattice", [this] { newLatticeInteractively(); });
  widgetsMenu->addSeparator();
  const std::pair<const char*, widgets::AffineKind> kinds[] = {{"actionAddTranslate", widgets::AffineKind::Translate},
                                                               {"actionAddRotate", widgets::AffineKind::Rotate},
                                                               {"actionAddScale", widgets::AffineKind::Scale}};
  for (const auto& [name, kind] : kinds)
    addMenuAction(widgetsMenu, tr("Add %1 Widget").arg(qs(std::string(widgets::affineKindName(kind)))), name,
                  [this, kind = kind] { addAffineWidget(kind); });
  addMenuAction(widgetsMenu, tr("&Bind Two Widgets"), "actionBind", [this] {
    const auto sel = impl_->controller->selection();
    if (sel.size() != 2) throw std::invalid_argument("select exactly two widgets to bind (Ctrl+click)");
    impl_->controller->bind(sel[0], sel[1]);
  });
  widgetsMenu->addSeparator();
  auto selectedLattice = [this]() -> widgets::WidgetId {
    for (widgets::WidgetId w : impl_->controller->selection())
      if (impl_->scene.widgets.type(w) == widgets::WidgetType::Lattice) return w;
    const auto roots = impl_->scene.widgets.roots();
    if (roots.size() == 1) return roots.front();
    throw std::invalid_argument("select a lattice");
  };
  auto selectedObject = [this]() -> std::string {
    if (const std::vector<std::string> selected = impl_->selectedObjectNames(); !selected.empty()) return selected.front();
    if (impl_->scene.objects().size() == 1) return impl_->scene.objects().front().name;
    throw std::invalid_argument("select an object in the outliner");
  };
  addMenuAction(widgetsMenu, tr("&Attach Lattice to Object"), "actionAttach", [this, selectedLattice, selectedObject] {
    if (!attachLattice(selectedLattice(), selectedObject())) impl_->status->say(tr("Attach cancelled"), 5000);
  });
  addMenuAction(widgetsMenu, tr("&Detach Lattice from Object"), "actionDetach", [this, selectedLattice, selectedObject] {
    impl_->controller->detachLattice(selectedLattice(), selectedObject());
  });
  // Direct manipulation (Hsu, Hughes & Kaufman 1992): a mode, because a drag on an object otherwise orbits.
  d.directManipulation = addMenuAction(widgetsMenu, tr("&Direct Manipulation"), "actionDirectManipulation", [this] {
    impl_->status->say(impl_->directManipulation->isChecked()
                           ? tr("Direct manipulation: drag a point of an object; its lattice follows")
                           : tr("Direct manipulation off"),
                       5000);
  });
  d.directManipulation->setCheckable(true);
  d.directManipulation->setToolTip(tr("Drag points of objects: the lattice gets the smallest change that puts the point under the pointer"));
  addMenuAction(widgetsMenu, tr("&Clear Pins"), "actionClearPins", [this] { impl_->controller->clearPins(); });
  widgetsMenu->addSeparator();
  addMenuAction(widgetsMenu, tr("Add &Primitive..."), "actionAddPrimitive", [this] { addPrimitiveInteractively(); });
  return widgetsMenu;
}

void MainWindow::addAffineWidget(widgets::AffineKind kind) {
  InteractionController& controller = *impl_->controller;
  if (const auto point = controller.pickedPoint()) {
    controller.addAffineAtPoint(*point, kind);
    return;
  }
  for (widgets::WidgetId w : controller.selection())
    if (impl_->scene.widgets.type(w) == widgets::WidgetType::Cell) {
      controller.addAffine(w, kind);
      return;
    }
  throw std::invalid_argument("pick a lattice point or select a cell first");
}

void MainWindow::newLatticeInteractively() {
  QDialog dialog(this);
  dialog.setObjectName("newLatticeDialog");
  dialog.setWindowTitle(tr("New Lattice"));
  auto* form = new QFormLayout(&dialog);
  QSpinBox* counts[3];
  QComboBox* bases[3];
  for (int a = 0; a < 3; ++a) {
    counts[a] = new QSpinBox;
    counts[a]->setObjectName(QString("count%1").arg("uvw"[a]));
    counts[a]->setRange(2, 32);
    counts[a]->setValue(3);
    bases[a] = new QComboBox;
    bases[a]->setObjectName(QString("basis%1").arg("uvw"[a]));
    bases[a]->addItems({tr("Bernstein"), tr("B-spline cubic"), tr("B-spline quadratic"), tr("B-spline linear")});
    form->addRow(tr("Points along %1").arg("uvw"[a]), counts[a]);
    form->addRow(tr("Basis along %1").arg("uvw"[a]), bases[a]);
  }
  auto* cylindrical = new QCheckBox(tr("cylindrical (radius, angle, height)"));
  cylindrical->setObjectName("cylindrical");
  form->addRow(tr("Shape"), cylindrical);
  if (!acceptedForm(dialog, form)) return;
  NewLatticeOptions options;
  for (int a = 0; a < 3; ++a) {
    options.counts[a] = counts[a]->value();
    const int degree = std::min(counts[a]->value() - 1, 4 - bases[a]->currentIndex());
    options.basis[static_cast<std::size_t>(a)] =
        bases[a]->currentIndex() == 0 ? ffd::AxisBasis::bernstein() : ffd::AxisBasis::bspline(degree);
  }
  options.cylindrical = cylindrical->isChecked();
  impl_->controller->newLattice(options);
  impl_->status->say(tr("New lattice: click one of its points, then add a widget"));
}

void MainWindow::addPrimitiveInteractively() {
  QDialog dialog(this);
  dialog.setObjectName("addPrimitiveDialog");
  dialog.setWindowTitle(tr("Add Primitive"));
  auto* form = new QFormLayout(&dialog);
  auto* kind = new QComboBox;
  kind->setObjectName("primitiveKind");
  for (auto k2 : {scenes::PrimitiveKind::Sphere, scenes::PrimitiveKind::Cylinder, scenes::PrimitiveKind::Cube,
                  scenes::PrimitiveKind::Cone, scenes::PrimitiveKind::Torus, scenes::PrimitiveKind::Plane})
    kind->addItem(qs(std::string(scenes::primitiveKindName(k2))), static_cast<int>(k2));
  auto* axis = new QComboBox;
  axis->setObjectName("primitiveAxis");
  axis->addItems({tr("+z"), tr("+x"), tr("+y")});
  auto* resolution = new QSpinBox;
  resolution->setObjectName("primitiveResolution");
  resolution->setRange(3, 512);
  resolution->setValue(32);
  form->addRow(tr("Type"), kind);
  form->addRow(tr("Axis"), axis);
  form->addRow(tr("Resolution"), resolution);
  if (!acceptedForm(dialog, form)) return;
  scenes::PrimitiveOptions options;
  options.kind = static_cast<scenes::PrimitiveKind>(kind->currentData().toInt());
  options.resolution = resolution->value();
  if (axis->currentIndex() == 1) options.placement = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY());
  if (axis->currentIndex() == 2) options.placement = Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitX());
  const std::string name = impl_->controller->addPrimitive(options);
  impl_->selectedObjects = {impl_->scene.objectId(name)};
  impl_->outliner->select(impl_->entries());
}

QMenu* MainWindow::createViewMenu(QDockWidget* outlinerDock, QDockWidget* propertiesDock) {
  Impl& d = *impl_;
  QMenu* viewMenu = menuBar()->addMenu(tr("&View"));
  addMenuAction(viewMenu, tr("&Reset Camera"), "actionResetCamera", [this] {
    impl_->sceneView->applyCamera(impl_->scene.camera());
    impl_->view->requestRender();
  });
  d.navigation = new ViewNavigation(
      d.view, *d.sceneView,
      [this] { return selectionBounds(impl_->scene, impl_->deformed(), impl_->controller->selection(), impl_->selectedObjectNames()); },
      [this] { return sceneBounds(impl_->scene, impl_->deformed()); }, this);
  d.navigation->addActions(viewMenu);
  viewMenu->addSeparator();
  // Looks of the selected objects (else of all): reflection lines on surfaces, curvature combs
  // on curves (DisplaySettings::surfaceStyle / curvatureComb; stripe count and comb scale are
  // scene-file settings).
  d.zebra = addMenuAction(viewMenu, tr("&Zebra Stripes"), "actionZebra", [this] {
    const bool on = impl_->zebra->isChecked();
    impl_->changeLook(on ? "Zebra stripes" : "Shaded surfaces", [on](const scenes::SceneObject& o, scenes::DisplaySettings& look) {
      if (o.mesh.triangles.rows() > 0) look.surfaceStyle = on ? scenes::SurfaceStyle::Zebra : scenes::SurfaceStyle::Shaded;
    });
  });
  d.zebra->setCheckable(true);
  d.comb = addMenuAction(viewMenu, tr("Curvature &Comb"), "actionCurvatureComb", [this] {
    const bool on = impl_->comb->isChecked();
    impl_->changeLook(on ? "Curvature comb" : "No curvature comb", [on](const scenes::SceneObject& o, scenes::DisplaySettings& look) {
      if (o.mesh.segments.rows() > 0) look.curvatureComb = on;
    });
  });
  d.comb->setCheckable(true);
  // Level of detail (SceneView::setLevelOfDetail): large surfaces drawn simplified while a drag or
  // playback runs, in full when it stops. Kept between sessions.
  QAction* simplify = addMenuAction(viewMenu, tr("&Simplify While Moving"), "actionSimplifyWhileMoving", [this] {
    const bool on = findChild<QAction*>("actionSimplifyWhileMoving")->isChecked();
    QSettings().setValue(kSimplifyWhileMovingKey, on);
    LevelOfDetail lod = impl_->sceneView->levelOfDetail();
    lod.enabled = on;
    impl_->sceneView->setLevelOfDetail(lod);
    impl_->frameDue = true;  // the next frame's refresh builds the proxies, before anything moves
    impl_->view->requestRender();
  });
  simplify->setCheckable(true);
  simplify->setChecked(QSettings().value(kSimplifyWhileMovingKey, true).toBool());
  {
    LevelOfDetail lod = d.sceneView->levelOfDetail();
    lod.enabled = simplify->isChecked();
    d.sceneView->setLevelOfDetail(lod);
  }
  viewMenu->addSeparator();
  viewMenu->addAction(outlinerDock->toggleViewAction());
  viewMenu->addAction(propertiesDock->toggleViewAction());

  return viewMenu;
}

void MainWindow::createOperationsToolbar(QMenu* widgetsMenu, QMenu* viewMenu) {
  Impl& d = *impl_;
  QToolBar* toolbar = addToolBar(tr("Operations"));
  toolbar->setObjectName("operationsToolbar");
  toolbar->addAction(d.undo);
  toolbar->addAction(d.redo);
  toolbar->addSeparator();
  for (const char* name : {"actionAddPrimitive", "actionNewLattice", "actionAddTranslate", "actionAddRotate",
                           "actionAddScale", "actionBind", "actionAttach", "actionDirectManipulation"})
    toolbar->addAction(findChild<QAction*>(name));
  d.editInput = new EditModeInput({this, d.view, d.sceneView.get(), d.status, &d.scene, d.controller.get(), d.edit.get(),
                                   [this](const std::string& m) { impl_->sayError(m); },
                                   [this](const QPoint& p) { return impl_->rayAt(p); }, [this] { return impl_->tolerance(); },
                                   [this] { impl_->controller->onChanged(); }, [this] { return impl_->selectedObjects; },
                                   [this] { impl_->properties->showSelection(impl_->entries()); }},
                                  widgetsMenu, toolbar);
  viewMenu->addSeparator();
  addToolbarTextOption(viewMenu, toolbar);
}

}  // namespace ffdkit::app
