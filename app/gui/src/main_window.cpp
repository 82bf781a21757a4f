// MainWindow: the window, its docks, the model -> view wiring, the 3D view's pointer and keys,
// drops and closing. Its menus and actions are in main_window_menus.cpp, the document's files in
// main_window_document.cpp, a large attach's background embedding in main_window_embed.cpp.
#include "ffdkit/gui/main_window.h"

#include <algorithm>
#include <numbers>

#include <QCloseEvent>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QKeyEvent>
#include <QLabel>
#include <QMessageBox>
#include <QMimeData>
#include <QMouseEvent>
#include <QScrollArea>
#include <QSettings>
#include <QStatusBar>

#include "keyboard_shortcuts.h"
#include "main_window_impl.h"
#include "read_preferences.h"

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
  d.properties = new PropertyPanel(*d.controller, d.scene, d.edit.get());
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
    // Every model change (an undo too) comes here: the Edit Mode toggle follows
    // EditController::editing() before anything is drawn.
    if (s.editInput) s.editInput->syncEditToggle();
    if (!s.showingScene) return;
    // The scene is evaluated and drawn once, at the next frame (drawFrame), for every event
    // of this event-loop tick; a change that draws nothing new asks for no frame (requestFrame).
    s.requestFrame();
    if (s.timeline) s.timeline->sync();
    QString dragText;
    if (const auto value = s.controller->handleDragValue()) {
      // What the transformer drag does so far, as a designer reads it.
      const TransformerHandle handle = *s.controller->transformerHandle();
      const int group = static_cast<int>(handle) / 3;
      const QString amount = group == 0   ? QString::number(*value, 'f', 3)
                             : group == 1 ? QString("%1°").arg(*value * 180.0 / std::numbers::pi, 0, 'f', 1)
                                          : QString("x%1").arg(*value, 0, 'f', 3);
      dragText = QString("%1 %2").arg(transformerHandleName(handle), amount);
    }
    // Keep Volume / Keep Centre during a drag: the volume change of each kept object.
    if (s.editInput && s.controller->dragging())
      if (const QString guard = s.editInput->guardText(); !guard.isEmpty())
        dragText += (dragText.isEmpty() ? QString() : QString(" · ")) + guard;
    if (!dragText.isEmpty()) s.status->say(dragText);
  };
  // Evaluation once per event-loop tick: the controllers only ask for a frame; the frame
  // evaluates what every event before it changed (SceneDeformer::evaluate), then draws.
  d.controller->requestEvaluation = [this] { impl_->requestFrame(); };
  connect(d.view, &VtkViewWidget::aboutToRender, this, [this] { impl_->drawFrame(); });
  d.controller->onStructureChanged = [this, refreshPanel] {
    // A removed object leaves the selection, as its row leaves the outliner's (an undo that
    // brings it back does not select it again).
    std::erase_if(impl_->selectedObjects, [this](scenes::ObjectId id) { return impl_->scene.findObject(id) == nullptr; });
    impl_->forgetRemovedBinding();
    impl_->outliner->sync(impl_->scene);
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
    s.undo->setToolTip(s.commands.canUndo() ? withShortcutText(tr("Undo %1").arg(undoStep), "actionUndo") : tr("Nothing to undo"));
    s.redo->setToolTip(s.commands.canRedo() ? withShortcutText(tr("Redo %1").arg(redoStep), "actionRedo") : tr("Nothing to redo"));
    s.status->clearStale();  // what was said was about the document before this change
    setWindowModified(s.modified());
    s.autosave();
    s.forgetRemovedBinding();
    s.outliner->select(s.entries());
    refreshPanel();
  };

  createMenus(outlinerDock, propertiesDock, refreshPanel);


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
  d.deformer.evaluate(d.scene);
  d.deformStatus->setText(deformStatusText(d.deformer.lastStats()));
  d.sceneView->setHighlights(d.controller->highlights());
  d.sceneView->show(d.scene, d.deformer);
  d.askedInputs.reset();  // a new scene: its first change asks for a frame
  d.showingScene = true;
  d.outliner->rebuild(d.scene);
  d.properties->showSelection({});
  d.syncLookActions();
  d.status->say(tr("%1 objects, %2 lattices")
                    .arg(d.scene.objects().size())
                    .arg(d.scene.widgets.widgets(widgets::WidgetType::Lattice).size()));
  d.controller->refresh();
  d.view->requestRender();
}

void MainWindow::Impl::drawFrame() {
  if (!frameDue || !showingScene) return;
  frameDue = false;
  try {
    // During a gesture the objects drawn as proxies at their proxies' points only (pinned objects
    // in full: their pins are drawn from the full mesh).
    scenes::EvaluationRequest request = sceneView->evaluationRequest(scene, deformer);
    for (const ObjectPoint& pin : controller->pins()) {
      request.subsets.erase(pin.object);
      request.followed.erase(pin.object);
    }
    if (deformer.evaluate(scene, request)) ++evaluations;
  } catch (const std::exception& e) {
    // A drag step or an undo whose result cannot be evaluated: said, and tried again at the
    // next change (edits are refused at once: InteractionController::edit).
    sayError(e.what());
    return;
  }
  sceneView->setHighlights(edit->highlights(controller->highlights()));
  sceneView->refresh(scene, deformer);
  const auto& stats = deformer.lastStats();
  // An update with nothing to do (a hover, a selection) keeps the last real deform time.
  if (stats.seconds > 0.0 && stats.deformedPoints > 0 && (stats.seconds >= 1e-5 || stats.reembeddedStages > 0))
    deformStatus->setText(deformStatusText(stats));
}

const scenes::Scene& MainWindow::scene() const { return impl_->scene; }
const scenes::SceneDeformer& MainWindow::deformer() const { return impl_->deformed(); }
std::uint64_t MainWindow::evaluations() const { return impl_->evaluations; }
scenes::CommandStack& MainWindow::commands() const { return impl_->commands; }
InteractionController& MainWindow::controller() const { return *impl_->controller; }
EditController& MainWindow::editController() const { return *impl_->edit; }
SceneView& MainWindow::sceneView() const {
  impl_->drawFrame();  // the view as the next frame draws it
  return *impl_->sceneView;
}
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
      QMessageBox::critical(this, tr("Cannot open"), qs(readErrorText(e.what())));
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
