#pragma once

// The steps of building the thesis's Fig. 6-2 tool by hand in the window (Kuriyama 1996,
// secs. 6.4, 6.5), with real Qt mouse and key events: a new 3 x 3 x 3 lattice, cells made from
// selected points in its edit mode, widgets on them, a transformer turn and typed drags. Shared
// by the edit-mode GUI test and the tutorial's screenshot program (tutorial_screenshots.cpp),
// so the tutorial shows exactly what the test checks.

#include <QDialog>
#include <QMenu>
#include <QMenuBar>

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ffdkit/interaction/edit_controller.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "gui_test_support.h"

namespace ffdkit::app::testing {

/// Flat index of point (i, j, k) of a 3 x 3 x 3 lattice.
inline Eigen::Index flat(int i, int j, int k) { return i + 3 * (j + 3 * k); }

/// Triggers action `name` and answers the dialog it opens with OK (New Lattice: 3 x 3 x 3
/// Bernstein by default); `shown` (if given) sees the dialog first, e.g. to take its picture.
inline void triggerWithDialog(MainWindow& w, const char* name, const std::function<void(QDialog*)>& shown = {}) {
  bool seen = false;
  QTimer::singleShot(0, [&] {
    auto* dialog = qobject_cast<QDialog*>(QApplication::activeModalWidget());
    if (dialog == nullptr) return;
    seen = true;
    if (shown) shown(dialog);
    dialog->accept();
  });
  action(w, name)->trigger();
  QVERIFY2(seen, name);
}

/// An oblique view of the unit box in which no two of its 27 grid points share a pixel.
inline void lookAtUnitBox(MainWindow& w) {
  scenes::Camera camera;
  camera.focalPoint = {0.5, 0.5, 0.5};
  camera.position = camera.focalPoint + 1.6 * Eigen::Vector3d(2.0, -3.2, 1.6);
  w.sceneView().applyCamera(camera);
  w.view()->grabFramebuffer();
}

/// A new 3 x 3 x 3 lattice (Widgets > New Lattice), seen from lookAtUnitBox, in edit mode (Tab).
inline widgets::WidgetId newLatticeInEditMode(MainWindow& w, const std::function<void(QDialog*)>& dialogShown = {}) {
  triggerWithDialog(w, "actionNewLattice", dialogShown);
  const widgets::WidgetId lattice = w.scene().widgets.roots().front();
  lookAtUnitBox(w);
  pressKey(w, Qt::Key_Tab);
  return lattice;
}

/// Clicks lattice point `index` of `lattice` in the view.
inline void clickPoint(MainWindow& w, widgets::WidgetId lattice, Eigen::Index index,
                       Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
  click(w, toWidget(w, w.scene().widgets.worldControlPoints(lattice).row(index).transpose()), modifiers);
}

/// Types `text` (digits, '.', '-') on the view, key by key.
inline void typeKeys(MainWindow& w, const std::string& text) {
  for (char c : text) {
    const Qt::Key key = c == '.' ? Qt::Key_Period : c == '-' ? Qt::Key_Minus : static_cast<Qt::Key>(Qt::Key_0 + (c - '0'));
    pressKey(w, key);
  }
}

/// In edit mode: selects exactly `points` (Alt+A, then Shift+click each); false if a click missed.
inline bool selectPoints(MainWindow& w, widgets::WidgetId lattice, const std::vector<Eigen::Index>& points) {
  pressKey(w, Qt::Key_A, Qt::AltModifier);
  for (Eigen::Index p : points) clickPoint(w, lattice, p, Qt::ShiftModifier);
  return w.editController().points().count() == static_cast<Eigen::Index>(points.size());
}

/// In edit mode, with points selected: Ctrl+M makes them a cell, then action `addWidget`
/// (Widgets > Add Rotate Widget, ...) puts a widget on it. The new widget, or an invalid id.
inline widgets::WidgetId makeCellWithWidget(MainWindow& w, const char* addWidget) {
  const std::size_t before = w.scene().widgets.widgets(widgets::WidgetType::Affine).size();
  pressKey(w, Qt::Key_M, Qt::ControlModifier);
  action(w, addWidget)->trigger();
  const auto affines = w.scene().widgets.widgets(widgets::WidgetType::Affine);
  return affines.size() == before + 1 ? affines.back() : widgets::WidgetId();
}

/// Selects translate widget `arrow` and turns it with its transformer's y ring by a typed
/// `degrees` (the ring pressed, dragged a little, the value typed, Return, released).
/// `whileTyped` (if given) runs with the value typed and the button still down.
inline void turnWithTransformerRingY(MainWindow& w, widgets::WidgetId arrow, const std::string& degrees,
                                     const std::function<void()>& whileTyped = {}) {
  w.selectWidget(w.scene().widgets.name(arrow));
  w.view()->grabFramebuffer();
  QVERIFY(w.controller().transformer().has_value());
  const Transformer t = *w.controller().transformer();
  const Eigen::Vector3d o = t.frame.translation();
  const Eigen::Vector3d tx = t.frame.linear().col(0), tz = t.frame.linear().col(2);
  const double r = TransformerLayout::turnRadius * t.size;
  const double a = 0.6;
  const QPoint ringAt = toWidget(w, o + r * (std::cos(a) * tz + std::sin(a) * tx));
  const QPoint ringTo = toWidget(w, o + r * (std::cos(a + 0.2) * tz + std::sin(a + 0.2) * tx));
  sendMouse(w.view(), QEvent::MouseButtonPress, ringAt, Qt::LeftButton, Qt::LeftButton);
  QCOMPARE(w.controller().transformerHandle(), std::optional(TransformerHandle::TurnY));
  sendMouse(w.view(), QEvent::MouseMove, ringTo, Qt::NoButton, Qt::LeftButton);
  typeKeys(w, degrees);
  if (whileTyped) whileTyped();
  pressKey(w, Qt::Key_Return);
  sendMouse(w.view(), QEvent::MouseButtonRelease, ringTo, Qt::LeftButton, Qt::NoButton);
}

/// Drags affine widget `widget` by its glyph (a translate widget's arrow, a rotate widget's
/// ring) with `amount` typed while the button is down (a distance, or degrees for a ring);
/// `whileTyped` (if given) runs with the value typed and the button still down.
inline void dragTyped(MainWindow& w, widgets::WidgetId widget, const std::string& amount,
                      const std::function<void()>& whileTyped = {}) {
  const auto& m = w.scene().widgets;
  const widgets::WidgetFrame f = m.affineFrame(widget);
  const bool turn = m.affineKind(widget) == widgets::AffineKind::Rotate;
  const Eigen::Vector3d grab = f.frame * (turn ? Eigen::Vector3d(0, f.size, 0) : Eigen::Vector3d(0.6 * f.size, 0, 0));
  const Eigen::Vector3d moved = f.frame * (turn ? Eigen::Vector3d(-0.3 * f.size, f.size, 0) : Eigen::Vector3d(0.9 * f.size, 0, 0));
  w.controller().clearSelection();
  sendMouse(w.view(), QEvent::MouseButtonPress, toWidget(w, grab), Qt::LeftButton, Qt::LeftButton);
  QCOMPARE(w.controller().selection(), std::vector{widget});
  sendMouse(w.view(), QEvent::MouseMove, toWidget(w, moved), Qt::NoButton, Qt::LeftButton);
  typeKeys(w, amount);
  sendMouse(w.view(), QEvent::MouseMove, toWidget(w, grab), Qt::NoButton, Qt::LeftButton);  // the typed value rules
  if (whileTyped) whileTyped();
  sendMouse(w.view(), QEvent::MouseButtonRelease, toWidget(w, grab), Qt::LeftButton, Qt::NoButton);
}

/// Fig. 6-2's cells, as flat indices of the 3 x 3 x 3 lattice: the face (0..1, 0..1, 2), the
/// edge (0..1, 2, 0) and the point (2, 2, 0).
inline std::vector<Eigen::Index> fig62FacePoints() { return {flat(0, 0, 2), flat(1, 0, 2), flat(0, 1, 2), flat(1, 1, 2)}; }
inline std::vector<Eigen::Index> fig62EdgePoints() { return {flat(0, 2, 0), flat(1, 2, 0)}; }
inline std::vector<Eigen::Index> fig62PointPoints() { return {flat(2, 2, 0)}; }

}  // namespace ffdkit::app::testing
