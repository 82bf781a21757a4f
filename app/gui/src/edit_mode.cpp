#include "edit_mode.h"

#include <QActionGroup>
#include <QApplication>
#include <QKeyEvent>
#include <QMenuBar>
#include <QMessageBox>
#include <QMouseEvent>
#include <QSignalBlocker>
#include <QStatusBar>
#include <QWheelEvent>

#include "keyboard_shortcuts.h"

#include <cmath>
#include <numbers>

namespace ffdkit::app {

namespace {

/// Places the box selection's band. It is a native window above the view's (VtkViewWidget), which
/// it cannot show through: a mask keeps only its outline.
void placeBand(QRubberBand* band, const QRect& box) {
  band->setGeometry(box);
  constexpr int kOutline = 2;
  const QRect whole(QPoint(), box.size());
  const QRect inside = whole.adjusted(kOutline, kOutline, -kOutline, -kOutline);
  band->setMask(inside.isEmpty() ? QRegion(whole) : QRegion(whole) - inside);
}

QString qs(const std::string& s) { return QString::fromStdString(s); }

// The axis constraint an X / Y / Z key (Shift: excluded) sets while transforming, or nullopt
// (the keys from keyboard_shortcuts.cpp).
std::optional<std::pair<int, bool>> axisKey(const QKeyEvent& e) {
  for (int axis = 0; axis < 3; ++axis)
    for (bool exclude : {false, true}) {
      const std::string name = std::string(exclude ? "excludeAxis" : "constrainAxis") + "XYZ"[axis];
      if (matchesShortcut(e, name)) return std::pair(axis, exclude);
    }
  return std::nullopt;
}

// The character a key types into a value ("0.5", "-90", "0.1,0,0.2"), or 0.
char typedChar(const QKeyEvent* e) {
  const int key = e->key();
  if (key >= Qt::Key_0 && key <= Qt::Key_9) return static_cast<char>('0' + (key - Qt::Key_0));
  if (key == Qt::Key_Period) return '.';
  if (key == Qt::Key_Minus) return '-';
  if (key == Qt::Key_Comma) return ',';
  return 0;
}

bool isConfirm(const QKeyEvent& e) { return matchesShortcut(e, "confirmTransform") || e.key() == Qt::Key_Enter; }

bool isRadiusKey(const QKeyEvent& e) {
  return matchesShortcut(e, "softRadiusUp") || matchesShortcut(e, "softRadiusDown");
}

bool isModalKey(const QKeyEvent* e) {
  return typedChar(e) != 0 || axisKey(*e) || matchesShortcut(*e, "typedBackspace") || isConfirm(*e) ||
         matchesShortcut(*e, "cancelDrag") || isRadiusKey(*e);
}

// The soft selection's radius changes by this factor per wheel notch or PageUp / PageDown
// (Blender's step).
constexpr double kRadiusStep = 1.1;

}  // namespace

EditModeInput::EditModeInput(Parts parts, QMenu* widgetsMenu, QToolBar* toolbar)
    : QObject(parts.window), p_(std::move(parts)) {
  using widgets::CellKind;
  p_.edit->onChanged = [this] { changed(); };

  editAction_ = addAction(widgetsMenu, tr("&Edit Lattice Points"), "actionEditMode", true, {});
  editAction_->setCheckable(true);
  editAction_->setToolTip(tr("Edit the selected lattice's points: select, move, turn, size, make cells"));
  connect(editAction_, &QAction::triggered, this, [this](bool on) { toggleEditMode(on); });
  toolbar->addAction(editAction_);

  // Make Cell: from the selected points (Widgets menu and the view's context menu).
  cellMenu_ = widgetsMenu->addMenu(tr("Make &Cell"));
  cellMenu_->setObjectName("menuMakeCell");
  addAction(cellMenu_, tr("From Selection"), "actionMakeCell", true, [this] { makeCell(std::nullopt); });
  cellMenu_->addSeparator();
  const std::pair<const char*, CellKind> kinds[] = {{"actionMakeCellPoint", CellKind::Point}, {"actionMakeCellEdge", CellKind::Edge},
                                                    {"actionMakeCellFace", CellKind::Face},   {"actionMakeCellSlab", CellKind::Slab},
                                                    {"actionMakeCellBox", CellKind::Box},     {"actionMakeCellCustom", CellKind::Custom}};
  for (const auto& [name, kind] : kinds) {
    const CellKind k = kind;
    QString text = qs(std::string(widgets::cellKindName(kind)));
    text[0] = text[0].toUpper();
    addAction(cellMenu_, text, name, false, [this, k] { makeCell(k); });
  }

  // Selection and transforms of the edit mode (keys on the view, as in Blender).
  selectMenu_ = p_.window->menuBar()->addMenu(tr("&Select"));
  selectMenu_->setObjectName("menuSelect");
  auto needEditing = [this] {
    if (!p_.edit->editing()) throw std::invalid_argument("press Tab to edit a lattice's points first");
  };
  addAction(selectMenu_, tr("&All"), "actionSelectAll", true, [this, needEditing] {
    needEditing();
    p_.edit->selectAll();
  });
  addAction(selectMenu_, tr("&None"), "actionSelectNone", true, [this, needEditing] {
    needEditing();
    p_.edit->selectNone();
  });
  addAction(selectMenu_, tr("&Invert"), "actionSelectInvert", true, [this, needEditing] {
    needEditing();
    p_.edit->invert();
  });
  addAction(selectMenu_, tr("&Box Select"), "actionBoxSelect", true, [this, needEditing] {
    needEditing();
    boxArmed_ = true;
    p_.status->say(tr("Box select: drag a rectangle (Shift adds, Ctrl removes)"));
  });
  QMenu* linked = selectMenu_->addMenu(tr("&Linked"));
  for (int axis = 0; axis < 3; ++axis)
    for (bool plane : {false, true}) {
      const QString text = plane ? tr("Planes %1 = const").arg(QChar("ijk"[axis])) : tr("Rows along %1").arg(QChar("ijk"[axis]));
      const std::string name = std::string(plane ? "actionSelectPlanes" : "actionSelectRows") + "ijk"[axis];
      QAction* a = addAction(linked, text, "", false, [this, needEditing, axis, plane] {
        needEditing();
        p_.edit->selectLinked(axis, plane);
      });
      a->setObjectName(QString::fromStdString(name));
    }
  selectMenu_->addSeparator();
  addAction(selectMenu_, tr("&Move"), "actionMoveSelection", true, [this] { beginModal(TransformMode::Move); });
  addAction(selectMenu_, tr("&Rotate"), "actionRotateSelection", true, [this] { beginModal(TransformMode::Rotate); });
  addAction(selectMenu_, tr("&Scale"), "actionScaleSelection", true, [this] { beginModal(TransformMode::Scale); });
  QMenu* pivot = selectMenu_->addMenu(tr("&Pivot"));
  auto* pivots = new QActionGroup(this);
  const std::tuple<const char*, QString, PivotChoice> choices[] = {
      {"actionPivotMedian", tr("&Median Point"), PivotChoice::Median},
      {"actionPivotActive", tr("&Active Point"), PivotChoice::Active},
      {"actionPivotIndividual", tr("&Individual Origins"), PivotChoice::Individual}};
  for (const auto& [name, text, choice] : choices) {
    const PivotChoice c = choice;
    QAction* a = addAction(pivot, text, name, false, [this, c] { p_.edit->setPivot(c); });
    a->setCheckable(true);
    a->setChecked(c == PivotChoice::Median);
    pivots->addAction(a);
  }
  // Mirror editing across the edited lattice's mid-plane normal to an index axis.
  QMenu* mirror = selectMenu_->addMenu(tr("Mi&rror"));
  mirror->setObjectName("menuMirror");
  auto* mirrors = new QActionGroup(this);
  for (int axis = -1; axis < 3; ++axis) {
    const QString text = axis < 0 ? tr("&Off") : tr("Across the Mid-Plane of &%1").arg(QChar("ijk"[axis]));
    const std::string name = axis < 0 ? std::string("actionMirrorOff") : std::string("actionMirror") + "ijk"[axis];
    QAction* a = addAction(mirror, text, "", false, [this, axis] {
      p_.edit->setMirror(axis < 0 ? std::nullopt : std::optional(axis));
      if (axis >= 0)
        p_.status->say(tr("Mirror editing: a selected point's image across the %1 mid-plane moves with it").arg(QChar("ijk"[axis])),
                       5000);
    });
    a->setObjectName(QString::fromStdString(name));
    a->setCheckable(true);
    a->setChecked(axis < 0);
    mirrors->addAction(a);
  }

  addSoftSelectionActions(selectMenu_);
  addShapeGuardActions(widgetsMenu);

  count_ = new QLabel;
  count_->setObjectName("editCount");
  count_->hide();
  p_.window->statusBar()->addPermanentWidget(count_);
  band_ = new QRubberBand(QRubberBand::Rectangle, p_.view);
  // The view shows its frames in a native child window, which covers plain child widgets: the
  // band is a native window of its own, stacked above it (raised when shown), and leaves the
  // view's ancestors as they are (placeBand).
  band_->setAttribute(Qt::WA_DontCreateNativeAncestors);
  band_->setAttribute(Qt::WA_NativeWindow);
  p_.view->installEventFilter(this);  // after the window's filter: this one sees events first
}

QAction* EditModeInput::addAction(QMenu* menu, const QString& text, const char* name, bool viewKeys,
                                  std::function<void()> slot) {
  QAction* a = menu->addAction(text);
  a->setObjectName(name);
  if (viewKeys) {
    // Its keys (keyboard_shortcuts.cpp) act in the 3D view only: a text field keeps its letters and Tab.
    a->setShortcutContext(Qt::WidgetShortcut);
    p_.view->addAction(a);
    viewActions_.push_back(a);
  }
  if (slot)
    connect(a, &QAction::triggered, this, [this, slot] {
      try {
        slot();
      } catch (const std::exception& e) {
        p_.sayError(e.what());
        QApplication::beep();
      }
    });
  return a;
}

QAction* EditModeInput::viewActionFor(const QKeyEvent& e) const {
  for (QAction* a : viewActions_)
    if (a->isEnabled() && matchesShortcut(e, a->objectName().toStdString())) return a;
  return nullptr;
}

void EditModeInput::leave() {
  boxFrom_.reset();
  band_->hide();
  p_.edit->exit();
  editAction_->setChecked(false);
}

void EditModeInput::toggleEditMode(bool on) {
  if (!on) {
    p_.edit->exit();
    p_.status->say(tr("Edit mode off"), 3000);
    return;
  }
  try {
    // The lattice of the selection (a lattice, or the lattice of a cell or widget), else the only one.
    const auto& m = p_.scene->widgets;
    std::optional<widgets::WidgetId> lattice;
    for (widgets::WidgetId w : p_.controller->selection()) {
      if (!m.contains(w)) continue;
      if (m.type(w) == widgets::WidgetType::Lattice) lattice = w;
      else if (m.type(w) == widgets::WidgetType::Cell || m.attachedCell(w)) lattice = m.latticeOf(w);
      if (lattice) break;
    }
    const auto all = m.widgets(widgets::WidgetType::Lattice);
    if (!lattice && all.size() == 1) lattice = all.front();
    if (!lattice) throw std::invalid_argument(all.empty() ? "add a lattice first (Widgets > New Lattice)"
                                                          : "select the lattice whose points to edit");
    entering_ = true;  // the toggle is checked before the mode begins
    p_.controller->clearSelection();  // the lattice's own highlight would hide the selected points
    p_.edit->enter(*lattice);
    entering_ = false;
    p_.status->say(tr("Editing the points of '%1': click, Shift+click, drag a box (Alt+drag orbits); "
                      "G / R / S move, turn, size; Tab leaves")
                       .arg(qs(m.name(*lattice))));
  } catch (const std::exception& e) {
    entering_ = false;
    const QSignalBlocker block(editAction_);
    editAction_->setChecked(false);
    p_.sayError(e.what());
    QApplication::beep();
  }
}

Eigen::Vector3d EditModeInput::viewDirection() const {
  const scenes::Camera camera = p_.sceneView->camera();
  return (camera.focalPoint - camera.position).normalized();
}

void EditModeInput::beginModal(TransformMode mode) {
  if (!havePos_) lastPos_ = QPoint(p_.view->width() / 2, p_.view->height() / 2);
  p_.edit->beginModal(mode, p_.rayAt(lastPos_), viewDirection());
  p_.view->setFocus();
}

void EditModeInput::makeCell(std::optional<widgets::CellKind> kind) {
  if (!p_.edit->editing()) throw std::invalid_argument("press Tab to edit a lattice's points, select some, then Make Cell");
  CellFromSelection cell = p_.edit->cellFor(kind);
  if (!cell.spec) {
    if (kind || p_.edit->points().empty()) throw std::invalid_argument(cell.why);
    // Anything else is a custom cell: asked, not assumed.
    const auto answer = QMessageBox::question(
        p_.window, tr("Make Cell"),
        tr("The %1 selected points are no point, edge, face, slab or box. Make a custom cell of them?")
            .arg(p_.edit->points().count()));
    if (answer != QMessageBox::Yes) return;
    cell = p_.edit->cellFor(widgets::CellKind::Custom);
  }
  const widgets::WidgetId id = p_.edit->makeCell(*cell.spec);
  p_.status->say(tr("Made %1 cell '%2': add a translate, rotate or scale widget to it (Widgets menu)")
                     .arg(qs(std::string(widgets::cellKindName(cell.spec->kind))), qs(p_.scene->widgets.name(id))),
                 8000);
}

bool EditModeInput::typeIntoDrag(const QKeyEvent* e) {
  // The drag of a transformer handle of this object's (the edit mode's points or a group), else
  // the InteractionController's (a glyph or one widget's transformer handle).
  InteractionController& c = *p_.controller;
  EditController& edit = *p_.edit;
  const std::optional<TransformerHandle> ownHandle = edit.draggedHandle();
  if (isConfirm(*e)) {
    dragTyped_.clear();
    if (ownHandle) edit.confirm();
    else c.release();
    return true;
  }
  if (matchesShortcut(*e, "typedBackspace")) {
    dragTyped_.backspace();
  } else if (const char ch = typedChar(e)) {
    dragTyped_.type(ch);
  } else {
    return false;
  }
  const auto typed = dragTyped_.components();
  if (!typed) return true;
  const double v = (*typed)[0];
  // Designer's units: degrees for a turn, a factor for a size; the model's: rad, log factor
  // (an affine scale widget) or the factor (a transformer's size handle).
  double value = v;
  QString unit;
  const std::optional<TransformerHandle> handle =
      ownHandle ? ownHandle : c.handleDragValue() ? c.transformerHandle() : std::nullopt;
  if (handle) {
    const int group = static_cast<int>(*handle) / 3;
    if (group == 1) value = v * std::numbers::pi / 180.0, unit = QStringLiteral("°");
    if (group == 2) unit = QStringLiteral("x");
  } else if (const auto widget = p_.scene->widgets.gestureWidget();
             widget && p_.scene->widgets.type(*widget) == widgets::WidgetType::Affine) {
    const widgets::AffineKind kind = p_.scene->widgets.affineKind(*widget);
    if (kind == widgets::AffineKind::Rotate) value = v * std::numbers::pi / 180.0, unit = QStringLiteral("°");
    if (kind == widgets::AffineKind::Scale) {
      if (!(v > 0.0)) return true;
      value = std::log(v);
      unit = QStringLiteral("x");
    }
  }
  if (ownHandle ? edit.setDragValue(value) : c.setDragValue(value))
    p_.status->say(tr("typed %1%2 (Enter or release confirms, Backspace edits, Esc cancels)").arg(qs(dragTyped_.text()), unit));
  return true;
}

void EditModeInput::syncEditToggle() {
  syncKeepActions();  // the outliner's selection or the objects may have changed
  // An undo (or any edit) that removes or resizes the edited lattice ends the mode: the toggle
  // follows, and the mode is left for good (a redo does not bring back a stale selection).
  if (entering_ || p_.edit->editing() || !editAction_->isChecked()) return;
  {
    const QSignalBlocker block(editAction_);
    editAction_->setChecked(false);
  }
  boxFrom_.reset();
  boxArmed_ = false;
  band_->hide();
  p_.edit->exit();
  p_.status->say(tr("Edit mode off: the edited lattice was removed or resized"), 5000);
}

void EditModeInput::changed() {
  syncEditToggle();
  if (p_.edit->editing()) {
    const PointSelection& s = p_.edit->points();
    count_->setText(tr("%1: %2 of %3 points selected")
                        .arg(qs(p_.scene->widgets.name(s.lattice())))
                        .arg(s.count())
                        .arg(s.pointCount()));
    count_->show();
  } else {
    count_->hide();
  }
  syncKeepActions();
  if (p_.showProperties) p_.showProperties();
  if (p_.edit->transforming()) {
    QString text = qs(p_.edit->describe());
    if (const QString guard = guardText(); !guard.isEmpty()) text += " · " + guard;
    p_.status->say(text);
  }
  p_.redraw();
}

void EditModeInput::finishBox(const QPoint& end, Qt::KeyboardModifiers modifiers) {
  const QPoint from = *boxFrom_;
  boxFrom_.reset();
  boxArmed_ = false;
  band_->hide();
  const SelectMode mode = (modifiers & Qt::ShiftModifier)     ? SelectMode::Add
                          : (modifiers & Qt::ControlModifier) ? SelectMode::Subtract
                                                              : SelectMode::Replace;
  if ((end - from).manhattanLength() < 4) {
    // A click on empty space: nothing selected (a Shift or Ctrl click keeps the selection).
    if (mode == SelectMode::Replace) p_.edit->selectNone();
    return;
  }
  // The points' pixels (VTK display coordinates), those in front of the camera only.
  const double ratio = p_.view->devicePixelRatioF();
  const double h = p_.view->height() * ratio;
  auto display = [&](const QPoint& q) { return Eigen::Vector2d(q.x() * ratio, h - q.y() * ratio - 1.0); };
  const Eigen::MatrixX3d world = p_.edit->worldPoints();
  const scenes::Camera camera = p_.sceneView->camera();
  const Eigen::Vector3d forward = camera.focalPoint - camera.position;
  Eigen::MatrixX2d screen(world.rows(), 2);
  for (Eigen::Index i = 0; i < world.rows(); ++i) {
    const Eigen::Vector3d q = world.row(i).transpose();
    screen.row(i) = (q - camera.position).dot(forward) > 0.0 ? p_.sceneView->displayPoint(q).transpose()
                                                             : Eigen::RowVector2d(-1e9, -1e9);
  }
  p_.edit->pickMany(pointsInRectangle(screen, display(from), display(end)), mode);
}

bool EditModeInput::eventFilter(QObject* watched, QEvent* event) {
  if (watched != p_.view) return false;
  EditController& edit = *p_.edit;
  try {
    switch (event->type()) {
      case QEvent::ShortcutOverride: {
        // While transforming, X / Y / Z, digits, Enter and Escape belong to the transform; in the
        // view, this object's keys are its own (over a menu's Alt mnemonic or a window key).
        auto* e = static_cast<QKeyEvent*>(event);
        const bool busy = edit.transforming() || p_.controller->dragging();
        if ((busy && isModalKey(e)) || (!busy && viewActionFor(*e))) {
          e->accept();
          return true;
        }
        return false;
      }
      case QEvent::KeyPress: {
        auto* e = static_cast<QKeyEvent*>(event);
        if (!edit.transforming() && !p_.controller->dragging())
          if (QAction* a = viewActionFor(*e)) {
            a->trigger();
            return true;
          }
        if (!edit.transforming() && p_.controller->dragging()) {
          if (matchesShortcut(*e, "cancelDrag")) dragTyped_.clear();
          return typeIntoDrag(e);
        }
        if (!edit.transforming()) {
          if (matchesShortcut(*e, "cancelDrag") && boxFrom_) {
            boxFrom_.reset();
            band_->hide();
            return true;
          }
          return false;
        }
        const bool snap = QApplication::keyboardModifiers() & Qt::ControlModifier;
        if (matchesShortcut(*e, "cancelDrag")) {
          dragTyped_.clear();
          edit.cancel();
          p_.status->say(tr("Transform cancelled"), 3000);
        } else if (isRadiusKey(*e)) {
          if (edit.softSelection().enabled)
            scaleSoftRadius(matchesShortcut(*e, "softRadiusUp") ? kRadiusStep : 1.0 / kRadiusStep);
        } else if (edit.draggedHandle()) {
          typeIntoDrag(e);  // a typed amount of the handle (the pointer no longer moves it)
        } else if (isConfirm(*e)) {
          edit.confirm();
        } else if (ModalTransform* modal = edit.modal()) {
          if (const auto axis = axisKey(*e)) {
            modal->setConstraint(modal->constraint().pressed(axis->first, axis->second));
          } else if (matchesShortcut(*e, "typedBackspace")) {
            modal->typed().backspace();
          } else if (const char c = typedChar(e)) {
            modal->typed().type(c);
          }
          edit.update(p_.rayAt(lastPos_), snap);
        }
        return true;
      }
      case QEvent::Wheel: {
        // During G / R / S with soft selection the wheel sets its radius (towards the user: larger,
        // as in Blender); otherwise it is the camera's.
        if (!edit.transforming() || !edit.softSelection().enabled) return false;
        const int notches = static_cast<QWheelEvent*>(event)->angleDelta().y() / 120;
        if (notches != 0) scaleSoftRadius(std::pow(kRadiusStep, -notches));
        return true;
      }
      case QEvent::MouseMove: {
        auto* e = static_cast<QMouseEvent*>(event);
        lastPos_ = e->position().toPoint();
        havePos_ = true;
        const bool snap = e->modifiers() & Qt::ControlModifier;
        if (edit.transforming()) {
          edit.update(p_.rayAt(lastPos_), snap);
          return true;
        }
        if (p_.controller->dragging() && !dragTyped_.empty()) return true;  // the typed value rules
        if (boxFrom_) {
          placeBand(band_, QRect(*boxFrom_, lastPos_).normalized());
          return true;
        }
        if (e->buttons() == Qt::NoButton) edit.hover(p_.rayAt(lastPos_), p_.tolerance());
        return false;
      }
      case QEvent::MouseButtonPress: {
        auto* e = static_cast<QMouseEvent*>(event);
        const QPoint at = e->position().toPoint();
        lastPos_ = at;
        havePos_ = true;
        dragTyped_.clear();
        if (edit.modal()) {
          // A click confirms a modal transform; a right click cancels it.
          if (e->button() == Qt::RightButton) edit.cancel();
          else edit.confirm();
          return true;
        }
        if (e->button() == Qt::RightButton && edit.editing()) rightAt_ = at;
        if (e->button() != Qt::LeftButton || (e->modifiers() & Qt::AltModifier)) return false;
        const widgets::Ray ray = p_.rayAt(at);
        if (!edit.editing()) {
          // Two or more widgets: their group transformer's handles, unless a glyph is under the pointer.
          widgets::PickOptions options;
          options.tolerance = p_.tolerance();
          if (edit.transformer() && !p_.scene->widgets.pick(ray, options) && edit.pressHandle(ray, p_.tolerance()))
            return true;
          return false;
        }
        if (!boxArmed_) {
          // The points first (small targets, the point of the mode), then the transformer's handles.
          const SelectMode mode = (e->modifiers() & Qt::ShiftModifier)     ? SelectMode::Toggle
                                  : (e->modifiers() & Qt::ControlModifier) ? SelectMode::Subtract
                                                                           : SelectMode::Replace;
          if (edit.click(ray, p_.tolerance(), mode)) return true;
          if (edit.pressHandle(ray, p_.tolerance())) return true;
        }
        boxFrom_ = at;
        placeBand(band_, QRect(at, QSize()));
        band_->show();
        return true;
      }
      case QEvent::MouseButtonRelease: {
        auto* e = static_cast<QMouseEvent*>(event);
        const QPoint at = e->position().toPoint();
        if (e->button() == Qt::LeftButton) dragTyped_.clear();
        if (e->button() == Qt::RightButton && rightAt_) {
          const bool click = (at - *rightAt_).manhattanLength() < 4;
          rightAt_.reset();
          if (click && edit.editing()) {
            // The context menu: Make Cell and the selection.
            auto* menu = new QMenu(p_.view);
            menu->setObjectName("editContextMenu");
            menu->setAttribute(Qt::WA_DeleteOnClose);
            menu->addMenu(cellMenu_);
            menu->addSeparator();
            for (const char* name : {"actionSelectAll", "actionSelectNone", "actionSelectInvert"})
              menu->addAction(p_.window->findChild<QAction*>(name));
            menu->popup(p_.view->mapToGlobal(at));
          }
          return false;
        }
        if (e->button() != Qt::LeftButton) return false;
        if (edit.transforming() && !edit.modal()) {
          edit.confirm();
          return true;
        }
        if (boxFrom_) {
          finishBox(at, e->modifiers());
          return true;
        }
        return edit.editing() && !(e->modifiers() & Qt::AltModifier);
      }
      default: break;
    }
  } catch (const std::exception& e) {
    p_.sayError(e.what());
    return true;
  }
  return false;
}

}  // namespace ffdkit::app
