#include "ffdkit/viewhost/vtk_view_widget.h"

#include <QBackingStore>
#include <QCoreApplication>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QPaintEngine>
#include <QPainter>
#include <QWheelEvent>
#include <QWindow>

#include <cstring>
#include <functional>
#include <utility>

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkGenericRenderWindowInteractor.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkRenderer.h>

namespace ffdkit::app {
namespace {


// VTK key symbols (X11 keysym names) for the keys interactor styles listen to.
const char* keySymbol(int key) {
  switch (key) {
    case Qt::Key_Left: return "Left";
    case Qt::Key_Right: return "Right";
    case Qt::Key_Up: return "Up";
    case Qt::Key_Down: return "Down";
    case Qt::Key_Return: return "Return";
    case Qt::Key_Enter: return "KP_Enter";
    case Qt::Key_Escape: return "Escape";
    case Qt::Key_Delete: return "Delete";
    case Qt::Key_Backspace: return "BackSpace";
    case Qt::Key_Tab: return "Tab";
    case Qt::Key_Space: return "space";
    case Qt::Key_Home: return "Home";
    case Qt::Key_End: return "End";
    case Qt::Key_PageUp: return "Prior";
    case Qt::Key_PageDown: return "Next";
    case Qt::Key_Shift: return "Shift_L";
    case Qt::Key_Control: return "Control_L";
    case Qt::Key_Alt: return "Alt_L";
    case Qt::Key_Plus: return "plus";
    case Qt::Key_Minus: return "minus";
    default: return nullptr;
  }
}

/// The event that draws the frames asked for since the last one (posted once per pass).
const QEvent::Type kFrameEvent = static_cast<QEvent::Type>(QEvent::registerEventType());

/// The native window VTK renders into: transparent for input (the view widget gets every
/// event), never focused; it reports when the window system shows it.
class ViewSurface : public QWindow {
 public:
  explicit ViewSurface(std::function<void()> exposed) : exposed_(std::move(exposed)) {
    setSurfaceType(QSurface::OpenGLSurface);
    setFlags(Qt::WindowTransparentForInput | Qt::WindowDoesNotAcceptFocus);
    // No alpha in the window: a compositing desktop would blend the view with what lies behind
    // it where VTK leaves the background's alpha below 1.
    QSurfaceFormat format = VtkViewWidget::defaultFormat();
    format.setAlphaBufferSize(0);
    setFormat(format);
  }

 protected:
  void exposeEvent(QExposeEvent*) override {
    if (isExposed()) exposed_();
  }

 private:
  std::function<void()> exposed_;
};

/// A paint that goes to an image of the widget (QWidget::grab, QWidget::render) rather than to
/// its window's backing store, on which the native child window lies.
bool paintsAnImage(const QWidget& widget, QPainter& painter) {
  const QPaintDevice* target = painter.paintEngine() != nullptr ? painter.paintEngine()->paintDevice() : nullptr;
  QBackingStore* store = widget.backingStore();
  return target != nullptr && (store == nullptr || target != store->paintDevice());
}

}  // namespace

struct VtkViewWidget::Impl {
  explicit Impl(VtkViewWidget& owner) : widget(owner) {}

  VtkViewWidget& widget;
  /// Made on the first frame; declared before VTK's objects, which release their resources in it.
  std::unique_ptr<QOpenGLContext> context;
  bool contextFailed = false;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkGenericRenderWindowInteractor> interactor;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  vtkNew<vtkCallbackCommand> makeCurrent;
  vtkNew<vtkCallbackCommand> isCurrent;
  vtkNew<vtkCallbackCommand> renderRequest;
  ViewSurface* surface = nullptr;  // owned by the container
  QWidget* container = nullptr;    // a child of the widget
  /// Whether something asked for a frame (requestRender) since VTK last rendered one.
  bool frameDue = true;
  /// Whether the window system showed the window since it last got a frame.
  bool presentDue = false;
  /// Whether a frame event is on its way.
  bool framePosted = false;
  /// The size (device pixels) of the frame VTK last rendered; empty before the first.
  QSize frameSize;
  std::uint64_t renders = 0;
  /// The camera's modification time when VTK last rendered a frame (vtkCamera::GetMTime).
  vtkMTimeType cameraDrawn = 0;

  QSize deviceSize() const {
    const double ratio = widget.devicePixelRatioF();
    return QSize(static_cast<int>(widget.width() * ratio + 0.5), static_cast<int>(widget.height() * ratio + 0.5));
  }

  void postFrame() {
    if (framePosted) return;
    framePosted = true;
    // As QWidget::update does: low priority, after the input events already queued.
    QCoreApplication::postEvent(&widget, new QEvent(kFrameEvent), Qt::LowEventPriority);
  }

