#pragma once

#include <cstdint>
#include <memory>

#include <QOpenGLWidget>
#include <QSurfaceFormat>

class vtkGenericOpenGLRenderWindow;
class vtkRenderWindowInteractor;
class vtkRenderer;

namespace ffdkit::app {

/// A Qt 6 widget that hosts a VTK render window.
///
/// Debian 12's QVTKOpenGLNativeWidget is built against Qt 5, so this is our own adapter:
/// a QOpenGLWidget owns a vtkGenericOpenGLRenderWindow that renders into the widget's
/// framebuffer (VTK blits to the framebuffer Qt has bound in paintGL), and every Qt input
/// event is translated into the matching VTK interactor event, so interactor styles and
/// picking behave as in a native VTK window.
///
/// Rendering is always done by Qt's paint cycle: the interactor's render requests and
/// requestRender() schedule a repaint instead of rendering immediately.
class VtkViewWidget : public QOpenGLWidget {
  Q_OBJECT

 public:
  explicit VtkViewWidget(QWidget* parent = nullptr);
  ~VtkViewWidget() override;

  /// The surface format VTK's OpenGL2 backend needs (OpenGL 3.2 core, depth buffer).
  /// Call QSurfaceFormat::setDefaultFormat(VtkViewWidget::defaultFormat()) before the
  /// QApplication is created.
  static QSurfaceFormat defaultFormat();

  vtkGenericOpenGLRenderWindow* renderWindow() const;
  vtkRenderWindowInteractor* interactor() const;
  /// The one renderer the widget creates (background and camera of the 3D view).
  vtkRenderer* renderer() const;

  /// Schedules a repaint through Qt that renders a new frame; safe to call from anywhere on the
  /// GUI thread. Whatever changes what the view shows calls it (the interactor's render
  /// requests do): a repaint Qt makes on its own (the window activated, a resize's second
  /// paint) at the last frame's size shows that frame again instead of rendering it anew.
  void requestRender();
  /// Frames VTK rendered (repaints that showed the last frame again are not counted).
  std::uint64_t renders() const;

 signals:
  /// Emitted at the start of every repaint, before VTK renders (or shows its last frame again):
  /// the owner brings the scene up to date here (MainWindow evaluates once per frame).
  void aboutToRender();

 protected:
  void initializeGL() override;
  void resizeGL(int width, int height) override;
  void paintGL() override;

  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;
  void keyReleaseEvent(QKeyEvent* event) override;
  void enterEvent(QEnterEvent* event) override;
  void leaveEvent(QEvent* event) override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ffdkit::app
