#pragma once

// Real Qt events for the GUI tests (Xvfb): mouse events sent to the application's 3D view,
// world points mapped to the view's pixels, and a main() that sets VTK's surface format first.

#include <QApplication>
#include <QMouseEvent>
#include <QSurfaceFormat>
#include <QTest>

#include <cmath>
#include <memory>

#include <Eigen/Core>

#include "ffdkit/app/main_window.h"
#include "ffdkit/app/scene_view.h"
#include "ffdkit/app/vtk_view_widget.h"

namespace ffdkit::app::testing {

inline void sendMouse(QWidget* widget, QEvent::Type type, QPoint at, Qt::MouseButton button, Qt::MouseButtons buttons,
                      Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
  QMouseEvent event(type, QPointF(at), widget->mapToGlobal(QPointF(at)), button, buttons, modifiers);
  QApplication::sendEvent(widget, &event);
}

/// Where the view draws world point p, in the view widget's (logical) coordinates.
inline QPoint toWidget(MainWindow& w, const Eigen::Vector3d& p) {
  const Eigen::Vector2d d = w.sceneView().displayPoint(p);
  const double ratio = w.view()->devicePixelRatioF();
  return QPoint(static_cast<int>(std::lround(d.x() / ratio)),
                static_cast<int>(std::lround((w.view()->height() * ratio - 1.0 - d.y()) / ratio)));
}

inline void click(MainWindow& w, QPoint at, Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
  sendMouse(w.view(), QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::LeftButton, modifiers);
  sendMouse(w.view(), QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton, modifiers);
}

/// The pointer moves over the view with no button down.
inline void hover(MainWindow& w, QPoint at) { sendMouse(w.view(), QEvent::MouseMove, at, Qt::NoButton, Qt::NoButton); }

/// A left-button drag in the view from pixel a to pixel b in ten moves.
inline void dragPixels(MainWindow& w, QPoint a, QPoint b) {
  sendMouse(w.view(), QEvent::MouseButtonPress, a, Qt::LeftButton, Qt::LeftButton);
  for (int step = 1; step <= 10; ++step)
    sendMouse(w.view(), QEvent::MouseMove, a + (b - a) * step / 10, Qt::NoButton, Qt::LeftButton);
  sendMouse(w.view(), QEvent::MouseButtonRelease, b, Qt::LeftButton, Qt::NoButton);
}

/// A left-button drag from where world point `from` is drawn to where `to` is.
inline void dragWorld(MainWindow& w, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  dragPixels(w, toWidget(w, from), toWidget(w, to));
}

/// A shown main window of `size` (if given), exposed, with a first frame drawn (which sizes
/// VTK's window); null if the window system never exposed it.
inline std::unique_ptr<MainWindow> openWindow(QSize size = QSize()) {
  auto window = std::make_unique<MainWindow>();
  if (size.isValid()) window->resize(size);
  window->show();
  if (!QTest::qWaitForWindowExposed(window.get())) return nullptr;
  window->view()->grabFramebuffer();
  return window;
}

/// main() of a GUI test: VTK's surface format before the QApplication, then the Qt Test run.
template <class Test>
int runGuiTest(int argc, char** argv) {
  QSurfaceFormat::setDefaultFormat(VtkViewWidget::defaultFormat());
  QApplication app(argc, argv);
  Test test;
  return QTest::qExec(&test, argc, argv);
}

}  // namespace ffdkit::app::testing