  /// The OpenGL context on the native window, VTK set up in it; false if none can be made.
  bool ensureContext() {
    if (context) return true;
    if (contextFailed) return false;
    surface->create();
    auto made = std::make_unique<QOpenGLContext>();
    made->setFormat(surface->requestedFormat());
    if (!made->create() || !made->makeCurrent(surface)) {
      contextFailed = true;
      qWarning("VtkViewWidget: no OpenGL context for the 3D view");
      return false;
    }
    context = std::move(made);
    window->SetOwnContext(false);
    window->SetFrameBlitModeToBlitToCurrent();  // to the window's framebuffer, the one bound
    window->SetIsCurrent(true);
    window->OpenGLInitContext();
    interactor->Initialize();
    return true;
  }

  /// One pass: the owner brings the scene up to date (aboutToRender), VTK renders if a frame is
  /// due or the size changed, and the window shows the new frame (or the last one again, if it
  /// was exposed since). False if there is no context.
  bool drawFrame() {
    framePosted = false;
    emit widget.aboutToRender();
    if (!ensureContext()) return false;
    context->makeCurrent(surface);
    const QSize size = deviceSize();
    if (window->GetSize()[0] != size.width() || window->GetSize()[1] != size.height()) {
      window->SetSize(size.width(), size.height());
      interactor->UpdateSize(size.width(), size.height());
      interactor->InvokeEvent(vtkCommand::ConfigureEvent, nullptr);
    }
    const bool exposed = surface->isExposed();
    if (frameDue || frameSize != size) {
      frameDue = false;  // a request while VTK renders asks for the next frame
      frameSize = size;
      ++renders;
      window->SetReadyForRendering(true);
      window->Render();  // and blits the frame to the window's back buffer
      window->SetReadyForRendering(false);
      cameraDrawn = renderer->GetActiveCamera()->GetMTime();
      presentDue = !exposed;
    } else if (presentDue && exposed) {
      window->BlitDisplayFramebuffer();  // VTK keeps its last frame in its display framebuffer
      presentDue = false;
    } else {
      return true;
    }
    if (exposed) {
      context->swapBuffers(surface);
      emit widget.frameSwapped();
    }
    return true;
  }

  /// VTK's last frame, read from its display framebuffer (the context current), opaque.
  QImage lastFrame() {
    const int w = window->GetSize()[0];
    const int h = window->GetSize()[1];
    if (w <= 0 || h <= 0) return {};
    QImage image(w, h, QImage::Format_RGB888);
    window->SetReadyForRendering(true);
    unsigned char* pixels = window->GetPixelData(0, 0, w - 1, h - 1, 1, 0);
    window->SetReadyForRendering(false);
    // OpenGL's rows go bottom up.
    for (int y = 0; y < h; ++y) std::memcpy(image.scanLine(h - 1 - y), pixels + static_cast<std::size_t>(y) * w * 3, w * 3);
    delete[] pixels;
    return image.convertToFormat(QImage::Format_RGB32);
  }
};

VtkViewWidget::VtkViewWidget(QWidget* parent) : QWidget(parent), impl_(std::make_unique<Impl>(*this)) {
  setFocusPolicy(Qt::StrongFocus);
  setMouseTracking(true);  // VTK styles hover-highlight on plain moves
  setAttribute(Qt::WA_OpaquePaintEvent);  // the native window covers the widget

  auto& d = *impl_;
  d.surface = new ViewSurface([this] {
    impl_->presentDue = true;
    if (isVisible()) impl_->postFrame();
  });
  d.container = QWidget::createWindowContainer(d.surface, this);
  // Input goes to this widget: the container lets mouse events through, and never takes focus
  // (it would hand it to the native window).
  d.container->setAttribute(Qt::WA_TransparentForMouseEvents);
  d.container->setFocusPolicy(Qt::NoFocus);
  d.container->setGeometry(rect());

  d.window->AddRenderer(d.renderer);
  d.window->SetMultiSamples(0);
  d.window->SetReadyForRendering(false);
  d.interactor->SetRenderWindow(d.window);
  d.interactor->SetInteractorStyle(d.style);
  // The interactor asks for renders while handling events; route them through the event loop.
  d.interactor->EnableRenderOff();

  d.makeCurrent->SetClientData(&d);
  d.makeCurrent->SetCallback([](vtkObject*, unsigned long, void* impl, void*) {
    auto& self = *static_cast<Impl*>(impl);
    if (self.context && QOpenGLContext::currentContext() != self.context.get()) self.context->makeCurrent(self.surface);
  });
  d.window->AddObserver(vtkCommand::WindowMakeCurrentEvent, d.makeCurrent);

  d.isCurrent->SetClientData(&d);
  d.isCurrent->SetCallback([](vtkObject*, unsigned long, void* impl, void* callData) {
    auto& self = *static_cast<Impl*>(impl);
    *static_cast<bool*>(callData) = self.context && QOpenGLContext::currentContext() == self.context.get();
  });
  d.window->AddObserver(vtkCommand::WindowIsCurrentEvent, d.isCurrent);

  d.renderRequest->SetClientData(this);
  d.renderRequest->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    // The interactor style asks for a frame when it moved the camera, and again when its gesture
    // ends (a right or middle click with no motion too): only a camera moved since the last frame
    // draws something new.
    auto* widget = static_cast<VtkViewWidget*>(self);
    if (widget->impl_->renderer->GetActiveCamera()->GetMTime() != widget->impl_->cameraDrawn) widget->requestRender();
  });
  d.interactor->AddObserver(vtkCommand::RenderEvent, d.renderRequest);
}

