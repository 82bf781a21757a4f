#pragma once

#include <cstdint>
#include <memory>

#include <QEvent>
#include <QImage>
#include <QSurfaceFormat>
#include <QWidget>

class vtkGenericOpenGLRenderWindow;
class vtkRenderWindowInteractor;
class vtkRenderer;

namespace ffdkit::app {

/// A Qt 6 widget that hosts a VTK render window.
///
/// Debian 12's QVTKOpenGLNativeWidget is built against Qt 5, so this is our own adapter: VTK
/// renders with a vtkGenericOpenGLRenderWindow into a native child window of the widget (a
/// QWindow with an OpenGL context of its own, in a window container), which shows each frame by
/// swapping its own buffers: the rest of the main window stays raster-painted and is not
/// composed through OpenGL on every frame. The child window is transparent for input: every Qt
/// input event reaches this widget, which translates it into the matching VTK interactor event,
/// so interactor styles and picking behave as in a native VTK window.
///
/// Rendering is always deferred to the event loop: the interactor's render requests and
/// requestRender() schedule one frame for the next pass of the event loop.
class VtkViewWidget : public QWidget {
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

  /// Schedules a new frame for the next pass of the event loop (one frame however many asked);
  /// safe to call from anywhere on the GUI thread. Whatever changes what the view shows calls it
  /// (the interactor's render requests do): when the window system shows the view again (it was
  /// uncovered, or resized to the last frame's size) it shows the last frame instead of
  /// rendering it anew.
  void requestRender();
  /// Frames VTK rendered (showing the last frame again is not counted).
  std::uint64_t renders() const;
  /// The type of the event the widget posts to itself for a frame (the pass that emits
  /// aboutToRender): what a tool that times frames watches for, as it would a paint event.
  static QEvent::Type frameEventType();

  /// The view's current image (device pixels, opaque): renders first if a frame is due, as the
  /// next pass of the event loop would. Null if no OpenGL context could be made.
  QImage grabFramebuffer();

 signals:
  /// Emitted at the start of every repaint, before VTK renders (or shows its last frame again):
  /// the owner brings the scene up to date here (MainWindow evaluates once per frame).
  void aboutToRender();
  /// A frame was handed to the window system (the child window's buffers swapped).
  void frameSwapped();

 protected:
  bool event(QEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;
  void paintEvent(QPaintEvent* event) override;

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
