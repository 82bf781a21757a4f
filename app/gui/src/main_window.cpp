#include "ffdkit/app/main_window.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <numbers>

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QCheckBox>
#include <QCloseEvent>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QMouseEvent>
#include <QEventLoop>
#include <QProgressDialog>
#include <QPointer>
#include <QThread>
#include <QTimer>
#include <QScrollArea>
#include <QSettings>
#include <QSpinBox>
#include <QStatusBar>
#include <QToolBar>

#include "ffdkit/ffd/cancelled.h"
#include "ffdkit/app/scene_bounds.h"
#include "import_options.h"
#include "keyboard_shortcuts.h"
#include "gltf_export_dialog.h"
#include "main_window_impl.h"

namespace ffdkit::app {

using namespace window_detail;

namespace {
/// The status bar's last deform time: "deform 8.80 ms, 1000000 points", and when the update
/// (re-)embedded, how much of it that took.
QString deformStatusText(const scenes::SceneDeformStats& stats) {
  QString text = QObject::tr("deform %1 ms, %2 points").arg(stats.seconds * 1e3, 0, 'f', 2).arg(stats.deformedPoints);
  if (stats.embedSeconds > 0.0) text += QObject::tr(" (embed %1 ms)").arg(stats.embedSeconds * 1e3, 0, 'f', 2);
  return text;
}

/// Adds OK / Cancel to a form dialog and runs it. @return true if accepted.
bool acceptedForm(QDialog& dialog, QFormLayout* form) {
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
  QObject::connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
  QObject::connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
  form->addRow(buttons);
  return dialog.exec() == QDialog::Accepted;
}
}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent), impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  setWindowTitle(tr("untitled[*] - ffdkit"));
  setAcceptDrops(true);
  d.view = new VtkViewWidget(this);
  d.view->setObjectName("view");
  d.view->setMouseTracking(true);
  d.view->installEventFilter(this);
  setCentralWidget(d.view);
  d.sceneView = std::make_unique<SceneView>(d.view->renderer());
  d.controller = std::make_unique<InteractionController>(d.scene, d.deformer, d.commands);
  d.edit = std::make_unique<EditController>(d.scene, d.deformer, d.commands, *d.controller);

  // Outliner and property panel.
  d.outliner = new Outliner;
  auto* outlinerDock = new QDockWidget(tr("Outliner"), this);
  outlinerDock->setObjectName("outlinerDock");
  outlinerDock->setWidget(d.outliner);
  addDockWidget(Qt::LeftDockWidgetArea, outlinerDock);
  d.properties = new PropertyPanel(*d.controller, d.scene);
  auto* scroll = new QScrollArea;
  scroll->setWidgetResizable(true);
  scroll->setWidget(d.properties);
  auto* propertiesDock = new QDockWidget(tr("Properties"), this);
  propertiesDock->setObjectName("propertiesDock");
  propertiesDock->setWidget(scroll);
  addDockWidget(Qt::RightDockWidgetArea, propertiesDock);
  connect(d.properties, &PropertyPanel::error, this, [this](const QString& m) { impl_->sayError(m.toStdString()); });

  auto refreshPanel = [this] {
    impl_->properties->showSelection(impl_->entries());
    impl_->syncLookActions();
  };
  connect(d.outliner, &Outliner::selectionEdited, this, [this, refreshPanel] {
    Impl& s = *impl_;
    s.selectedObjects.clear();
    s.selectedBinding.reset();
    std::vector<widgets::WidgetId> widgets;
    for (const auto& e : s.outliner->selection()) {
      if (e.kind == OutlinerEntry::Kind::Object) s.selectedObjects.push_back(e.object);
      if (e.kind == OutlinerEntry::Kind::Widget) widgets.push_back(e.widget);
      if (e.kind == OutlinerEntry::Kind::Binding) s.selectedBinding = e.binding;
    }
    s.controller->setSelection(widgets);
    s.status->clearStale();
    refreshPanel();
  });
  connect(d.outliner, &Outliner::siblingMoveRequested, this, [this](widgets::WidgetId lattice, int position) {
    try {
      impl_->controller->setSiblingPosition(lattice, static_cast<std::size_t>(position));
    } catch (const std::exception& e) {
      impl_->sayError(e.what());
    }
  });

  // Model -> view.
  d.status = new StatusLine;
  statusBar()->addWidget(d.status, 1);
  d.deformStatus = new QLabel;
  d.deformStatus->setObjectName("deformStatus");
  statusBar()->addPermanentWidget(d.deformStatus);
  d.controller->onChanged = [this] {
    Impl& s = *impl_;
    if (!s.showingScene) return;
    s.sceneView->setHighlights(s.edit->highlights(s.controller->highlights()));
    s.sceneView->refresh(s.scene, s.deformer);
    if (s.timeline) s.timeline->sync();
    if (const auto value = s.controller->handleDragValue()) {
      // What the transformer drag does so far, as a designer reads it.
      const TransformerHandle handle = *s.controller->transformerHandle();
      const int group = static_cast<int>(handle) / 3;
      const QString amount = group == 0   ? QString::number(*value, 'f', 3)
                             : group == 1 ? QString("%1°").arg(*value * 180.0 / std::numbers::pi, 0, 'f', 1)
                                          : QString("x%1").arg(*value, 0, 'f', 3);
      s.status->say(QString("%1 %2").arg(transformerHandleName(handle), amount));
    }
    const auto& stats = s.deformer.lastStats();
    // An update with nothing to do (a hover, a selection) keeps the last real deform time.
    if (stats.seconds > 0.0 && stats.deformedPoints > 0 && (stats.seconds >= 1e-5 || stats.reembeddedStages > 0))
      s.deformStatus->setText(deformStatusText(stats));
    s.view->requestRender();
  };
  d.controller->onStructureChanged = [this, refreshPanel] {
    impl_->outliner->rebuild(impl_->scene);
    refreshPanel();
  };
  d.commands.onChanged = [this, refreshPanel] {
    Impl& s = *impl_;
    s.undo->setEnabled(s.commands.canUndo());
    s.redo->setEnabled(s.commands.canRedo());
    // The menu names the step; the toolbar button keeps its short text (a fixed width) and
    // names the step in its tooltip.
    const QString undoStep = qs(s.commands.undoDescription()), redoStep = qs(s.commands.redoDescription());
    s.undo->setText(s.commands.canUndo() ? tr("&Undo %1").arg(undoStep) : tr("&Undo"));
    s.redo->setText(s.commands.canRedo() ? tr("&Redo %1").arg(redoStep) : tr("&Redo"));
    s.undo->setIconText(tr("Undo"));
    s.redo->setIconText(tr("Redo"));
    s.undo->setToolTip(s.commands.canUndo() ? tr("Undo %1 (Ctrl+Z)").arg(undoStep) : tr("Nothing to undo"));
    s.redo->setToolTip(s.commands.canRedo() ? tr("Redo %1 (Ctrl+Shift+Z)").arg(redoStep) : tr("Nothing to redo"));
    s.status->clearStale();  // what was said was about the document before this change
    setWindowModified(s.modified());
    s.autosave();
    if (s.selectedBinding && !s.scene.widgets.bindings().empty()) {
      const auto all = s.scene.widgets.bindings();
      if (std::find(all.begin(), all.end(), *s.selectedBinding) == all.end()) s.selectedBinding.reset();
    }
    s.outliner->select(s.entries());
    refreshPanel();
  };

  // Helpers for actions.
  auto action = [this](QMenu* menu, const QString& text, const char* name, auto slot) {
    QAction* a = menu->addAction(text);
    a->setObjectName(name);
    connect(a, &QAction::triggered, this, [this, slot] {
      try {
        slot();
      } catch (const std::exception& e) {
        impl_->sayError(e.what());
        QApplication::beep();
      }
    });
    return a;
  };
  auto fileAction = [this, action](QMenu* menu, const QString& text, const char* name, bool save, const QString& filter,
                                   auto apply) {
    return action(menu, text, name, [this, text, save, filter, apply] {
      const QString path = save ? QFileDialog::getSaveFileName(this, text, QString(), filter)
                                : QFileDialog::getOpenFileName(this, text, QString(), filter);
      if (path.isEmpty()) return;
      try {
        apply(std::filesystem::path(path.toStdString()));
      } catch (const std::exception& e) {
        QMessageBox::critical(this, text, qs(e.what()));
      }
    });
  };

  const QString sceneFilter = tr("ffdkit scenes (*.json);;All files (*)");
  const QString widgetFilter = tr("ffdkit widget files (*.json);;All files (*)");
  const QString meshFilter = tr("Meshes (*.obj *.ply *.stl *.vtp *.vtk *.gltf *.glb *.xyz *.npy);;All files (*)");

  QMenu* file = menuBar()->addMenu(tr("&File"));
  action(file, tr("&New Scene"), "actionNewScene", [this] {
    if (maybeSave()) newScene();
  });
  action(file, tr("&Open Scene..."), "actionOpenScene", [this, sceneFilter] {
    if (!maybeSave()) return;
    const QString path = QFileDialog::getOpenFileName(this, tr("Open Scene"), QString(), sceneFilter);
    if (path.isEmpty()) return;
    try {
      openScene(path.toStdString());
    } catch (const std::exception& e) {
      QMessageBox::critical(this, tr("Open Scene"), qs(e.what()));
    }
  });
  d.recentMenu = file->addMenu(tr("Open &Recent"));
  action(file, tr("&Save Scene"), "actionSaveScene", [this] { saveInteractively(false); });
  action(file, tr("Save Scene &As..."), "actionSaveSceneAs", [this] { saveInteractively(true); });
  file->addSeparator();
  fileAction(file, tr("Open &Widget File..."), "actionOpenWidgetFile", false, widgetFilter,
             [this](const std::filesystem::path& p) { openWidgetFile(p); });
  fileAction(file, tr("Save W&idget File..."), "actionSaveWidgetFile", true, widgetFilter,
             [this](const std::filesystem::path& p) { saveWidgetFile(p); });
  file->addSeparator();
  fileAction(file, tr("&Import Mesh..."), "actionImportMesh", false, meshFilter,
             [this](const std::filesystem::path& p) { importMesh(p); });
  addImportUpAxisMenu(file);
  fileAction(file, tr("&Export Deformed Mesh..."), "actionExportMesh", true, meshFilter,
             [this](const std::filesystem::path& p) { exportMesh(p); });
  action(file, tr("Export &glTF..."), "actionExportGltf", [this] { exportGltfInteractively(this, impl_->scene); });
  file->addSeparator();
  // A preference, off by default: a shared scene must not make the app read files outside the
  // scene's folder (scenes::SceneReadOptions::allowMeshesOutsideFolder).
  QAction* outside = file->addAction(tr("Allow Meshes &Outside a Scene's Folder"));
  outside->setObjectName("actionAllowOutsideMeshes");
  outside->setCheckable(true);
  outside->setChecked(QSettings().value(kAllowOutsideMeshesKey, false).toBool());
  connect(outside, &QAction::toggled, this, [](bool on) { QSettings().setValue(kAllowOutsideMeshesKey, on); });
  file->addSeparator();
  action(file, tr("&Quit"), "actionQuit", [this] { close(); });

  QMenu* edit = menuBar()->addMenu(tr("&Edit"));
  d.undo = action(edit, tr("&Undo"), "actionUndo", [this] { impl_->commands.undo(); });
  d.redo = action(edit, tr("&Redo"), "actionRedo", [this] { impl_->commands.redo(); });
  d.undo->setEnabled(false);
  d.redo->setEnabled(false);
  edit->addSeparator();
  action(edit, tr("&Delete Widget"), "actionRemove", [this] {
    const auto sel = impl_->controller->selection();
    if (!impl_->selectedObjects.empty() && sel.empty() && !impl_->selectedBinding) {
      deleteSelectedObjects();  // the Delete key deletes whatever is selected
    } else if (impl_->selectedBinding) {
      impl_->controller->unbind(*impl_->selectedBinding);
      impl_->selectedBinding.reset();
    } else if (!sel.empty()) {
      impl_->controller->removeWidget(sel.front());
    }
  });
  action(edit, tr("Delete &Object"), "actionDeleteObject", [this] { deleteSelectedObjects(); });
  action(edit, tr("Re&name..."), "actionRename", [this] { renameSelection(); });
  edit->addSeparator();
  action(edit, tr("&Preferences..."), "actionPreferences", [this] {
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

  // The thesis operations (seed 001 §6.4).
  QMenu* widgetsMenu = menuBar()->addMenu(tr("&Widgets"));
  QAction* newLattice = action(widgetsMenu, tr("New &Lattice..."), "actionNewLattice", [this] {
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
  });
  widgetsMenu->addSeparator();
  const std::pair<const char*, widgets::AffineKind> kinds[] = {{"actionAddTranslate", widgets::AffineKind::Translate},
                                                               {"actionAddRotate", widgets::AffineKind::Rotate},
                                                               {"actionAddScale", widgets::AffineKind::Scale}};
  QAction* addActions[3];
  int k = 0;
  for (const auto& [name, kind] : kinds) {
    const widgets::AffineKind kindCopy = kind;
    addActions[k++] = action(widgetsMenu,
                             tr("Add %1 Widget").arg(qs(std::string(widgets::affineKindName(kind)))), name,
                             [this, kindCopy] {
                               Impl& s = *impl_;
                               if (const auto point = s.controller->pickedPoint()) {
                                 s.controller->addAffineAtPoint(*point, kindCopy);
                                 return;
                               }
                               for (widgets::WidgetId w : s.controller->selection())
                                 if (s.scene.widgets.type(w) == widgets::WidgetType::Cell) {
                                   s.controller->addAffine(w, kindCopy);
                                   return;
                                 }
                               throw std::invalid_argument("pick a lattice point or select a cell first");
                             });
  }
  QAction* bind = action(widgetsMenu, tr("&Bind Two Widgets"), "actionBind", [this] {
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
    if (!impl_->selectedObjects.empty()) return impl_->selectedObjects.front();
    if (impl_->scene.objects.size() == 1) return impl_->scene.objects.front().name;
    throw std::invalid_argument("select an object in the outliner");
  };
  QAction* attach = action(widgetsMenu, tr("&Attach Lattice to Object"), "actionAttach",
                           [this, selectedLattice, selectedObject] {
                             if (!attachLattice(selectedLattice(), selectedObject()))
                               impl_->status->say(tr("Attach cancelled"), 5000);
                           });
  action(widgetsMenu, tr("&Detach Lattice from Object"), "actionDetach", [this, selectedLattice, selectedObject] {
    impl_->controller->detachLattice(selectedLattice(), selectedObject());
  });
  // Direct manipulation (spec §10): a mode, because a drag on an object otherwise orbits.
  d.directManipulation = action(widgetsMenu, tr("&Direct Manipulation"), "actionDirectManipulation", [this] {
    impl_->status->say(impl_->directManipulation->isChecked()
                           ? tr("Direct manipulation: drag a point of an object; its lattice follows")
                           : tr("Direct manipulation off"),
                       5000);
  });
  d.directManipulation->setCheckable(true);
  d.directManipulation->setToolTip(tr("Drag points of objects: the lattice gets the smallest change that puts the point under the pointer (D)"));
  action(widgetsMenu, tr("&Clear Pins"), "actionClearPins", [this] { impl_->controller->clearPins(); });
  widgetsMenu->addSeparator();
  QAction* primitive = action(widgetsMenu, tr("Add &Primitive..."), "actionAddPrimitive", [this] {
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
    impl_->selectedObjects = {name};
    impl_->outliner->select(impl_->entries());
  });

  QMenu* viewMenu = menuBar()->addMenu(tr("&View"));
  action(viewMenu, tr("&Reset Camera"), "actionResetCamera", [this] {
    impl_->sceneView->applyCamera(impl_->scene.camera);
    impl_->view->requestRender();
  });
  d.navigation = new ViewNavigation(
      d.view, *d.sceneView,
      [this] { return selectionBounds(impl_->scene, impl_->deformer, impl_->controller->selection(), impl_->selectedObjects); },
      [this] { return sceneBounds(impl_->scene, impl_->deformer); }, this);
  d.navigation->addActions(viewMenu);
  viewMenu->addSeparator();
  // Looks of the selected objects (else of all): reflection lines on surfaces, curvature combs
  // on curves (DisplaySettings::surfaceStyle / curvatureComb; stripe count and comb scale are
  // scene-file settings).
  d.zebra = action(viewMenu, tr("&Zebra Stripes"), "actionZebra", [this] {
    const bool on = impl_->zebra->isChecked();
    impl_->changeLook(on ? "Zebra stripes" : "Shaded surfaces", [on](const scenes::SceneObject& o, scenes::DisplaySettings& look) {
      if (o.mesh.triangles.rows() > 0) look.surfaceStyle = on ? scenes::SurfaceStyle::Zebra : scenes::SurfaceStyle::Shaded;
    });
  });
  d.zebra->setCheckable(true);
  d.comb = action(viewMenu, tr("Curvature &Comb"), "actionCurvatureComb", [this] {
    const bool on = impl_->comb->isChecked();
    impl_->changeLook(on ? "Curvature comb" : "No curvature comb", [on](const scenes::SceneObject& o, scenes::DisplaySettings& look) {
      if (o.mesh.segments.rows() > 0) look.curvatureComb = on;
    });
  });
  d.comb->setCheckable(true);
  viewMenu->addSeparator();
  viewMenu->addAction(outlinerDock->toggleViewAction());
  viewMenu->addAction(propertiesDock->toggleViewAction());

  QToolBar* toolbar = addToolBar(tr("Operations"));
  toolbar->setObjectName("operationsToolbar");
  toolbar->addAction(d.undo);
  toolbar->addAction(d.redo);
  toolbar->addSeparator();
  toolbar->addAction(primitive);
  toolbar->addAction(newLattice);
  for (QAction* a : addActions) toolbar->addAction(a);
  toolbar->addAction(bind);
  toolbar->addAction(attach);
  toolbar->addAction(d.directManipulation);
  d.editInput = new EditModeInput({this, d.view, d.sceneView.get(), d.status, &d.scene, d.controller.get(), d.edit.get(),
                                   [this](const std::string& m) { impl_->sayError(m); },
                                   [this](const QPoint& p) { return impl_->rayAt(p); }, [this] { return impl_->tolerance(); },
                                   [this] { impl_->controller->onChanged(); }},
                                  widgetsMenu, toolbar);

  d.timeline = addTimelineDock(this, d.scene, d.commands, *d.controller);
  connect(d.timeline, &TimelineWidget::error, this, [this](const QString& m) { impl_->sayError(m.toStdString()); });
  connect(d.timeline, &TimelineWidget::frameChanged, this, refreshPanel);
  QMenu* help = menuBar()->addMenu(tr("&Help"));
  action(help, tr("&Keyboard Shortcuts"), "actionKeyboardShortcuts", [this] { showKeyboardShortcuts(this); });
  applyKeyboardShortcuts(this);  // every action's keys from the one table (keyboard_shortcuts.h)

  rebuildRecentMenu();

  setScene({});
  resize(1280, 800);
  resizeDocks({outlinerDock, propertiesDock}, {280, 340}, Qt::Horizontal);
  // The layout the user left (dock sizes and places, toolbar, window geometry).
  QSettings settings;
  restoreGeometry(settings.value("windowGeometry").toByteArray());
  restoreState(settings.value("windowState").toByteArray());

  connect(&d.autosaveTimer, &QTimer::timeout, this, [this] { impl_->autosave(); });
  startAutosaveTimer();
}

MainWindow::~MainWindow() = default;

namespace {
long backgroundPoints = 200000;
}

void MainWindow::setBackgroundEmbedPoints(long points) { backgroundPoints = points; }
long MainWindow::backgroundEmbedPoints() { return backgroundPoints; }

bool MainWindow::attachLattice(widgets::WidgetId lattice, const std::string& object) {
  Impl& d = *impl_;
  const scenes::SceneObject* target = d.scene.findObject(object);
  if (target == nullptr || target->mesh.points.rows() < backgroundPoints) {
    d.controller->attachLattice(lattice, object);
    return true;
  }
  // Embed on a copy of the scene in a worker thread; the GUI stays live, shows the embedding's
  // progress and can cancel it: the worker's progress hook reports into atomics that a timer
  // polls, and stops the embedding (ffd::Cancelled) at its next chunk once Cancel is pressed.
  struct Job {
    scenes::Scene scene;
    scenes::SceneDeformer deformer;
    std::string error;
    std::atomic<int> permille{0};
    std::atomic<bool> cancel{false};
  };
  auto job = std::make_shared<Job>();
  job->scene = d.scene;
  fitAndAttachLattice(job->scene, lattice, object);  // throws before anything starts
  job->deformer.setProgress([raw = job.get()](double fraction) {
    raw->permille.store(static_cast<int>(std::lround(1000.0 * fraction)));
    return !raw->cancel.load();
  });
  QThread* thread = QThread::create([job] {
    try {
      job->deformer.finishGesture(job->scene);
    } catch (const ffd::Cancelled&) {
      // The copy is dropped below.
    } catch (const std::exception& e) {
      job->error = e.what();
    }
  });
  QProgressDialog progress(tr("Embedding %1 points of '%2'...").arg(target->mesh.points.rows()).arg(qs(object)),
                           tr("Cancel"), 0, 1000, this);
  progress.setObjectName("embedProgress");
  progress.setWindowModality(Qt::WindowModal);
  progress.setMinimumDuration(0);
  progress.setAutoReset(false);
  progress.setAutoClose(false);
  QTimer poll;
  connect(&poll, &QTimer::timeout, &progress, [&] { progress.setValue(job->permille.load()); });
  QEventLoop loop;
  connect(thread, &QThread::finished, &loop, &QEventLoop::quit);
  connect(&progress, &QProgressDialog::canceled, &loop, [&] {
    job->cancel.store(true);  // the worker stops at its next chunk; wait for it below
  });
  connect(thread, &QThread::finished, thread, &QObject::deleteLater);
  thread->start();
  progress.show();
  poll.start(30);
  loop.exec();  // until the worker has finished, cancelled or not
  poll.stop();
  progress.reset();
  const bool cancelled = job->cancel.load();
  job->deformer.setProgress({});  // the hook points into the job
  if (cancelled) return false;
  if (!job->error.empty()) throw std::runtime_error(job->error);
  d.controller->adoptDeformer(std::move(job->deformer));
  d.controller->attachLattice(lattice, object);  // the same edit: nothing left to embed
  return true;
}

void MainWindow::selectWidget(const std::string& name) {
  Impl& d = *impl_;
  const widgets::WidgetId id = d.scene.widgets.find(name);
  d.selectedObjects.clear();
  d.selectedBinding.reset();
  d.controller->setSelection({id});
  d.outliner->select(d.entries());
  d.properties->showSelection(d.entries());
}

void MainWindow::setScene(scenes::Scene scene) {
  Impl& d = *impl_;
  d.showingScene = false;
  if (d.editInput) d.editInput->leave();
  d.controller->cancel();
  d.controller->clearSelection();
  d.controller->clearPins();
  d.scene = std::move(scene);
  d.restoredUnsaved = false;  // a new document; offerRecovery marks a restored one after this
  d.selectedObjects.clear();
  d.selectedBinding.reset();
  d.commands.clear();
  d.deformer.reset();
  d.deformer.finishGesture(d.scene);
  d.deformStatus->setText(deformStatusText(d.deformer.lastStats()));
  d.sceneView->setHighlights(d.controller->highlights());
  d.sceneView->show(d.scene, d.deformer);
  d.showingScene = true;
  d.outliner->rebuild(d.scene);
  d.properties->showSelection({});
  d.syncLookActions();
  d.status->say(tr("%1 objects, %2 lattices")
                    .arg(d.scene.objects.size())
                    .arg(d.scene.widgets.widgets(widgets::WidgetType::Lattice).size()));
  d.controller->refresh();
  d.view->requestRender();
}

const scenes::Scene& MainWindow::scene() const { return impl_->scene; }
const scenes::SceneDeformer& MainWindow::deformer() const { return impl_->deformer; }
scenes::CommandStack& MainWindow::commands() const { return impl_->commands; }
InteractionController& MainWindow::controller() const { return *impl_->controller; }
EditController& MainWindow::editController() const { return *impl_->edit; }
SceneView& MainWindow::sceneView() const { return *impl_->sceneView; }
QTreeWidget* MainWindow::outliner() const { return impl_->outliner; }
VtkViewWidget* MainWindow::view() const { return impl_->view; }

bool MainWindow::eventFilter(QObject* watched, QEvent* event) {
  Impl& d = *impl_;
  if (watched != d.view) return QMainWindow::eventFilter(watched, event);
  // In a lattice's edit mode the left button is the edit mode's (edit_mode.cpp); what it passes
  // on (Alt+drag) orbits.
  if (auto* e = dynamic_cast<QMouseEvent*>(event); e && d.edit->editing()) {
    if (event->type() == QEvent::MouseButtonPress && e->button() == Qt::LeftButton) d.navigation->beginOrbit(e->position().toPoint());
    if (event->type() == QEvent::MouseMove && d.navigation->orbitTo(e->position().toPoint())) return true;
    if (event->type() == QEvent::MouseButtonRelease && e->button() == Qt::LeftButton) d.navigation->endOrbit();
    return e->button() == Qt::LeftButton || QMainWindow::eventFilter(watched, event);
  }
  try {
    switch (event->type()) {
      case QEvent::MouseButtonPress: {
        auto* e = static_cast<QMouseEvent*>(event);
        if (e->button() != Qt::LeftButton) break;
        d.pressAt = e->position().toPoint();
        const bool extend = (e->modifiers() & (Qt::ControlModifier | Qt::ShiftModifier)) != 0;
        const bool lattices = (e->modifiers() & Qt::AltModifier) != 0;
        const auto hit = d.controller->press(d.rayAt(d.pressAt), d.tolerance(), extend, lattices);
        if (hit == InteractionController::PressResult::Nothing && d.directManipulation->isChecked() && !lattices &&
            d.controller->pressObject(d.rayAt(d.pressAt), d.tolerance(), e->modifiers().testFlag(Qt::ShiftModifier)))
          return true;  // dragging a point of an object: no orbit
        d.pressOnEmpty = hit == InteractionController::PressResult::Nothing;
        if (hit == InteractionController::PressResult::Handle) return true;  // the manipulator: no orbit
        if (hit != InteractionController::PressResult::Nothing) {
          d.selectedObjects.clear();
          d.selectedBinding.reset();
          d.outliner->select(d.entries());
          d.properties->showSelection(d.entries());
        }
        if (hit == InteractionController::PressResult::Widget) return true;  // no camera orbit
        d.navigation->beginOrbit(d.pressAt);  // empty space or a lattice point: the drag orbits
        return true;
      }
      case QEvent::MouseMove: {
        auto* e = static_cast<QMouseEvent*>(event);
        if (d.controller->dragging()) {
          d.controller->drag(d.rayAt(e->position().toPoint()));
          return true;
        }
        if (d.navigation->orbitTo(e->position().toPoint())) return true;
        if (e->buttons() == Qt::NoButton) d.controller->hover(d.rayAt(e->position().toPoint()), d.tolerance());
        break;
      }
      case QEvent::MouseButtonRelease: {
        auto* e = static_cast<QMouseEvent*>(event);
        if (e->button() != Qt::LeftButton) break;
        d.navigation->endOrbit();
        if (const auto grabbed = d.controller->grabbedPoint();
            grabbed && (e->position().toPoint() - d.pressAt).manhattanLength() < 4) {
          d.controller->cancel();  // a click on an object point (direct manipulation) pins or unpins it
          d.controller->togglePin({grabbed->first, grabbed->second});
          return true;
        }
        if (d.controller->dragging()) {
          d.controller->release();
          return true;
        }
        if (d.pressOnEmpty && (e->position().toPoint() - d.pressAt).manhattanLength() < 4) {
          // A click on empty space dismisses the selection (and its manipulator).
          d.controller->clearSelection();
          d.selectedObjects.clear();
          d.selectedBinding.reset();
          d.outliner->select({});
          d.properties->showSelection({});
        }
        d.pressOnEmpty = false;
        break;
      }
      case QEvent::KeyPress:
        if (matchesShortcut(*static_cast<QKeyEvent*>(event), "cancelDrag") && d.controller->dragging()) d.controller->cancel();
        // No key reaches VTK's interactor style: its defaults (w wireframe, 3 stereo, e / q
        // exit, r reset, f fly to, p pick, j / t / a / c modes, ...) are not ffdkit's; ffdkit's
        // keys are action shortcuts, handled before the view sees the key.
        return true;
      case QEvent::KeyRelease: return true;
      default: break;
    }
  } catch (const std::exception& e) {
    d.sayError(e.what());
    return true;
  }
  return QMainWindow::eventFilter(watched, event);
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  if (event->mimeData()->hasUrls()) event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
  for (const QUrl& url : event->mimeData()->urls()) {
    if (!url.isLocalFile()) continue;
    const std::filesystem::path file = url.toLocalFile().toStdString();
    if (opensAsScene(file) && !maybeSave()) continue;
    try {
      openAny(file);
    } catch (const std::exception& e) {
      QMessageBox::critical(this, tr("Cannot open"), qs(e.what()));
    }
  }
  event->acceptProposedAction();
}

void MainWindow::setLayoutRemembered(bool remembered) { impl_->rememberLayout = remembered; }

void MainWindow::closeEvent(QCloseEvent* event) {
  impl_->controller->cancel();
  if (!maybeSave()) {
    event->ignore();
    return;
  }
  if (impl_->rememberLayout) {
    QSettings settings;
    settings.setValue("windowGeometry", saveGeometry());
    settings.setValue("windowState", saveState());
  }
  impl_->recovery.remove();  // closed properly: nothing to recover
  event->accept();
}

}  // namespace ffdkit::app