VtkViewWidget::~VtkViewWidget() {
  // Release VTK's GPU resources while our context still exists.
  auto& d = *impl_;
  if (d.context && d.context->makeCurrent(d.surface)) {
    d.window->Finalize();
    d.context->doneCurrent();
  }
  d.window->RemoveObserver(d.makeCurrent);
  d.window->RemoveObserver(d.isCurrent);
}

QSurfaceFormat VtkViewWidget::defaultFormat() {
  QSurfaceFormat format;
  format.setRenderableType(QSurfaceFormat::OpenGL);
  format.setVersion(3, 2);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setSwapBehavior(QSurfaceFormat::DoubleBuffer);
  format.setRedBufferSize(8);
  format.setGreenBufferSize(8);
  format.setBlueBufferSize(8);
  format.setAlphaBufferSize(8);
  format.setDepthBufferSize(24);
  format.setStencilBufferSize(8);
  format.setSamples(0);
  return format;
}

vtkGenericOpenGLRenderWindow* VtkViewWidget::renderWindow() const { return impl_->window; }
vtkRenderWindowInteractor* VtkViewWidget::interactor() const { return impl_->interactor; }
vtkRenderer* VtkViewWidget::renderer() const { return impl_->renderer; }

void VtkViewWidget::requestRender() {
  impl_->frameDue = true;
  if (isVisible()) impl_->postFrame();  // a hidden view draws when it is shown
}

std::uint64_t VtkViewWidget::renders() const { return impl_->renders; }

QEvent::Type VtkViewWidget::frameEventType() { return kFrameEvent; }

QImage VtkViewWidget::grabFramebuffer() {
  if (!impl_->drawFrame()) return {};
  return impl_->lastFrame();
}

bool VtkViewWidget::event(QEvent* event) {
  if (event->type() == kFrameEvent) {
    if (impl_->framePosted && isVisible()) impl_->drawFrame();
    impl_->framePosted = false;
    return true;
  }
  if (event->type() == QEvent::Show && (impl_->frameDue || impl_->presentDue)) impl_->postFrame();
  return QWidget::event(event);
}

void VtkViewWidget::resizeEvent(QResizeEvent* event) {
  impl_->container->setGeometry(rect());
  if (isVisible() && impl_->deviceSize() != impl_->frameSize) impl_->postFrame();
  QWidget::resizeEvent(event);
}

void VtkViewWidget::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  // On the screen the native window shows the frame; a grab of the window gets it painted.
  if (!paintsAnImage(*this, painter)) return;
  const QImage frame = grabFramebuffer();
  if (frame.isNull()) painter.fillRect(rect(), Qt::black);
  else painter.drawImage(rect(), frame);
}

namespace {

void setMouseInfo(vtkRenderWindowInteractor* interactor, const QWidget* widget, const QPointF& position,
                  Qt::KeyboardModifiers modifiers, int repeatCount) {
  const double ratio = widget->devicePixelRatioF();
  interactor->SetEventInformationFlipY(static_cast<int>(position.x() * ratio + 0.5),
                                       static_cast<int>(position.y() * ratio + 0.5),
                                       (modifiers & Qt::ControlModifier) ? 1 : 0,
                                       (modifiers & Qt::ShiftModifier) ? 1 : 0, 0, repeatCount);
  interactor->SetAltKey((modifiers & Qt::AltModifier) ? 1 : 0);
}

unsigned long pressEventFor(Qt::MouseButton button) {
  switch (button) {
    case Qt::LeftButton: return vtkCommand::LeftButtonPressEvent;
    case Qt::RightButton: return vtkCommand::RightButtonPressEvent;
    case Qt::MiddleButton: return vtkCommand::MiddleButtonPressEvent;
    default: return vtkCommand::NoEvent;
  }
}

unsigned long releaseEventFor(Qt::MouseButton button) {
  switch (button) {
    case Qt::LeftButton: return vtkCommand::LeftButtonReleaseEvent;
    case Qt::RightButton: return vtkCommand::RightButtonReleaseEvent;
    case Qt::MiddleButton: return vtkCommand::MiddleButtonReleaseEvent;
    default: return vtkCommand::NoEvent;
  }
}

}  // namespace

void VtkViewWidget::mousePressEvent(QMouseEvent* event) {
  setMouseInfo(impl_->interactor, this, event->position(), event->modifiers(), 0);
  if (auto id = pressEventFor(event->button()); id != vtkCommand::NoEvent) impl_->interactor->InvokeEvent(id);
  event->accept();
}

void VtkViewWidget::mouseDoubleClickEvent(QMouseEvent* event) {
  // VTK reports a double click as a press whose repeat count is 1.
  setMouseInfo(impl_->interactor, this, event->position(), event->modifiers(), 1);
  if (auto id = pressEventFor(event->button()); id != vtkCommand::NoEvent) impl_->interactor->InvokeEvent(id);
  event->accept();
}

void VtkViewWidget::mouseMoveEvent(QMouseEvent* event) {
  setMouseInfo(impl_->interactor, this, event->position(), event->modifiers(), 0);
  impl_->interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
  event->accept();
}

void VtkViewWidget::mouseReleaseEvent(QMouseEvent* event) {
  setMouseInfo(impl_->interactor, this, event->position(), event->modifiers(), 0);
  if (auto id = releaseEventFor(event->button()); id != vtkCommand::NoEvent) impl_->interactor->InvokeEvent(id);
  event->accept();
}

void VtkViewWidget::wheelEvent(QWheelEvent* event) {
  setMouseInfo(impl_->interactor, this, event->position(), event->modifiers(), 0);
  const QPoint delta = event->angleDelta();
  if (delta.y() > 0) impl_->interactor->InvokeEvent(vtkCommand::MouseWheelForwardEvent);
  if (delta.y() < 0) impl_->interactor->InvokeEvent(vtkCommand::MouseWheelBackwardEvent);
  if (delta.x() > 0) impl_->interactor->InvokeEvent(vtkCommand::MouseWheelLeftEvent);
  if (delta.x() < 0) impl_->interactor->InvokeEvent(vtkCommand::MouseWheelRightEvent);
  event->accept();
}

namespace {

void setKeyInfo(vtkRenderWindowInteractor* interactor, const QKeyEvent* event) {
  const QString text = event->text();
  const char keyCode = (text.size() == 1 && text[0].unicode() < 128) ? static_cast<char>(text[0].unicode()) : 0;
  const char* symbol = keySymbol(event->key());
  const QByteArray fallback = text.toLatin1();
  const Qt::KeyboardModifiers modifiers = event->modifiers();
  interactor->SetKeyEventInformation((modifiers & Qt::ControlModifier) ? 1 : 0,
                                     (modifiers & Qt::ShiftModifier) ? 1 : 0, keyCode,
                                     event->isAutoRepeat() ? 1 : 0,
                                     symbol != nullptr ? symbol : fallback.constData());
  interactor->SetAltKey((modifiers & Qt::AltModifier) ? 1 : 0);
}

}  // namespace

void VtkViewWidget::keyPressEvent(QKeyEvent* event) {
  setKeyInfo(impl_->interactor, event);
  impl_->interactor->InvokeEvent(vtkCommand::KeyPressEvent);
  // Interactor styles act on CharEvent ('r' resets the camera, 'w' wireframe, ...).
  impl_->interactor->InvokeEvent(vtkCommand::CharEvent);
  event->accept();
}

void VtkViewWidget::keyReleaseEvent(QKeyEvent* event) {
  setKeyInfo(impl_->interactor, event);
  impl_->interactor->InvokeEvent(vtkCommand::KeyReleaseEvent);
  event->accept();
}

void VtkViewWidget::enterEvent(QEnterEvent* event) {
  setMouseInfo(impl_->interactor, this, event->position(), event->modifiers(), 0);
  impl_->interactor->InvokeEvent(vtkCommand::EnterEvent);
  event->accept();
}

void VtkViewWidget::leaveEvent(QEvent* event) {
  impl_->interactor->InvokeEvent(vtkCommand::LeaveEvent);
  event->accept();
}

}  // namespace ffdkit::app
